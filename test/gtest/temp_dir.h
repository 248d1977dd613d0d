// Shared by the core's gtests: a temporary folder of this test process for the files a test writes (meshes,
// world files), so two runs at once (several worktrees on one machine) never read each other's half-written
// files under the same name in /tmp.
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace unexmin {
namespace test {

/// <gtest TempDir>/unexmin_test_<pid>/, created on first use and removed with its files when the process
/// exits; ends with '/'.
inline const std::string& testTempDir() {
  struct Folder {
    std::string path = ::testing::TempDir() + "unexmin_test_" + std::to_string(::getpid()) + "/";
    Folder() { std::filesystem::create_directories(path); }
    ~Folder() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Folder folder;
  return folder.path;
}

}  // namespace test
}  // namespace unexmin
