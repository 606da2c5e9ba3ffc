// Test support: the OpenPLX text of a car (vehicle_assembly_test, owned_rows_test, bare_mjcf_rows_test).
#pragma once

#include <string>

namespace openplx::testing {

struct Car {
  bool static_chassis = false;
  bool elastic_wheels = false;
  bool steered = false;        // front suspensions with Properties.Steering and an Ackermann steering
  double chassis_width = 0.8;  // m; 1.6 puts the wheels half inside the chassis box (wheel wells)
  bool steel = false;          // chassis and rims of one material, with a SurfaceContact model for it
};

// Four wheels on spring-damper suspensions. The mounts are the vehicle's own connectors, redirected to the
// chassis (the front ones in 0.31's trait spelling, the rear ones as RedirectedMateConnector); the chassis
// has no placement of its own. Rear wheels driven by `speed` (rad/s).
std::string car(const Car& c);

// The car of AGXUnity's elastic_wheel steering test: elastic wheels, Ackermann-steered front.
Car elastic_steered_car();

}  // namespace openplx::testing
