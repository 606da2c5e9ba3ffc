// Test support: a static chassis with two front wheels 1.6 m apart, each on a SingleMate suspension clear
// of the chassis box (MuJoCo lets a child touch a parent welded to the world). `spring` is each suspension's
// spring block; `steerable` gives them Vehicles.Suspensions.Properties.Steering. A steering mechanism, if
// any, is the caller's to append.
#pragma once

#include <string>

namespace openplx::testing {

std::string front_axle(const std::string& spring, bool steerable);

}  // namespace openplx::testing
