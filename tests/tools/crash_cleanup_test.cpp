// --check's temporary files are removed even when a crash inside MuJoCo ends the process: a child process
// holds a CrashCleanup over a file and a folder, then dies of a signal; the files must be gone, and the
// signal must still end it (the handler it had runs after the cleanup).
#include "tools/cli/crash_cleanup.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "tests/support/scratch_dir.h"

namespace {

namespace fs = std::filesystem;

// Runs `body` in a child; returns its wait status.
template <typename F>
int in_child(F body) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    body();
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

TEST(CrashCleanup, AFatalSignalRemovesTheFilesAndStillEndsTheProcess) {
  const openplx::testing::ScratchDir dir;
  for (int signal : {SIGSEGV, SIGABRT, SIGBUS}) {
    SCOPED_TRACE(signal);
    const fs::path folder = dir / "check.meshes", mesh = folder / "m.stl", xml = dir / "check.xml";
    fs::create_directory(folder);
    std::ofstream(mesh) << "x";
    std::ofstream(xml) << "<mujoco/>";
    const int status = in_child([&] {
      ::signal(signal, SIG_DFL);  // as a plain process starts; the test runner's handlers left aside
      const openplx::cli::CrashCleanup cleanup({xml, folder, mesh});
      ::raise(signal);
    });
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal) << status;
    EXPECT_FALSE(fs::exists(mesh));
    EXPECT_FALSE(fs::exists(folder));
    EXPECT_FALSE(fs::exists(xml));
  }
}

// Once the check is over, a crash is none of its business: the files stay (they are the run's, by then).
TEST(CrashCleanup, AfterItEndsTheHandlersAreAsBefore) {
  const openplx::testing::ScratchDir dir;
  const fs::path kept = dir / "kept.xml";
  std::ofstream(kept) << "<mujoco/>";
  const int status = in_child([&] {
    ::signal(SIGABRT, SIG_DFL);
    { const openplx::cli::CrashCleanup cleanup({kept}); }
    ::raise(SIGABRT);
  });
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT) << status;
  EXPECT_TRUE(fs::exists(kept));
}

}  // namespace
