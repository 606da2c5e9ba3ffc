#include "tools/cli/crash_cleanup.h"

#include <signal.h>
#include <unistd.h>

#include <array>
#include <cstring>

namespace openplx::cli {
namespace {

constexpr size_t kMaxPaths = 64;   // a check's XML, its mesh folder and its meshes
constexpr size_t kMaxPath = 4096;  // PATH_MAX
constexpr std::array<int, 5> kFatal = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};

// Copied into static storage: the handler may only read memory and call async-signal-safe functions.
char paths[kMaxPaths][kMaxPath];
size_t path_count = 0;
struct sigaction previous[kFatal.size()];

void remove_paths(int signal) {
  for (size_t k = path_count; k-- > 0;)
    if (::unlink(paths[k]) != 0) ::rmdir(paths[k]);  // a folder (empty by now)
  path_count = 0;
  for (size_t k = 0; k < kFatal.size(); ++k)
    if (kFatal[k] == signal) ::sigaction(signal, &previous[k], nullptr);
  ::raise(signal);  // handled as before, now that the files are gone
}

}  // namespace

CrashCleanup::CrashCleanup(const std::vector<std::filesystem::path>& list) {
  path_count = 0;
  for (const std::filesystem::path& p : list) {
    const std::string text = p.string();
    if (path_count == kMaxPaths || text.size() >= kMaxPath) continue;  // left to the normal cleanup only
    std::memcpy(paths[path_count], text.c_str(), text.size() + 1);
    ++path_count;
  }
  struct sigaction action {};
  action.sa_handler = remove_paths;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_NODEFER;  // the signal raised again inside must reach the previous handler
  for (size_t k = 0; k < kFatal.size(); ++k) ::sigaction(kFatal[k], &action, &previous[k]);
}

CrashCleanup::~CrashCleanup() {
  for (size_t k = 0; k < kFatal.size(); ++k) ::sigaction(kFatal[k], &previous[k], nullptr);
  path_count = 0;
}

}  // namespace openplx::cli
