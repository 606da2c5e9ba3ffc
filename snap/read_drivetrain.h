// The numbers of drivetrain couplings and power sources (the structural part, which shafts they join, is in
// resolve_system.cpp).
#pragma once

#include "snap/attribute_reader.h"
#include "snap/resolved_system.h"

namespace openplx::snap {

// What `c.kind` maps with: gear flexibility and viscosity, gearbox gears, clutch and brake capacity and
// engagement, limited-slip breakaway torque, engine torque curves, converter tables.
void read_drive_parameters(AttributeReader& in, frontend::ObjectId id, DriveCoupling& c);

// A MeanValueEngine's full-throttle torque over speed (rev/min), from its rated figures. AGX's mean-value
// model (manifold pressure, volumetric efficiency) is not published; this curve keeps what the figures say:
// the peak max_torque at max_torque_RPM, the power peak at max_power_RPM (a parabola in speed with dP/dn = 0
// there), flat below idle, nothing past max_RPM. UNCONFIRMED against AGX.
Curve mean_value_torque_curve(double max_torque, double max_torque_rpm, double max_power_rpm, double idle_rpm,
                              double max_rpm);

// Linear interpolation in a curve, flat beyond its ends (0 for an empty one).
double interpolate(const Curve& curve, double x);

}  // namespace openplx::snap
