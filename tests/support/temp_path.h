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

// A temporary file removed when the test ends, also when an assertion ends
// it early.
struct TempFile {
  std::filesystem::path path;
  explicit TempFile(const std::string& name) : path(UniqueTempPath(name)) {}
  ~TempFile() { std::filesystem::remove(path); }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
};

}  // namespace beamid::testing
