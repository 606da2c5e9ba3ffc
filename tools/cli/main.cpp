#include <malloc.h>

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "tools/cli/cli.h"

int main(int argc, char** argv) {
  // The front end evaluates on a thread with a large stack. glibc would give that thread an arena of its
  // own that grows a page range at a time, one mprotect call each (about 900 for a 16-link robot, a third
  // of the run): one arena, grown through brk with a generous pad, avoids that.
  mallopt(M_ARENA_MAX, 1);
  mallopt(M_TOP_PAD, 16 << 20);
  std::ios::sync_with_stdio(false);
  std::vector<std::string> args(argv + 1, argv + argc);
  // Freeing a large model object by object costs as much as a pass; the exit frees it at once.
  openplx::cli::end_process_after_run();
  openplx::cli::show_progress_on_terminal();
  const int status = openplx::cli::run(args, std::cout, std::cerr);
  std::cout.flush();
  std::cerr.flush();
  std::_Exit(status);
}
