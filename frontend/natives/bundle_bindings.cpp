// Natives of the non-Math bundles: the few `fn`s a model's evaluation calls (the rest are runtime hooks
// such as on_init() or signal factories, which evaluation never calls).
#include <cmath>
#include <string>

#include "frontend/evaluation/evaluator.h"
#include "frontend/natives/builtin_natives.h"

namespace openplx::natives {
namespace {

using frontend::NativeCall;
using frontend::NativeRegistry;
using frontend::Value;
using Args = std::span<const Value>;

// Bytes per point of each Sensors.LidarOutputField (its suffix names the element type).
int lidar_field_bytes(int64_t field) {
  switch (field) {
    case 1:
      return 8;  // TimeStamp_F64
    case 11:
      return 12;  // Position3D_F32
    case 12:
      return 4;  // Distance_F32
    case 13:
      return 48;  // RayPose3x4_F32
    case 21:
      return 4;  // IsHit_I32
    case 22:
      return 4;  // Intensity_F32
    case 31:
      return 4;  // EntityId_I32
    default:
      return -1;
  }
}

// A material (or terrain material) is "default" when nothing assigned its density: the runtime then
// uses its own default material instead of a custom one.
Value is_default_material(NativeCall& c, Args a) {
  const frontend::Object& material = c.evaluator().graph().at(a[0].object);
  const frontend::Slot* density = material.find("density");
  return Value::of_bool(!density || !density->explicit_value);
}

// The 0.20 releases' gyroscope, accelerometer and magnetometer outputs (our bundles' IMUOutput since): one
// record of the fields listed, each a Sensors.Signals.TriaxialOutputField axis read as a double.
Value triaxial_marshalling(NativeCall& c, Args a) {
  int bytes = 0;
  for (const Value& field : a[0].array()) {
    if (field.int_value < 1 || field.int_value > 3)
      return c.fail("unknown triaxial output field " + std::to_string(field.int_value));
    bytes += 8;  // X_F64, Y_F64, Z_F64
  }
  return c.make_with("Physics.Signals.Marshalling", {{"is_dynamic", Value::of_bool(false)},
                                                     {"size", Value::of_int(bytes)},
                                                     {"array_type", Value::of_int(0)}});
}

}  // namespace

void register_bundle_natives(NativeRegistry& r) {
  for (const char* sensor : {"Gyroscope", "Accelerometer", "Magnetometer"})
    r.add(std::string("Sensors.Signals.") + sensor + "Output.marshalling_from_fields", &triaxial_marshalling);
  r.add("Physics3D.Bodies.Inertia.symmetric_tensor", [](NativeCall& c, Args a) {
    auto d = c.fields(a[0], {"x", "y", "z"});
    const double e01 = a[1].as_real(), e02 = a[2].as_real(), e12 = a[3].as_real();
    Value out = c.make("Math.Matrix3x3", {{"e00", d[0]},
                                          {"e01", e01},
                                          {"e02", e02},
                                          {"e10", e01},
                                          {"e11", d[1]},
                                          {"e12", e12},
                                          {"e20", e02},
                                          {"e21", e12},
                                          {"e22", d[2]}});
    return out;
  });
  r.add("Visuals.Properties.Color.from_rgb", [](NativeCall& c, Args a) {
    return c.make("Visuals.Properties.Color",
                  {{"r", a[0].as_real()}, {"g", a[1].as_real()}, {"b", a[2].as_real()}, {"a", 1.0}});
  });
  r.add("Physics.Geometries.Material.is_default_material", &is_default_material);
  r.add("Terrain.TerrainMaterial.is_default_terrain_material", &is_default_material);
  r.add("Sensors.Signals.LidarOutput.marshalling_from_fields", [](NativeCall& c, Args a) {
    int bytes = 0;
    for (const Value& field : a[0].array()) {
      const int size = lidar_field_bytes(field.int_value);
      if (size < 0) return c.fail("unknown lidar output field " + std::to_string(field.int_value));
      bytes += size;
    }
    // One record per lidar ray, as many as hit: a dynamic array of `bytes`-sized points.
    return c.make_with("Physics.Signals.Marshalling", {{"is_dynamic", Value::of_bool(true)},
                                                       {"size", Value::of_int(bytes)},
                                                       {"array_type", Value::of_int(2)}});
  });
}

}  // namespace openplx::natives
