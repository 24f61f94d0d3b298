// A temporary path of this test process alone: ctest runs every test in its
// own process, in parallel, so a fixed name in /tmp would be shared.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace beamid::testing {

inline std::filesystem::path UniqueTempPath(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string test = info ? std::string(info->test_suite_name()) + "." + info->name() : "suite";
  // A parameterised test's names hold '/' ("Encodings/UffRecordingTest"),
  // which would nest the path in a folder that no TearDown removes.
  std::replace(test.begin(), test.end(), '/', '_');
  return std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()) + "_" + test);
}

}  // namespace beamid::testing
