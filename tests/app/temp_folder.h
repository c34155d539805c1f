#pragma once
// A fresh folder for one test, named after the process and the test (so tests that run in
// parallel never share one), removed when the test ends.
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

namespace testing_app {

class TempFolder {
 public:
  TempFolder() {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    path = std::filesystem::temp_directory_path() / ("sandbox-test-" + std::to_string(::getpid()) + "-" +
                                                     test->test_suite_name() + "-" + test->name());
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempFolder() { std::filesystem::remove_all(path); }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;

  /// Creates a small file of that name in the folder.
  void touch(const std::string& name) const { std::ofstream(path / name) << "x"; }

  std::filesystem::path path;
};

}  // namespace testing_app
