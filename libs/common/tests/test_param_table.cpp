// ParamTable: one table of fields loads, saves and lists a section; the saved text loads back to the
// same values, degrees are saved exactly, and bad values are errors naming the section and the key.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"

using namespace roadslam;

namespace {

enum class Shape { Round, Square, Flat };
const NameTable<Shape>& shapeNames() {
  static const NameTable<Shape> t{{Shape::Round, "round"}, {Shape::Square, "square"}, {Shape::Flat, "flat"}};
  return t;
}

struct Demo {
  double range_m = 12.5;                  ///< [m]
  double angle_rad = 10 * unit::kDeg;     ///< [rad], ini in degrees
  double period_s = 0.25;                 ///< [s], ini in milliseconds
  int count = 7;
  std::uint16_t port = 2368;
  bool on = true;
  std::string name = "demo";
  Shape shape = Shape::Square;
  double old_name_m = 1.5;                ///< [m], also read under the alias "oldN"

  void fields(ParamTable& t) {
    t.num("range_m", range_m);
    t.angle("angle_deg", angle_rad);
    t.scaled("period_ms", period_s, unit::kMs);
    t.num("count", count);
    t.num("port", port);
    t.flag("on", on);
    t.text("name", name);
    t.choice("shape", shape, shapeNames());
    t.numOrAlias("new_name_m", "oldN", old_name_m);
  }
};

std::string saved(const Demo& d) {
  mrpt::config::CConfigFileMemory out;
  saveFields(d, out, "demo");
  return out.getContent();
}

std::string errorOf(const std::string& ini) {
  Demo d;
  try {
    loadFields(d, mrpt::config::CConfigFileMemory(ini), "demo");
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ParamTable, SavedTextLoadsBackToTheSameValues) {
  Demo a;
  a.range_m = 3.25;
  a.angle_rad = 2.5 * unit::kDeg;
  a.count = -4;
  a.port = 10110;
  a.on = false;
  a.name = "other";
  a.shape = Shape::Flat;
  const std::string text = saved(a);
  Demo b;
  loadFields(b, mrpt::config::CConfigFileMemory(text), "demo");
  EXPECT_EQ(b.range_m, a.range_m);
  EXPECT_EQ(b.angle_rad, a.angle_rad);
  EXPECT_EQ(b.period_s, a.period_s);
  EXPECT_EQ(b.count, -4);
  EXPECT_EQ(b.port, 10110);
  EXPECT_FALSE(b.on);
  EXPECT_EQ(b.name, "other");
  EXPECT_EQ(b.shape, Shape::Flat);
  EXPECT_EQ(saved(b), text);
}

TEST(ParamTable, AnEmptySectionKeepsTheDefaults) {
  Demo d;
  loadFields(d, mrpt::config::CConfigFileMemory(), "demo");
  EXPECT_EQ(saved(d), saved(Demo{}));
  EXPECT_EQ(d.range_m, 12.5);
  EXPECT_EQ(d.shape, Shape::Square);
}

TEST(ParamTable, DegreesAreSavedExactlyAndLoadedAsRadians) {
  const std::string text = saved(Demo{});
  EXPECT_NE(text.find("angle_deg = 10.000000"), std::string::npos) << text;
  EXPECT_NE(text.find("period_ms = 250.000000"), std::string::npos) << text;
  Demo d;
  loadFields(d, mrpt::config::CConfigFileMemory(std::string("[demo]\nangle_deg = 90\n")), "demo");
  EXPECT_EQ(d.angle_rad, 90 * unit::kDeg);
}

TEST(ParamTable, KeysComeInTableOrderWithAliases) {
  const auto keys = fieldKeys<Demo>();
  ASSERT_EQ(keys.size(), 10u);
  EXPECT_EQ(keys.front(), "range_m");
  EXPECT_EQ(keys[1], "angle_deg");
  EXPECT_EQ(keys[8], "new_name_m");
  EXPECT_EQ(keys[9], "oldN");
}

TEST(ParamTable, UnknownNameListsTheValidOnes) {
  const std::string e = errorOf("[demo]\nshape = oval\n");
  EXPECT_NE(e.find("[demo] shape = 'oval': expected round, square or flat"), std::string::npos) << e;
}

TEST(ParamTable, NonNumericValueNamesSectionAndKey) {
  EXPECT_NE(errorOf("[demo]\nrange_m = far\n").find("[demo] range_m = 'far' is not a number"), std::string::npos);
  EXPECT_NE(errorOf("[demo]\ncount = 2.5\n").find("[demo] count = '2.5' is not an integer"), std::string::npos);
  EXPECT_NE(errorOf("[demo]\non = maybe\n").find("[demo] on = 'maybe' is not a boolean"), std::string::npos);
}

TEST(ParamTable, AliasIsReadAndBothIsAnError) {
  Demo d;
  loadFields(d, mrpt::config::CConfigFileMemory(std::string("[demo]\noldN = 4\n")), "demo");
  EXPECT_EQ(d.old_name_m, 4);
  EXPECT_NE(saved(d).find("new_name_m = 4.000000"), std::string::npos);
  const std::string e = errorOf("[demo]\noldN = 4\nnew_name_m = 5\n");
  EXPECT_NE(e.find("[demo] oldN = 4: alias of 'new_name_m', which the section sets too: set only one"),
            std::string::npos) << e;
}

TEST(ParamTable, BothNameAndAliasNamesTheFileAndBothLines) {
  const auto path = std::filesystem::temp_directory_path() / ("roadslam-alias-" + std::to_string(::getpid()) + ".ini");
  std::ofstream(path) << "; demo\n[demo]\nnew_name_m = 5\n\noldN = 4\n";
  std::string e;
  try {
    Demo d;
    loadFields(d, *loadIniFile(path.string()), "demo");
  } catch (const std::exception& x) {
    e = x.what();
  }
  std::filesystem::remove(path);
  EXPECT_EQ(e, path.string() + ":5: [demo] oldN = 4: alias of 'new_name_m', which line 3 sets too: set only one");
}

TEST(ParamTable, A64BitCountIsSavedExactly) {
  struct Clock {
    std::int64_t start_epoch_s = 1700000000123;
    void fields(ParamTable& t) { t.num("start_epoch_s", start_epoch_s); }
  } c;
  mrpt::config::CConfigFileMemory out;
  saveFields(c, out, "clock");
  EXPECT_NE(out.getContent().find("start_epoch_s = 1700000000123"), std::string::npos) << out.getContent();
  Clock d;
  d.start_epoch_s = 0;
  loadFields(d, mrpt::config::CConfigFileMemory(out.getContent()), "clock");
  EXPECT_EQ(d.start_epoch_s, 1700000000123);
}

TEST(ParamTable, NameTableGoesBothWays) {
  EXPECT_EQ(nameOf(shapeNames(), Shape::Round), "round");
  EXPECT_EQ(valueOf(shapeNames(), "flat", "shape"), Shape::Flat);
  EXPECT_THROW(valueOf(shapeNames(), "Flat", "shape"), std::invalid_argument);
  EXPECT_EQ(listOfNames({"a"}), "a");
  EXPECT_EQ(listOfNames({"a", "b"}), "a or b");
}
