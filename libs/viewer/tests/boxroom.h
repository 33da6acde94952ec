#pragma once
/// \file boxroom.h
/// Test support of viewer_tests: one temporary folder per test process, and the bundled box room
/// (6 sweeps of a static VLP-16) converted to a rawlog once in it.

#include <filesystem>
#include <string>

namespace roadslam::viewer::test {

std::filesystem::path tempDir();
const std::string& boxroomRawlog();

}  // namespace roadslam::viewer::test
