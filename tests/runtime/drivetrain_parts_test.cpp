// Drivetrain parts against the physics they model (docs/mapping.md "Drivetrains"): gearbox gears and neutral,
// the limited-slip differential's breakaway torque and lock-up, a viscous gear's exponential approach, engine
// torque from its curve at the measured speed with the idle governor, a torque converter's fluid law.
// Shafts are driven and held by velocity motors (motor constraints), so speeds are set exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;

constexpr double kRpm = 60.0 / (2 * 3.14159265358979323846);  // rev/min per rad/s

rt::Simulation load(const openplx::testing::ScratchDir& dir, const std::string& text) {
  const auto file = dir / "model.openplx";
  std::ofstream(file) << text;
  return rt::Simulation::load(file.string());
}

std::string shaft(const std::string& name, double inertia) {
  return "    " + name + " is DriveTrain.Shaft:\n        inertia.inertia: " + std::to_string(inertia) + "\n";
}

std::string motor(const std::string& name, const std::string& shaft_name, double speed) {
  return "    " + name + " is Physics1D.Interactions.RotationalVelocityMotor:\n        connectors: [" +
         shaft_name + ".input]\n        target_speed: " + std::to_string(speed) + "\n";
}

// The input shaft turns at 1 rad/s; the output follows 1 / ratio of the selected gear.
TEST(DriveTrainGearBox, GearsNeutralAndReverse) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim =
      load(dir, "Box is Physics3D.System:\n" + shaft("in", 1) + shaft("out", 1) + motor("drive", "in", 1) +
                    "    box is DriveTrain.GearBox:\n"
                    "        connectors: [in.output, out.input]\n"
                    "        forward_gears: [4.0, 2.0]\n"
                    "        reverse_gears: [-5.0]\n"
                    "        initial_gear: 1\n");
  rt::Output out = sim.output("out.angular_velocity_output");
  rt::Output ratio = sim.output("box.ratio_output");
  rt::Output gear = sim.output("box.gear_output");
  rt::Input select = sim.input("box.gear_input");
  sim.advance(0.2);
  EXPECT_NEAR(out.real(), 0.25, 1e-4);
  EXPECT_DOUBLE_EQ(ratio.real(), 4.0);
  select.set(2.0);
  sim.advance(0.2);
  EXPECT_NEAR(out.real(), 0.5, 1e-4);
  EXPECT_DOUBLE_EQ(gear.real(), 2.0);
  select.set(-1.0);  // reverse: the sign comes from the list, not the ratio's own sign
  sim.advance(0.2);
  EXPECT_NEAR(out.real(), -0.2, 1e-4);
  EXPECT_DOUBLE_EQ(ratio.real(), -5.0);
  select.set(0.0);  // neutral: nothing couples the output, which keeps its speed
  sim.advance(0.2);
  EXPECT_NEAR(out.real(), -0.2, 1e-4);
  EXPECT_DOUBLE_EQ(ratio.real(), 0.0);
  EXPECT_THROW(select.set(3.0), rt::SignalError);
}

// Drive shaft held at 2 rad/s, gear ratio 1, unit axle inertias, a braking torque T on the left axle. Holding
// the axles together takes T / 2 between them: below the breakaway torque B = 50 they stick, above it they
// slip with the left axle decelerating at T / 2 - B (the right one accelerating as much).
std::string limited_slip() {
  return "Axle is Physics3D.System:\n" + shaft("drive", 1) + shaft("left", 1) + shaft("right", 1) +
         motor("engine", "drive", 2) +
         "    load is DriveTrain.TorqueMotor:\n        connectors: [left.input]\n"
         "    differential is DriveTrain.TorqueLimitedSlipDifferential:\n"
         "        drive_shaft: drive\n        left_axle_shaft: left\n        right_axle_shaft: right\n"
         "        breakaway_torque: 50\n";
}

struct AxleSpeeds {
  double left, right;
};

AxleSpeeds run_axle(const openplx::testing::ScratchDir& dir, double load_torque, bool locked,
                    double seconds) {
  rt::Simulation sim = load(dir, limited_slip());
  sim.input("differential.lock_up_input").set(locked);
  sim.advance(0.1);  // the motor brings the axles to 2 rad/s together
  EXPECT_NEAR(sim.output("left.angular_velocity_output").real(), 2.0, 1e-3);
  sim.input("load.torque_input").set(-load_torque);
  sim.advance(seconds);
  return {sim.output("left.angular_velocity_output").real(),
          sim.output("right.angular_velocity_output").real()};
}

TEST(DriveTrainDifferential, LimitedSlipSticksBelowBreakawayAndSlipsAbove) {
  const openplx::testing::ScratchDir dir;
  const AxleSpeeds stick = run_axle(dir, 80, false, 0.2);  // needs 40 N m < 50
  EXPECT_NEAR(stick.left, 2.0, 1e-3);
  EXPECT_NEAR(stick.right, 2.0, 1e-3);
  const AxleSpeeds slip = run_axle(dir, 150, false, 0.2);  // needs 75 N m > 50: slips at 25 rad/s^2
  EXPECT_NEAR(slip.left, 2.0 - 25 * 0.2, 0.05);
  EXPECT_NEAR(slip.right, 2.0 + 25 * 0.2, 0.05);
  const AxleSpeeds locked = run_axle(dir, 150, true, 0.2);  // locked up: no slip at any torque
  EXPECT_NEAR(locked.left, 2.0, 1e-3);
  EXPECT_NEAR(locked.right, 2.0, 1e-3);
}

// Input held at 1 rad/s, ratio 2, output inertia I = 1 with viscosity c = 2: the output approaches 1 / ratio
// as 0.5 (1 - exp(-c t / I)).
TEST(DriveTrainGear, ViscousGearApproachesItsRatioExponentially) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim =
      load(dir, "Pair is Physics3D.System:\n" + shaft("in", 1) + shaft("out", 1) + motor("drive", "in", 1) +
                    "    gear is DriveTrain.ViscousGear:\n"
                    "        connectors: [in.output, out.input]\n"
                    "        ratio: 2\n"
                    "        dissipation.viscosity: 2\n");
  rt::Output out = sim.output("out.angular_velocity_output");
  rt::Output torque = sim.output("gear.torque_output");
  sim.advance(0.5);
  // Explicit Euler on dw/dt = (c / I)(0.5 - w): (1 - c h / I)^n instead of exp(-c t / I), h = 0.002.
  EXPECT_NEAR(out.real(), 0.5 * (1 - std::exp(-1.0)), 2e-3);
  EXPECT_NEAR(torque.real(), 2 * (0.5 - out.real()), 1e-6);  // c times the slip, on the output
}

// MeanValueEngine defaults (GMTruck): 556 N m at 3200 rev/min, power peak at 4200, idle 1000. The shaft is
// held at a speed by a velocity motor; the engine's torque output is throttle times its curve there. The
// motor holds the speed to about 1e-5 of itself, so torques match to that times the curve's slope.
std::string engine_on_held_shaft(double rpm) {
  return "Bench is Physics3D.System:\n" + shaft("crank", 1) + motor("dyno", "crank", rpm / kRpm) +
         "    engine is DriveTrain.MeanValueEngine:\n        connectors: [crank.input]\n";
}

double engine_torque(const openplx::testing::ScratchDir& dir, double rpm, double throttle) {
  rt::Simulation sim = load(dir, engine_on_held_shaft(rpm));
  sim.input("engine.throttle_input").set(throttle);
  sim.advance(0.05);
  EXPECT_NEAR(sim.output("engine.rpm_output").real(), rpm, 1e-3 * rpm);
  return sim.output("engine.torque_output").real();
}

TEST(DriveTrainEngine, MeanValueTorqueFollowsItsCurveAtTheMeasuredSpeed) {
  const openplx::testing::ScratchDir dir;
  EXPECT_NEAR(engine_torque(dir, 3200, 1.0), 556, 1e-4);  // the peak: no slope
  EXPECT_NEAR(engine_torque(dir, 3200, 0.5), 278, 1e-4);
  // Power T n peaks at max_power_RPM.
  const double p_low = engine_torque(dir, 4000, 1.0) * 4000, p_peak = engine_torque(dir, 4200, 1.0) * 4200,
               p_high = engine_torque(dir, 4400, 1.0) * 4400;
  EXPECT_GT(p_peak, p_low);
  EXPECT_GT(p_peak, p_high);
  EXPECT_NEAR(engine_torque(dir, 7500, 1.0), 0, 1e-9);  // past max_RPM
}

TEST(DriveTrainEngine, EmpiricalTorqueInterpolatesItsTable) {
  const openplx::testing::ScratchDir dir;
  // Its documented default table: 100 N m at 0, 800 at 100, 0 at 150 rev/min.
  rt::Simulation sim =
      load(dir, "Bench is Physics3D.System:\n" + shaft("crank", 1) + motor("dyno", "crank", 125 / kRpm) +
                    "    engine is DriveTrain.EmpiricalEngine:\n"
                    "        connectors: [crank.input]\n"
                    "        initial_throttle: 0.5\n");
  sim.advance(0.05);
  EXPECT_NEAR(sim.output("engine.torque_output").real(), 0.5 * 400, 0.5 * 16 * 125e-5);  // slope 16 N m/rpm
}

TEST(DriveTrainEngine, IdleGovernorHoldsIdleWithoutThrottle) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim = load(dir, "Bench is Physics3D.System:\n" + shaft("crank", 0.5) +
                                     "    engine is DriveTrain.MeanValueEngine:\n"
                                     "        connectors: [crank.input]\n");
  rt::Output rpm = sim.output("engine.rpm_output");
  sim.advance(5.0);
  // Unloaded, the governor settles where its throttle is 0: exactly idle, within the step's torque kick.
  EXPECT_GT(rpm.real(), 0.9 * 1000);
  EXPECT_LE(rpm.real(), 1000 + 1.0);
}

// Pump held at 200 rad/s, turbine held still (stall), then at 0.8 of the pump: pump torque is
// factor(nu) rho D^5 w^2 against the pump, turbine torque the multiplier times that (default tables). Speeds
// are held to about 1e-5 of themselves: torques (as w^2) to 2e-5.
TEST(DriveTrainTorqueConverter, FluidLawAtStallAndAtCoupling) {
  const openplx::testing::ScratchDir dir;
  for (const double nu : {0.0, 0.8}) {
    rt::Simulation sim =
        load(dir, "Converter is Physics3D.System:\n" + shaft("pump", 1) + shaft("turbine", 1) +
                      motor("engine", "pump", 200) + motor("load", "turbine", 200 * nu) +
                      "    converter is DriveTrain.EmpiricalTorqueConverter:\n"
                      "        connectors: [pump.output, turbine.input]\n"
                      "    pump_torque is DriveTrain.Signals.TorqueConverterPumpTorqueOutput:\n"
                      "        torque_converter: converter\n"
                      "    turbine_torque is DriveTrain.Signals.TorqueConverterTurbineTorqueOutput:\n"
                      "        torque_converter: converter\n");
    sim.advance(0.05);
    const double factor = nu == 0 ? 0.0024 : 0.0017, multiplier = nu == 0 ? 2.0 : 1.0;
    const double expected = factor * 850 * std::pow(0.3, 5) * 200 * 200;
    EXPECT_NEAR(sim.output("pump_torque").real(), -expected, 1e-4 * expected);
    EXPECT_NEAR(sim.output("turbine_torque").real(), multiplier * expected, 1e-4 * expected);
    EXPECT_NEAR(sim.output("converter.slip_velocity_output").real(), 200 * nu - 200, 1e-3);
  }
}

}  // namespace

namespace {

// A Physics3D torque motor given a shaft's connector drives the shaft: 10 N m on 2 kg m^2 for 1 s is 5 rad/s.
TEST(DriveTrainMotor, Physics3DTorqueMotorOnAShaft) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim = load(dir, "Spin is Physics3D.System:\n" + shaft("s", 2) +
                                     "    motor is Physics3D.Interactions.TorqueMotor:\n"
                                     "        connectors: [s.input]\n");
  sim.input("motor.torque_input").set(10.0);
  sim.advance(1.0);
  EXPECT_NEAR(sim.output("s.angular_velocity_output").real(), 5.0, 1e-9);
}

// samples/drivetrain_machine.openplx: engine, automatic clutch, gearbox, differential, two driven wheels.
// Throttled it drives forward; braked (clutch out) it stops, the brakes' 1500 N m per wheel being more than
// the tyres' grip can turn.
TEST(DriveTrainMachine, DrivesForwardWhenThrottledAndStopsWhenBraked) {
  rt::Simulation sim = rt::Simulation::load(std::string(OPENPLX_SAMPLES_DIR) + "/drivetrain_machine.openplx");
  rt::Output position = sim.output("position");
  rt::Output velocity = sim.output("velocity");
  rt::Output rpm = sim.output("engine_rpm");
  sim.input("throttle").set(0.5);
  sim.advance(4.0);
  EXPECT_GT(position.vec3().x(), 10.0);
  EXPECT_GT(velocity.vec3().x(), 5.0);
  EXPECT_NEAR(position.vec3().y(), 0.0, 1e-6);  // both wheels drive alike: straight ahead
  EXPECT_GT(rpm.real(), 800);                   // above idle
  sim.input("throttle").set(0.0);
  sim.input("clutch").set(false);
  sim.input("brake_left").set(1.0);
  sim.input("brake_right").set(1.0);
  const double braking_from = position.vec3().x();
  sim.advance(2.0);
  EXPECT_NEAR(velocity.vec3().x(), 0.0, 1e-2);
  EXPECT_GT(position.vec3().x(), braking_from);  // it slid on, forward, and stopped
}

}  // namespace
