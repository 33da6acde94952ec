// Seeds for the candump fuzz driver: one line of every frame type can-utils writes.
#include <string>
#include <vector>

std::vector<std::string> fuzzSeeds() {
  return {"(1436509052.249713) can0 123#DEADBEEF\n"
          "(1436509052.249714) can0 12345678#0011223344556677\n"
          "(1436509052.249715) vcan1 321#R\n(1436509052.249716) can0 321#R7\n"
          "(1436509052.249717) can0 123##2001122334455667788990011\n"
          "(1436509052.249718) can0 20000080#0000000000000000\n"
          "(1436509052.249719) can0 123#1122334455667788_C\n"
          "(1436509052.249720) can0 7FF#11.22.33 R\n# comment\n\n"};
}

std::vector<std::string> fuzzTokens() {
  return {"(", ")", ".", "#", "##", "R", "_", " ", "\n", "\r", "can0", "FFFFFFFF", "7FF", "800", "0000000000"};
}
