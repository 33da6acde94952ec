#pragma once
// Scratch folders for the run-folder tests.
#include <filesystem>
#include <fstream>
#include <string>

namespace roadslam::runfolder::test {

inline std::string freshDir(const std::string& name) {
  const std::string d = std::string(ROADSLAM_BINARY_DIR) + "/test-out/runfolder/" + name;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

inline void writeText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

inline std::string readText(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The message of what \p f throws ("" when it does not).
template <class F>
std::string thrown(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace roadslam::runfolder::test
