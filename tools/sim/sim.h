// `openplx-sim`, callable in-process for tests. Exit status: 0 success, 1 model or signal errors or a run
// MuJoCo had to reset (SimulationError, printed; no values printed then), 2 usage (also --time beyond 1e9
// steps, --timestep outside [1e-6, 1] s).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace openplx::sim {

int run_sim(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace openplx::sim
