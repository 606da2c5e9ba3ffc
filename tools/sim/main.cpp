#include <iostream>

#include "tools/sim/sim.h"

int main(int argc, char** argv) {
  return openplx::sim::run_sim(std::vector<std::string>(argv + 1, argv + argc), std::cout, std::cerr);
}
