// Test support: a fresh folder for the files one test writes. Its name carries the test's name, the
// process id and a counter, so tests never share files, whatever their order and however many run at once
// (ctest -j, two builds on one machine). The folder and all in it is removed when the object goes away.
#pragma once

#include <filesystem>

namespace openplx::testing {

class ScratchDir {
 public:
  ScratchDir();
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::filesystem::path& relative) const { return path_ / relative; }

 private:
  std::filesystem::path path_;
};

}  // namespace openplx::testing
