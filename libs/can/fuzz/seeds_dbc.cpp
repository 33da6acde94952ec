// Seeds for the DBC fuzz driver: a small DBC using every supported statement.
#include <string>
#include <vector>

std::vector<std::string> fuzzSeeds() {
  return {R"(VERSION "1"
NS_ :
	CM_
BS_:
BU_: A B
VAL_TABLE_ T 1 "one" 0 "zero" ;
BO_ 100 M: 8 A
 SG_ S : 7|16@0+ (0.01,-67.67) [0|250] "km/h" B
 SG_ T : 16|12@1- (0.5,0) [-1|1] "" B
BO_ 2566844926 X: 64 B
 SG_ MUX M : 0|4@1+ (1,0) [0|15] "" A
 SG_ F m1 : 32|32@1- (1,0) [0|0] "" A
 SG_ G m2M : 8|8@1+ (1,0) [0|0] "" A
CM_ "net";
CM_ BO_ 100 "msg";
CM_ SG_ 100 S "sig \"q\"";
BA_DEF_ BO_ "Cyc" INT 0 100;
BA_DEF_DEF_ "Cyc" 10;
BA_ "Cyc" BO_ 100 20;
VAL_ 100 S 1 "a" -1 "b" ;
SIG_VALTYPE_ 2566844926 F : 1;
)",
          "BO_ 1 A: 1 X\n SG_ B : 0|1@1+ (1,0) [0|1] \"\" Y\n"};
}

std::vector<std::string> fuzzTokens() {
  return {"BO_ ", " SG_ ", "CM_ ", "VAL_ ", "BA_ ", "BA_DEF_ ", "SIG_VALTYPE_ ", " M ", " m3 ", "@0-", "@1+",
          "|", ":", ";", "\"", "(", ")", "[", "]", ",", "\n", "4294967295", "-1e308", "2147483648", "64", "0"};
}
