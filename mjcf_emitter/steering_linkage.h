// The planar linkages of kinematic steering (Vehicles.Steering.Kinematic), solved exactly and fitted with the
// quartics MuJoCo's joint equalities take. The geometry is ours, UNCONFIRMED against AGX, which documents
// only the parameters' meanings.
//
// The plane is the one across the steering axis: x forward, y to the left, the kingpins at (0, ±track/2).
// Wheel angles are positive about the steering axis pointing up (a left turn). Each knuckle arm, of
// knuckle_length, points rearward and tilts inward by |knuckle_angle| - 90° (knuckle_angle is read from the
// axle line pointing outward).
//  - Ackermann: one tie rod joins the two arm ends, with the length it has straight ahead; the input is the
//    left wheel's angle.
//  - BellCrank: each tie rod leaves its arm end inward at initial_angle_right_tie_rod to the axle line
//    (positive: sloping forward) and both meet on the centre line at the end of a lever of
//    steering_column_distance, pivoted on the centre line ahead of that end (the lever points rearward).
//    The input θ is the steering-wheel angle; the lever turns gear·θ about the up axis, so a positive input
//    swings its end to the right, pulls the arm ends (behind the kingpins) right and turns the wheels left.
//  - RackAndPinion: the tie rods start at the same angle but end at the two ends of a rack of rack_length,
//    centred on the centre line; the pinion turns gear·θ and, with steering_column_distance as its arm,
//    moves the rack to the right by steering_column_distance·gear·θ.
// Each wheel's angle closes its own tie-rod loop (two circles meet), continuing from the previous solution.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace openplx::mjcf {

struct SteeringGeometry {
  double track = 0;            // m, between the kingpins
  double knuckle_length = 0;   // m
  double knuckle_angle = 0;    // rad
  double tie_rod_angle = 0;    // rad (BellCrank, RackAndPinion)
  double column_distance = 0;  // m: the lever's (BellCrank) or pinion arm's (RackAndPinion) length
  double rack_length = 0;      // m (RackAndPinion; 0 for BellCrank: both tie rods meet at one point)
  double gear = 1;             // steering arm rotation per input rotation
};

// y = c[0] + c[1] x + ... + c[4] x^4, least-squares fitted through zero (c[0] = 0: straight ahead is exact).
struct QuarticFit {
  std::array<double, 5> c{};
  double max_error = 0;  // over the samples fitted
};

struct SteeringSample {
  double input = 0, left = 0, right = 0;  // rad
};

struct SteeringLinkage {
  std::string problem;                  // not empty: the geometry cannot steer, and why
  std::vector<SteeringSample> samples;  // straight ahead, then left turns outward, then right turns
  double low = 0, high = 0;             // the inputs covered
  bool closes = true;                   // false: the loop broke before both wheels reached the range's edge
  QuarticFit input_to_left;             // left = p(input) (the identity for Ackermann)
  QuarticFit linkage;                   // right = q(left)
};

// The steering range: both wheels within this angle of straight ahead (about 34°, a road vehicle's lock).
inline constexpr double kSteeringRange = 0.6;

SteeringLinkage ackermann_linkage(const SteeringGeometry& g);
SteeringLinkage bell_crank_linkage(const SteeringGeometry& g);
SteeringLinkage rack_and_pinion_linkage(const SteeringGeometry& g);

}  // namespace openplx::mjcf
