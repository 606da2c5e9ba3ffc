#include "frontend/urdf/urdf_import.h"

#include <urdf_parser/urdf_parser.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "frontend/quoted.h"

namespace openplx::frontend {
namespace {

namespace fs = std::filesystem;

std::string num(double v) {
  std::ostringstream out;
  out.precision(17);
  out << v;
  std::string s = out.str();
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // a Real literal
  return s;
}

std::string vec(const Eigen::Vector3d& v) {
  return "{" + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + "}";
}

Eigen::Vector3d to_eigen(const urdf::Vector3& v) {
  return {v.x, v.y, v.z};
}
Eigen::Quaterniond to_eigen(const urdf::Rotation& r) {
  return Eigen::Quaterniond(r.w, r.x, r.y, r.z).normalized();
}

// An identifier for any URDF name.
std::string id(const std::string& name) {
  return "`" + name + "`";
}

// `local_transform` (or another AffineTransform attribute) of a pose, at `indent`.
std::string transform(const std::string& attribute, const Eigen::Vector3d& p, const Eigen::Quaterniond& q,
                      const std::string& indent) {
  return indent + attribute + ":\n" + indent + "    position: " + vec(p) + "\n" + indent +
         "    rotation: Math.Quat.from_xyzw(" + num(q.x()) + ", " + num(q.y()) + ", " + num(q.z()) + ", " +
         num(q.w()) + ")\n";
}

// A direction orthogonal to `axis`, for a connector's normal.
Eigen::Vector3d normal_to(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d a = axis.normalized();
  const Eigen::Vector3d least = std::abs(a.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (least - least.dot(a) * a).normalized();
}

std::string connector(const std::string& name, const Eigen::Vector3d& position, const Eigen::Vector3d& axis,
                      const Eigen::Vector3d& normal) {
  return "        " + id(name) +
         " is Physics3D.Interactions.MateConnector:\n            position: " + vec(position) +
         "\n            main_axis: " + vec(axis) + "\n            normal: " + vec(normal) + "\n";
}

// A mesh file: relative names resolve against the URDF's folder; `package://P/rest` against the folder that
// holds P next to (or above) the URDF.
std::string mesh_path(const std::string& filename, const fs::path& urdf_dir) {
  std::string name = filename;
  if (name.rfind("file://", 0) == 0) name = name.substr(7);
  if (name.rfind("package://", 0) == 0) {
    const std::string rest = name.substr(10);
    const size_t slash = rest.find('/');
    const std::string package = rest.substr(0, slash),
                      inside = slash == std::string::npos ? "" : rest.substr(slash + 1);
    for (fs::path dir = urdf_dir; !dir.empty(); dir = dir.parent_path()) {
      if (dir.filename() == package) return (dir / inside).lexically_normal().generic_string();
      if (fs::is_directory(dir / package))
        return (dir / package / inside).lexically_normal().generic_string();
      if (dir == dir.parent_path()) break;
    }
    return (urdf_dir / inside).lexically_normal().generic_string();
  }
  const fs::path p(name);
  return (p.is_absolute() ? p : urdf_dir / p).lexically_normal().generic_string();
}

// One geometry of a link: collision geometries are Physics3D ones, visual ones Visuals ones.
std::string geometry(const std::string& name, const urdf::Geometry& g, const urdf::Pose& origin, bool visual,
                     const fs::path& urdf_dir, std::string& error) {
  const std::string ns = visual ? "Visuals.Geometries." : "Physics3D.Geometries.";
  Eigen::Quaterniond q = to_eigen(origin.rotation);
  std::string body;
  switch (g.type) {
    case urdf::Geometry::BOX:
      body = "            size: " + vec(to_eigen(static_cast<const urdf::Box&>(g).dim)) + "\n";
      return "        " + id(name) + " is " + ns + "Box:\n" + body +
             transform("local_transform", to_eigen(origin.position), q, "            ");
    case urdf::Geometry::SPHERE:
      return "        " + id(name) + " is " + ns +
             "Sphere:\n            radius: " + num(static_cast<const urdf::Sphere&>(g).radius) + "\n" +
             transform("local_transform", to_eigen(origin.position), q, "            ");
    case urdf::Geometry::CYLINDER: {
      const auto& c = static_cast<const urdf::Cylinder&>(g);
      // URDF cylinders lie along z, OpenPLX ones along y: turn y onto z.
      q = q * Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()));
      return "        " + id(name) + " is " + ns + "Cylinder:\n            radius: " + num(c.radius) +
             "\n            height: " + num(c.length) + "\n" +
             transform("local_transform", to_eigen(origin.position), q, "            ");
    }
    case urdf::Geometry::MESH: {
      const auto& m = static_cast<const urdf::Mesh&>(g);
      const std::string file = mesh_path(m.filename, urdf_dir);
      if (file.find('"') != std::string::npos) {
        error = "mesh path contains a quote: " + file;
        return "";
      }
      return "        " + id(name) + " is " + ns + "ExternalTriMeshGeometry:\n            path: @\"" + file +
             "\"\n            scale: " + vec(to_eigen(m.scale)) + "\n" +
             transform("local_transform", to_eigen(origin.position), q, "            ");
    }
  }
  return "";
}

}  // namespace

std::optional<std::string> urdf_to_openplx(const std::string& path, const std::string& model_name,
                                           std::string& error) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream xml;
  xml << in.rdbuf();
  if (!in) {
    error = "cannot read " + path;
    return std::nullopt;
  }
  urdf::ModelInterfaceSharedPtr robot = urdf::parseURDF(xml.str());
  if (!robot) {
    error = "urdfdom rejected " + path + " (see its messages above)";
    return std::nullopt;
  }
  const fs::path urdf_dir = fs::path(path).parent_path();
  std::string out = id(model_name) + " is Physics3D.System:\n";
  out +=
      "    world_anchor is Physics3D.Interactions.MateConnector:\n        main_axis: {0.0, 0.0, 1.0}\n"
      "        normal: {1.0, 0.0, 0.0}\n";
  // Links in name order (deterministic), each with the connectors of the joints it takes part in.
  std::vector<urdf::LinkSharedPtr> links;
  robot->getLinks(links);
  std::sort(links.begin(), links.end(), [](const auto& a, const auto& b) { return a->name < b->name; });
  std::vector<urdf::JointSharedPtr> joints;
  for (const auto& [name, joint] : robot->joints_) joints.push_back(joint);  // std::map: name order
  const std::string root = robot->getRoot() ? robot->getRoot()->name : "";
  // A root link named `world` is the world itself (the ROS convention MuJoCo's compiler follows): its joints
  // start from connectors fixed in the system.
  const bool world_root = root == "world";
  // A massless root link stays where it is (MuJoCo keeps it massless, welded to the world): a static body.
  const auto root_link = robot->getRoot();
  const bool massless_root =
      !world_root && root_link && (!root_link->inertial || root_link->inertial->mass <= 0);
  if (world_root) {
    for (const auto& joint : joints) {
      if (joint->parent_link_name != "world") continue;
      Eigen::Vector3d axis = to_eigen(joint->axis);
      if (axis.squaredNorm() < 1e-24) axis = Eigen::Vector3d::UnitX();
      axis.normalize();
      const urdf::Pose& o = joint->parent_to_joint_origin_transform;
      const Eigen::Quaterniond r = to_eigen(o.rotation);
      out +=
          connector(joint->name + "_parent", to_eigen(o.position), r * axis, r * normal_to(axis)).substr(4);
    }
  }
  for (const auto& link : links) {
    if (world_root && link->name == "world") continue;
    out += "    " + id(link->name) + " is Physics3D.Bodies.RigidBody:\n";
    if (massless_root && link->name == root) out += "        is_dynamic: false\n";
    if (link->inertial) {
      const urdf::Inertial& i = *link->inertial;
      out += "        inertia.mass: " + num(i.mass) + "\n";
      out += "        inertia.tensor: Physics3D.Bodies.Inertia.symmetric_tensor(" +
             vec({i.ixx, i.iyy, i.izz}) + ", " + num(i.ixy) + ", " + num(i.ixz) + ", " + num(i.iyz) + ")\n";
      out += transform("kinematics.local_cm_transform", to_eigen(i.origin.position),
                       to_eigen(i.origin.rotation), "        ");
    }
    for (size_t k = 0; k < link->collision_array.size(); ++k) {
      const auto& c = link->collision_array[k];
      if (!c->geometry) continue;
      out += geometry("collision_" + std::to_string(k), *c->geometry, c->origin, false, urdf_dir, error);
    }
    for (size_t k = 0; k < link->visual_array.size(); ++k) {
      const auto& v = link->visual_array[k];
      if (!v->geometry) continue;
      out += geometry("visual_" + std::to_string(k), *v->geometry, v->origin, true, urdf_dir, error);
    }
    if (!error.empty()) return std::nullopt;
    if (link->name == root)
      out += connector("root_anchor", Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(),
                       Eigen::Vector3d::UnitX());
    for (const auto& joint : joints) {
      Eigen::Vector3d axis = to_eigen(joint->axis);
      if (axis.squaredNorm() < 1e-24) axis = Eigen::Vector3d::UnitX();
      axis.normalize();
      const Eigen::Vector3d normal = normal_to(axis);
      if (joint->parent_link_name == link->name) {
        const urdf::Pose& o = joint->parent_to_joint_origin_transform;
        const Eigen::Quaterniond r = to_eigen(o.rotation);
        out += connector(joint->name + "_parent", to_eigen(o.position), r * axis, r * normal);
      }
      if (joint->child_link_name == link->name)
        out += connector(joint->name + "_child", Eigen::Vector3d::Zero(), axis, normal);
    }
  }
  if (!root.empty() && !world_root && !massless_root) {
    out += "    root_lock is Physics3D.Interactions.Lock:\n        connectors: [world_anchor, " + id(root) +
           "." + id("root_anchor") + "]\n";
  }
  for (const auto& joint : joints) {
    std::string mate;
    switch (joint->type) {
      case urdf::Joint::REVOLUTE:
      case urdf::Joint::CONTINUOUS:
        mate = "Hinge";
        break;
      case urdf::Joint::PRISMATIC:
        mate = "Prismatic";
        break;
      case urdf::Joint::FIXED:
        mate = "Lock";
        break;
      case urdf::Joint::FLOATING:
        continue;  // a free body
      default:
        error = "joint `" + joint->name + "` has a type MuJoCo cannot take (planar or unknown)";
        return std::nullopt;
    }
    const std::string parent =
        world_root && joint->parent_link_name == "world" ? "" : id(joint->parent_link_name) + ".";
    const std::string connectors = "[" + parent + id(joint->name + "_parent") + ", " +
                                   id(joint->child_link_name) + "." + id(joint->name + "_child") + "]";
    out += "    " + id(joint->name) + " is Physics3D.Interactions." + mate +
           ":\n        connectors: " + connectors + "\n";
    const bool limited = (joint->type == urdf::Joint::REVOLUTE || joint->type == urdf::Joint::PRISMATIC) &&
                         joint->limits && joint->limits->lower < joint->limits->upper;
    if (limited) {
      out += "    " + id(joint->name + "_limits") + " is Physics3D.Interactions." +
             (mate == "Hinge" ? "RotationalRange" : "LinearRange") + ":\n        connectors: " + connectors +
             "\n        start: " + num(joint->limits->lower) + "\n        end: " + num(joint->limits->upper) +
             "\n";
    }
  }
  for (const auto& joint : joints) {
    if (!joint->mimic || robot->joints_.count(joint->mimic->joint_name) == 0) continue;
    out += "    " + id(joint->name + "_mimic") + " is Urdf.Mimic:\n        follower: " + id(joint->name) +
           "\n        leader: " + id(joint->mimic->joint_name) +
           "\n        multiplier: " + num(joint->mimic->multiplier) +
           "\n        offset: " + num(joint->mimic->offset) + "\n";
  }
  return out;
}

}  // namespace openplx::frontend
