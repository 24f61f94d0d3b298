// A temporary path of this test process alone: ctest runs every test in its
// own process, in parallel, so a fixed name in /tmp would be shared.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace beamid::testing {

inline std::filesystem::path UniqueTempPath(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string test = info ? std::string(info->test_suite_name()) + "." + info->name() : "suite";
  return std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()) + "_" + test);
}

}  // namespace beamid::testing
