#include "tests/support/scratch_dir.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <string>
#include <system_error>

namespace openplx::testing {

ScratchDir::ScratchDir() {
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

ScratchDir::~ScratchDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

}  // namespace openplx::testing
