// `openplx-sim`, callable in-process for tests. Exit status: 0 success, 1 model or signal errors, 2 usage.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace openplx::sim {

int run_sim(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace openplx::sim
