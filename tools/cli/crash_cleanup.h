// Files a run must not leave behind even when the process dies of a signal (a crash inside MuJoCo while
// --check loads or steps the model): while a CrashCleanup lives, a fatal signal first removes its paths
// (files, then folders, in reverse order of listing), then goes on to whatever handled it before (the default
// action, or a sanitizer's report).
#pragma once

#include <filesystem>
#include <vector>

namespace openplx::cli {

class CrashCleanup {
 public:
  // Paths in the order they were made (a folder before its files). One CrashCleanup at a time per process.
  explicit CrashCleanup(const std::vector<std::filesystem::path>& paths);
  ~CrashCleanup();
  CrashCleanup(const CrashCleanup&) = delete;
  CrashCleanup& operator=(const CrashCleanup&) = delete;
};

}  // namespace openplx::cli
