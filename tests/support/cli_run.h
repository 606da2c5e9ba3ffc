// The converter's command line run in process (openplx::cli::run), its exit status and both streams kept.
// Header-only: only the test programs that link the command line (openplx_cli) include it.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "tools/cli/cli.h"

namespace openplx::testing {

struct Conversion {
  int status = -1;
  std::string out, errors;
};

inline Conversion cli(const std::vector<std::string>& args) {
  std::ostringstream out, errors;
  Conversion r;
  r.status = openplx::cli::run(args, out, errors);
  r.out = out.str();
  r.errors = errors.str();
  return r;
}

}  // namespace openplx::testing
