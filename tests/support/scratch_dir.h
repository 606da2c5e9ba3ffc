// Test support: a fresh folder for the files one test writes. Its name carries the test's name, the
// process id and a counter, so tests never share files, whatever their order and however many run at once
// (ctest -j, two builds on one machine). The folder and all in it is removed when the object goes away.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace openplx::testing {

class ScratchDir {
 public:
  ScratchDir() {
    static std::atomic<unsigned> counter{0};
    std::string name = "openplx";
    if (const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info()) {
      name += std::string("_") + info->test_suite_name() + "_" + info->name();
    }
    // Parameterised tests have '/' in their names; long names would pass the file system's limit.
    for (char& c : name) {
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
    }
    name.resize(std::min<size_t>(name.size(), 120));
    name += "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + "_XXXXXX";
    std::string pattern = (std::filesystem::temp_directory_path() / name).string();
    // mkdtemp creates the folder only if it did not exist: a stale one from a crashed run is never reused.
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw std::system_error(errno, std::generic_category(), "cannot create a scratch folder " + pattern);
    }
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::filesystem::path& relative) const { return path_ / relative; }

 private:
  std::filesystem::path path_;
};

}  // namespace openplx::testing
