// Running a program as a child with a time limit and its output captured: the survey gives each URDF (and
// our converter) its own process, so a crash or a hang in either importer costs one file.
#pragma once

#include <string>
#include <vector>

namespace openplx::urdf_survey {

struct ChildResult {
  std::string output;  // standard output and standard error, interleaved
  int exit_code = -1;  // when it exited by itself
  int signal = 0;      // when a signal ended it (timeouts end it with SIGKILL)
  bool timed_out = false;
};

// Runs `argv` in a process group of its own, killing the whole group after `timeout_seconds`.
ChildResult run_child(const std::vector<std::string>& argv, double timeout_seconds);

}  // namespace openplx::urdf_survey
