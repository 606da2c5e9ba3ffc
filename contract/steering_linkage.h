// The planar linkages of kinematic steering (Vehicles.Steering.Kinematic), solved in closed form and fitted
// with the polynomials MuJoCo's joint equality (a quartic) and the runtime (any degree) evaluate.
//
// AGX's geometry, every length a fraction of the track w (the distance between the two kingpins, i.e. the
// suspensions' chassis connectors), as AGXUnity's steering drawing builds it. The plane is the one across
// the steering axis: x forward, y to the left, kingpins at (0, ±w/2); wheel angles are positive about the
// steering axis pointing up (a left turn).
//  - Knuckle arms of b = knuckle_length·w: the right one along the outward axle direction turned by
//    knuckle_angle (φ0) about the steering axis, b (sin φ0, -cos φ0); the left one its mirror image,
//    b (sin φ0, cos φ0). AGX's defaults (φ0 about -108°..-115°) point them rearward and inward.
//  - Ackermann: one tie rod joins the two arm ends, its length the distance between them straight ahead,
//    (1 + 2 l cos φ0)·w; the input is the left wheel's angle.
//  - BellCrank and RackAndPinion: from each arm end a tie rod runs inward at initial_angle_right_tie_rod
//    (α0) to the axle line (positive: sloping forward), of length R = (1 + 2 l cos φ0 - lr)·w / (2 cos α0),
//    so that it ends at the rack's end, lr·w/2 from the centre line (lr = rack_length; 0 for BellCrank,
//    whose tie rods meet on the centre line). The steering column stands s = steering_column_distance·l·w
//    ahead of those inner ends, on the centre line; the input θ is the steering-wheel angle and the column
//    turns gear·θ (AGX's gear: UNCONFIRMED whether it multiplies or divides; here it multiplies).
//    BellCrank: the tie rods' inner ends ride on a lever of length s from the column, pointing rearward at
//    rest. RackAndPinion: the rack moves right by s·tan(gear·θ).
// Each wheel's angle closes its own loop (two circles meet), on the branch of straight ahead.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace openplx::mjcf {

enum class SteeringMechanism { Ackermann, BellCrank, RackAndPinion };

struct SteeringGeometry {
  SteeringMechanism mechanism = SteeringMechanism::Ackermann;
  double track = 0;            // m, between the kingpins
  double knuckle_length = 0;   // l: the knuckle arm over the track
  double knuckle_angle = 0;    // φ0, rad
  double tie_rod_angle = 0;    // α0, rad (BellCrank, RackAndPinion)
  double column_distance = 0;  // lc: the steering arm over the knuckle arm (BellCrank, RackAndPinion)
  double rack_length = 0;      // lr: the rack over the track (RackAndPinion)
  double gear = 1;             // column rotation per input rotation (BellCrank, RackAndPinion)
};

// The wheel angles (left, right) for `input` on the straight-ahead branch; nullopt where a loop cannot close.
std::optional<std::pair<double, double>> steering_angles(const SteeringGeometry& g, double input);

// y = c[0] + c[1] x + ... (c[0] = 0: straight ahead is exact).
struct PolynomialFit {
  std::vector<double> c;
  double max_error = 0;  // rad, over the linkage's whole input range
};

struct SteeringSample {
  double input = 0, left = 0, right = 0;  // rad
};

struct SteeringLinkage {
  std::string problem;                  // not empty: the geometry cannot steer, and why (naming attributes)
  std::vector<std::string> attributes;  // the attributes `problem` is about
  std::vector<SteeringSample> samples;  // over [low, high], ascending input
  double low = 0, high = 0;             // the inputs the linkage reaches: both loops close, both wheels
                                        // turning with the input (each end a dead point or a loop's limit)
  // Each fit's max_error is over the whole reach; each was fitted over a part of it about straight ahead
  // (near a dead point a wheel's angle bends like a square root, which no polynomial follows).
  PolynomialFit input_to_left;  // left = p(input): {0, 1} for Ackermann, a higher degree for columns
  PolynomialFit linkage;        // right = q(left), a quartic (c has 5 entries: MuJoCo's polycoef)
  double input_fitted_low = 0, input_fitted_high = 0;  // the inputs over which p was fitted
  double input_to_left_fitted = 0;                     // p's error there (rad)
  double fitted_low = 0, fitted_high = 0;              // the inputs over which q was fitted
  double linkage_fitted = 0;                           // q's error there (rad)
};

SteeringLinkage steering_linkage(const SteeringGeometry& g);

double evaluate_polynomial(const std::vector<double>& c, double x);

// The input within [low, high] (the reach, over which p rises or falls throughout) whose p(input) is `left`:
// the steering angle output of a column. Past p's value at an end it continues from that end.
double steering_input_for(const std::vector<double>& c, double left, double low, double high);

}  // namespace openplx::mjcf
