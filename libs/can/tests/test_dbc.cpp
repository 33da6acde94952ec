// DBC parser/writer on a synthetic database exercising every supported statement, round trip, and
// errors that name line and column.
#include <roadslam/can/dbc.h>

#include <gtest/gtest.h>

using namespace roadslam::can;

namespace {
const char* kDbc = R"(VERSION "1.2"

NS_ :
	CM_
	BA_DEF_
	SIG_VALTYPE_

BS_:

BU_: ECU1 ECU2 _4WD

VAL_TABLE_ Gears 3 "D" 2 "N" 1 "R" 0 "P" ;

BO_ 100 WHEELS: 8 ECU1
 SG_ FL : 7|16@0+ (0.01,-67.67) [0|250] "km/h" ECU2,_4WD
 SG_ FR : 16|12@1- (0.5,0) [-1024|1023.5] "km/h" ECU2
 SG_ GEAR : 63|2@0+ (1,0) [0|3] "" Vector__XXX

BO_ 2566844926 EXT_MUX: 8 ECU2
 SG_ MUX M : 0|4@1+ (1,0) [0|15] "" ECU1
 SG_ A m0 : 8|8@1+ (1,0) [0|255] "" ECU1
 SG_ B m1 : 8|16@1- (0.1,-5) [0|0] "V" ECU1
 SG_ F m2 : 32|32@1- (1,0) [0|0] "" ECU1

CM_ "network comment";
CM_ BU_ ECU1 "the first ECU";
CM_ BO_ 100 "four wheel
speeds";
CM_ SG_ 100 FL "front left \"wheel\"";
BA_DEF_ BO_ "GenMsgCycleTime" INT 0 65535;
BA_DEF_ "BusType" STRING ;
BA_DEF_ SG_ "Kind" ENUM "a","b";
BA_DEF_DEF_ "GenMsgCycleTime" 100;
BA_ "BusType" "CAN";
BA_ "GenMsgCycleTime" BO_ 100 10;
BA_ "Kind" SG_ 100 FL 1;
VAL_ 100 GEAR 3 "D" 2 "N" 1 "R" 0 "P" ;
VAL_ 2566844926 MUX -1 "neg" 0 "zero" ;
SIG_VALTYPE_ 2566844926 F : 1;
EV_ Foo: 0 [0|1] "" 0 1 DUMMY_NODE_VECTOR0 Vector__XXX;
)";
}  // namespace

TEST(Dbc, ParsesEveryStatement) {
  const Database db = parseDbc(kDbc, "test.dbc");
  EXPECT_EQ(db.version, "1.2");
  EXPECT_EQ(db.nodes, (std::vector<std::string>{"ECU1", "ECU2", "_4WD"}));
  ASSERT_EQ(db.messages.size(), 2U);
  const Message& w = db.messages[0];
  EXPECT_EQ(w.id(), 100U);
  EXPECT_FALSE(w.extended());
  EXPECT_EQ(w.comment, "four wheel\nspeeds");
  const Signal& fl = w.signals[0];
  EXPECT_FALSE(fl.little_endian);
  EXPECT_EQ(fl.start_bit, 7U);
  EXPECT_DOUBLE_EQ(fl.offset, -67.67);
  EXPECT_EQ(fl.receivers, (std::vector<std::string>{"ECU2", "_4WD"}));
  EXPECT_EQ(fl.comment, "front left \"wheel\"");
  EXPECT_TRUE(w.signals[1].is_signed);
  EXPECT_EQ(w.signals[2].value_descriptions.at(1), "R");
  const Message& e = db.messages[1];
  EXPECT_TRUE(e.extended());
  EXPECT_EQ(e.id(), 2566844926U & 0x1FFFFFFFU);
  EXPECT_EQ(e.signals[0].mux, MuxRole::kMultiplexor);
  EXPECT_EQ(e.signals[2].mux, MuxRole::kMultiplexed);
  EXPECT_EQ(e.signals[2].mux_value, 1U);
  EXPECT_EQ(e.signals[3].value_type, ValueType::kFloat32);
  EXPECT_EQ(e.signals[0].value_descriptions.at(-1), "neg");
  EXPECT_EQ(db.comments, std::vector<std::string>{"network comment"});
  EXPECT_EQ(db.node_comments.at("ECU1"), "the first ECU");
  EXPECT_EQ(db.value_tables.at("Gears").at(3), "D");
  ASSERT_EQ(db.attribute_defs.size(), 3U);
  EXPECT_EQ(db.attribute_defs[0].type_spec, "INT 0 65535");
  EXPECT_EQ(db.attribute_defs[2].type_spec, "ENUM \"a\",\"b\"");
  ASSERT_EQ(db.attributes.size(), 3U);
  EXPECT_EQ(db.attributes[2].target, "100 FL");
  EXPECT_EQ(db.skipped_statements, 1U);
}

TEST(Dbc, WriteThenParseGivesTheSameDatabase) {
  const Database db = parseDbc(kDbc, "test.dbc");
  const std::string text = writeDbc(db);
  const Database again = parseDbc(text, "written.dbc");
  EXPECT_TRUE(again == db) << text;
  EXPECT_EQ(writeDbc(again), text);
  Database changed = again;
  changed.messages[0].signals[0].factor = 0.02;  // the comparison itself must see a change
  EXPECT_FALSE(changed == db);
}

TEST(Dbc, ErrorsNameFileLineAndColumn) {
  struct Case {
    std::string text;
    std::string where;
  };
  const Case cases[] = {
      {"VERSION \"\"\nBO_ 100 M: 8 X\n SG_ S : 7|16@2+ (1,0) [0|1] \"\" X\n", "bad.dbc:3:15:"},
      {"BO_ 100 M: 8 X\n SG_ S : 7|16@1+ (1,0 [0|1] \"\" X\n", "bad.dbc:2:23:"},
      {"BO_ 100 M: 8 X\n SG_ S 7|16@1+ (1,0) [0|1] \"\" X\n", "bad.dbc:2:8:"},
      {"BO_ 99999999999 M: 8 X\n", "bad.dbc:1:5:"},
      {" SG_ S : 7|16@1+ (1,0) [0|1] \"\" X\n", "bad.dbc:1:2:"},
      {"BO_ 100 M: 8 X\nCM_ SG_ 100 S \"x\"\n", "bad.dbc:3:1:"},
      {"BO_ 100 M: 8 X\nCM_ BO_ 100 \"unterminated;\n", "bad.dbc:2:13:"},
      {"BO_ 100 M: 8 X\n SG_ S : 0|0@1+ (1,0) [0|1] \"\" X\n", "bad.dbc:2:12:"},
      {"FOO_ bar;\n", "bad.dbc:1:1:"},
      {"BO_ 100 M: 8 X\n SG_ F : 0|16@1+ (1,0) [0|1] \"\" X\nSIG_VALTYPE_ 100 F : 1;\n", "bad.dbc:3:22:"},
  };
  for (const Case& c : cases) {
    try {
      parseDbc(c.text, "bad.dbc");
      ADD_FAILURE() << "no error for: " << c.text;
    } catch (const DbcError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(c.where, 0), 0U) << e.what() << " expected " << c.where;
    }
  }
}
