#include "frontend/semantics/deprecations.h"

#include <array>
#include <utility>

namespace openplx::frontend {
namespace {

// ../shared/spec/bundles-api.md §0.1 (migration 0.18.10 -> 0.19.0) and the 0.17.8 listings.
struct Move {
  std::string_view old_namespace;
  std::string_view name;
  std::string_view new_qualified;
};
constexpr std::array kMoves = {
    Move{"Physics.Charges", "Charge", "Physics.Interactions.Connector"},
    Move{"Physics.Charges", "ContactGeometry", "Physics.Geometries.ContactGeometry"},
    Move{"Physics.Charges", "Material", "Physics.Geometries.Material"},
    Move{"Physics.Charges", "LinearElasticMaterial", "Physics.Geometries.LinearElasticMaterial"},
    Move{"Physics1D.Charges", "MateConnector", "Physics1D.Interactions.MateConnector"},
    Move{"Physics1D.Charges", "LinearConnector", "Physics1D.Interactions.LinearConnector"},
    Move{"Physics1D.Charges", "RotationalConnector", "Physics1D.Interactions.RotationalConnector"},
    Move{"Physics3D.Charges", "MateConnector", "Physics3D.Interactions.MateConnector"},
    Move{"Physics3D.Charges", "RedirectedMateConnector", "Physics3D.Interactions.RedirectedMateConnector"},
    Move{"Physics3D.Charges", "AdaptiveMateConnector", "Physics3D.Interactions.AdaptiveMateConnector"},
    Move{"Physics3D.Charges", "World", "Physics3D.Interactions.World"},
    Move{"Physics3D.Charges", "ContactGeometry", "Physics3D.Geometries.ContactGeometry"},
    Move{"Physics3D.Charges", "Box", "Physics3D.Geometries.Box"},
    Move{"Physics3D.Charges", "Sphere", "Physics3D.Geometries.Sphere"},
    Move{"Physics3D.Charges", "Cylinder", "Physics3D.Geometries.Cylinder"},
    Move{"Physics3D.Charges", "Capsule", "Physics3D.Geometries.Capsule"},
    Move{"Physics3D.Charges", "Plane", "Physics3D.Geometries.Plane"},
    Move{"Physics3D.Charges", "ConvexMesh", "Physics3D.Geometries.ConvexMesh"},
    Move{"Physics3D.Charges", "TriMeshGeometry", "Physics3D.Geometries.TriMeshGeometry"},
    Move{"Physics3D.Charges", "TriMesh", "Physics3D.Geometries.TriMesh"},
    Move{"Physics3D.Charges", "ExternalTriMeshGeometry", "Physics3D.Geometries.ExternalTriMeshGeometry"},
    // Moved out of namespaces that still exist.
    Move{"Physics.Signals", "Torque3DOutput", "Physics3D.Signals.Torque3DOutput"},
    Move{"Physics.Signals", "Torque3DOutputTrait", "Physics3D.Signals.Torque3DOutputTrait"},
    Move{"Physics.Signals", "Force3DOutput", "Physics3D.Signals.Force3DOutput"},
    Move{"Physics.Signals", "Force3DOutputTrait", "Physics3D.Signals.Force3DOutputTrait"},
    // 0.17.8's engine, renamed when EmpiricalEngine arrived (same members).
    Move{"DriveTrain", "CombustionEngine", "DriveTrain.MeanValueEngine"},
};

constexpr std::array<std::pair<std::string_view, std::string_view>, 3> kMethods = {{
    {"Math.Quat.angleAxis", "Math.Quat.angle_axis"},
    {"Math.Quat.fromTo", "Math.Quat.from_to"},
    {"Math.Quat.fromXYZW", "Math.Quat.from_xyzw"},
}};

}  // namespace

std::optional<std::string> renamed_model(std::string_view old_namespace, std::string_view name) {
  for (const Move& move : kMoves) {
    if (move.old_namespace == old_namespace && move.name == name) return std::string(move.new_qualified);
  }
  return std::nullopt;
}

std::vector<std::string_view> renamed_namespaces() {
  std::vector<std::string_view> out;
  for (const Move& move : kMoves) {
    if (move.old_namespace.find(".Charges") == std::string_view::npos) continue;  // the ones that vanished
    if (out.empty() || out.back() != move.old_namespace) out.push_back(move.old_namespace);
  }
  return out;
}

std::optional<std::string_view> renamed_attribute(std::string_view name) {
  if (name == "charges") return std::string_view("connectors");
  return std::nullopt;
}

std::optional<std::string_view> legacy_attribute(std::string_view current) {
  if (current == "connectors") return std::string_view("charges");
  return std::nullopt;
}

std::optional<std::string_view> renamed_method(std::string_view qualified) {
  for (const auto& [old_name, new_name] : kMethods) {
    if (old_name == qualified) return new_name;
  }
  if (qualified == "Math.Vec3.fromXYZ") return std::string_view("Math.Vec3.from_xyz");
  return std::nullopt;
}

}  // namespace openplx::frontend
