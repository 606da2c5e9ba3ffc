#include "frontend/urdf/urdf_import.h"

#include <urdf_parser/urdf_parser.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <charconv>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "frontend/urdf/package_lookup.h"
#include "frontend/urdf/package_uri.h"
#include "frontend/urdf/physical_inertia.h"
#include "frontend/urdf/urdf_document.h"

namespace openplx::frontend {
namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLElement;

// The shortest text that reads back as exactly `v`, as an OpenPLX Real literal.
std::string num(double v) {
  char buffer[32];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof(buffer), v);
  std::string s(buffer, error == std::errc() ? end : buffer);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // a Real literal, not an Int
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

// Whether a URDF name fits in a backtick identifier (which cannot hold a backtick or a line break).
bool identifier_safe(const std::string& name) {
  return name.find_first_of("`\r\n") == std::string::npos;
}

// An identifier for any URDF name.
std::string id(const std::string& name) {
  return "`" + name + "`";
}

// A direction orthogonal to `axis`, for a connector's normal.
Eigen::Vector3d normal_to(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d a = axis.normalized();
  const Eigen::Vector3d least = std::abs(a.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (least - least.dot(a) * a).normalized();
}

Eigen::Vector3d joint_axis(const urdf::Joint& joint) {
  Eigen::Vector3d axis = to_eigen(joint.axis);
  if (axis.squaredNorm() < 1e-24) axis = Eigen::Vector3d::UnitX();
  return axis.normalized();
}

// Generated OpenPLX, one line at a time, each remembering the URDF byte offset it came from.
class Writer {
 public:
  explicit Writer(const UrdfDocument& doc) : doc_(doc) {}
  // Lines written from now on come from element `e` (the `<robot>` element when null).
  void from(const XMLElement* e) { origin_ = doc_.offset_of(e ? e : doc_.robot()); }
  uint32_t origin() const { return origin_; }  // the URDF byte offset lines are written from now
  void line(const std::string& text) {
    out_ += text;
    out_ += '\n';
    origins_.push_back(origin_);
  }
  void transform(const std::string& attribute, const Eigen::Vector3d& p, const Eigen::Quaterniond& q,
                 const std::string& indent) {
    line(indent + attribute + ":");
    line(indent + "    position: " + vec(p));
    line(indent + "    rotation: Math.Quat.from_xyzw(" + num(q.x()) + ", " + num(q.y()) + ", " + num(q.z()) +
         ", " + num(q.w()) + ")");
  }
  void connector(const std::string& name, const Eigen::Vector3d& position, const Eigen::Vector3d& axis,
                 const Eigen::Vector3d& normal, const std::string& indent) {
    line(indent + id(name) + " is Physics3D.Interactions.MateConnector:");
    line(indent + "    position: " + vec(position));
    line(indent + "    main_axis: " + vec(axis));
    line(indent + "    normal: " + vec(normal));
  }
  std::string& text() { return out_; }
  std::vector<uint32_t>& origins() { return origins_; }

 private:
  const UrdfDocument& doc_;
  std::string out_;
  std::vector<uint32_t> origins_;
  uint32_t origin_ = 0;
};

// Where a mesh file is: relative names resolve against the URDF's folder; `package://P/rest` against
// package P as find_package looks it up (a Urdf.PackagePath in the model overrides this later, see
// `package_uri`), else against the first of the URDF's folder and those above it that holds `rest` (a
// robot checked out under another name). `missing_package` is P when neither finds it: the path is then
// `rest` in the URDF's folder.
struct MeshFile {
  std::string path;
  std::optional<PackageUri> missing_package;
};
MeshFile mesh_path(const std::string& filename, const fs::path& urdf_dir) {
  std::string name = filename;
  if (name.rfind("file://", 0) == 0) name = name.substr(7);
  if (const std::optional<PackageUri> uri = parse_package_uri(name)) {
    std::optional<fs::path> root = find_package(uri->package, urdf_dir);
    if (!root) root = find_beside_urdf(uri->inside, urdf_dir);
    return {(root.value_or(urdf_dir) / uri->inside).lexically_normal().generic_string(),
            root ? std::nullopt : uri};
  }
  const fs::path p(name);
  return {(p.is_absolute() ? p : urdf_dir / p).lexically_normal().generic_string(), std::nullopt};
}

struct Context {
  const UrdfDocument& doc;
  Writer& w;
  fs::path urdf_dir;
  std::vector<UrdfFinding>& findings;
  std::map<std::string, std::string> materials;  // URDF material name -> generated model name
  bool packages_final = false;                   // UrdfImportOptions::packages_final
};

// The shape element (<box>, <mesh>, ...) of a link's nth <collision> or <visual>.
const XMLElement* shape_element(const UrdfDocument& doc, const std::string& link, const char* kind,
                                size_t nth) {
  const XMLElement* e = UrdfDocument::child(doc.link(link), kind, static_cast<int>(nth));
  const XMLElement* g = UrdfDocument::child(e, "geometry");
  return g && g->FirstChildElement() ? g->FirstChildElement() : e;
}

// One geometry of a link: collision geometries are Physics3D ones, visual ones Visuals ones.
bool geometry(Context& c, const std::string& name, const urdf::Geometry& g, const urdf::Pose& origin,
              bool visual, const std::string& material, bool capsule) {
  const std::string ns = visual ? "Visuals.Geometries." : "Physics3D.Geometries.";
  const std::string in = "            ";
  Eigen::Quaterniond q = to_eigen(origin.rotation);
  switch (g.type) {
    case urdf::Geometry::BOX:
      c.w.line("        " + id(name) + " is " + ns + "Box:");
      c.w.line(in + "size: " + vec(to_eigen(static_cast<const urdf::Box&>(g).dim)));
      break;
    case urdf::Geometry::SPHERE:
      c.w.line("        " + id(name) + " is " + ns + "Sphere:");
      c.w.line(in + "radius: " + num(static_cast<const urdf::Sphere&>(g).radius));
      break;
    case urdf::Geometry::CYLINDER: {
      const auto& cyl = static_cast<const urdf::Cylinder&>(g);
      // URDF cylinders lie along z, OpenPLX ones along y: turn y onto z.
      q = q * Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()));
      // A URDF 1.1 capsule reaches here as a cylinder (urdf_values.cpp): same radius and cylindrical length.
      c.w.line("        " + id(name) + " is " + ns + (capsule ? "Capsule:" : "Cylinder:"));
      c.w.line(in + "radius: " + num(cyl.radius));
      c.w.line(in + "height: " + num(cyl.length));
      break;
    }
    case urdf::Geometry::MESH: {
      const auto& m = static_cast<const urdf::Mesh&>(g);
      const MeshFile mesh = mesh_path(m.filename, c.urdf_dir);
      const std::string& file = mesh.path;
      if (file.find('"') != std::string::npos || m.filename.find('"') != std::string::npos) {
        c.findings.push_back({true, c.w.origin(), "mesh path contains a quote: " + m.filename, {}});
        return false;
      }
      // A package found nowhere, with no Urdf.PackagePath to come: said here, at the <mesh>. A visual is
      // left out (a robot's looks never stop it loading); a collision mesh cannot be.
      if (mesh.missing_package && c.packages_final) {
        const PackageUri& uri = *mesh.missing_package;
        c.findings.push_back(
            {!visual,
             c.w.origin(),
             "mesh " + m.filename + ": package `" + uri.package + "` not found" +
                 (visual ? "; this visual was left out" : ""),
             {package_search_text(uri.package, uri.inside, c.urdf_dir), package_setting_text(uri.package)}});
        return true;  // nothing written: the visual is left out, the error stops the import
      }
      c.w.line("        " + id(name) + " is " + ns + "ExternalTriMeshGeometry:");
      c.w.line(in + "path: @\"" + file + "\"");
      c.w.line(in + "scale: " + vec(to_eigen(m.scale)));
      if (m.filename.rfind("package://", 0) == 0)
        c.w.line(in + "package_uri is String: \"" + m.filename + "\"");
      break;
    }
  }
  if (!material.empty()) c.w.line(in + "material becomes " + id(material));
  c.w.transform("local_transform", to_eigen(origin.position), q, in);
  return true;
}

// URDF materials with a colour become Visuals materials (models of the generated document), by name.
void declare_materials(Context& c, const urdf::ModelInterface& robot, const std::string& model_name) {
  std::vector<urdf::LinkSharedPtr> links;
  robot.getLinks(links);
  std::map<std::string, urdf::MaterialSharedPtr> used;  // name order: deterministic
  for (const auto& link : links) {
    for (const auto& v : link->visual_array) {
      if (v->material)
        used.emplace(v->material_name.empty() ? link->name + "/" : v->material_name, v->material);
    }
  }
  std::map<std::string, const XMLElement*> declared;  // top-level <material> by name, the last one
  for (const XMLElement* e = c.doc.robot()->FirstChildElement("material"); e;
       e = e->NextSiblingElement("material")) {
    if (e->Attribute("name")) declared[e->Attribute("name")] = e;
  }
  for (const auto& [name, material] : used) {
    // Internal names; one that cannot be an identifier is numbered instead.
    const std::string model =
        model_name + ".material." + (identifier_safe(name) ? name : std::to_string(c.materials.size()));
    c.materials[name] = model;
    const auto at = declared.find(name);
    c.w.from(at == declared.end() ? nullptr : at->second);
    const urdf::Color& rgba = material->color;
    c.w.line(id(model) + " is Visuals.Materials.Material:");
    c.w.line("    with Visuals.Materials.SurfaceFeatures.BaseColor");
    c.w.line("    base_color_tint: {" + num(rgba.r) + ", " + num(rgba.g) + ", " + num(rgba.b) + ", " +
             num(rgba.a) + "}");
    if (!material->texture_filename.empty()) {
      c.findings.push_back({false,
                            c.doc.offset_of(c.doc.robot()),
                            "material `" + name + "` has texture " + material->texture_filename +
                                ", which is not mapped (MuJoCo 2.2.2 takes textures only as its own assets); "
                                "the colour is kept",
                            {}});
    }
  }
}

// The link's inertial, checked: a non-physical tensor is repaired, with a warning at <inertia>.
void inertial(Context& c, const urdf::Link& link) {
  const urdf::Inertial& i = *link.inertial;
  Eigen::Matrix3d tensor;
  tensor << i.ixx, i.ixy, i.ixz, i.ixy, i.iyy, i.iyz, i.ixz, i.iyz, i.izz;
  const XMLElement* at = UrdfDocument::child(c.doc.link(link.name), "inertial");
  if (std::optional<InertiaRepair> repair = repair_inertia(i.mass, tensor)) {
    const XMLElement* inertia = UrdfDocument::child(at, "inertia");
    c.findings.push_back({false,
                          c.doc.offset_of(inertia ? inertia : at),
                          "link `" + link.name + "` has a non-physical inertia: " + repair->what,
                          {}});
    tensor = repair->tensor;
  }
  c.w.from(at);
  c.w.line("        inertia.mass: " + num(i.mass));
  // A mass of 0 is "computed from the geometry" in OpenPLX but massless in URDF (and MuJoCo's importer).
  if (i.mass == 0) c.w.line("        urdf_mass is String: \"as_written\"");
  // From <inertia>: what the emitter finds wrong with the tensor it writes is reported there.
  const XMLElement* inertia = UrdfDocument::child(at, "inertia");
  c.w.from(inertia ? inertia : at);
  c.w.line("        inertia.tensor: Physics3D.Bodies.Inertia.symmetric_tensor(" + vec(tensor.diagonal()) +
           ", " + num(tensor(0, 1)) + ", " + num(tensor(0, 2)) + ", " + num(tensor(1, 2)) + ")");
  c.w.from(at);
  c.w.transform("kinematics.local_cm_transform", to_eigen(i.origin.position), to_eigen(i.origin.rotation),
                "        ");
}

// World poses of the links at the zero configuration (for links that no mate places: floating joints).
std::map<std::string, Eigen::Isometry3d> zero_poses(const urdf::ModelInterface& robot) {
  std::map<std::string, Eigen::Isometry3d> pose;
  std::vector<urdf::LinkConstSharedPtr> stack{robot.getRoot()};
  pose[robot.getRoot()->name] = Eigen::Isometry3d::Identity();
  while (!stack.empty()) {
    urdf::LinkConstSharedPtr link = stack.back();
    stack.pop_back();
    for (const auto& child : link->child_links) {
      const urdf::Pose& o = child->parent_joint->parent_to_joint_origin_transform;
      Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
      t.translate(to_eigen(o.position));
      t.rotate(to_eigen(o.rotation));
      pose[child->name] = pose[link->name] * t;
      stack.push_back(child);
    }
  }
  return pose;
}

std::string mate_of(const urdf::Joint& joint) {
  switch (joint.type) {
    case urdf::Joint::REVOLUTE:
    case urdf::Joint::CONTINUOUS:
      return "Physics3D.Interactions.Hinge";
    case urdf::Joint::PRISMATIC:
      return "Physics3D.Interactions.Prismatic";
    case urdf::Joint::FIXED:
      return "Physics3D.Interactions.Lock";
    case urdf::Joint::PLANAR:
      return "Urdf.Planar";
    default:
      return "";
  }
}

// OpenPLX names of the joints. URDF keeps links and joints in separate namespaces, a generated system has
// one scope: a joint named like a link (or like another generated name) becomes `<name>_joint`, numbered if
// that is taken too. Its MuJoCo joint keeps the URDF name (`urdf_name`).
std::map<std::string, std::string> joint_attributes(const urdf::ModelInterface& robot) {
  static constexpr const char* kDerived[] = {"", "_limits", "_properties", "_mimic", "_parent", "_child"};
  std::set<std::string> taken{"world_anchor", "root_lock", "root_anchor"};
  for (const auto& [name, link] : robot.links_) taken.insert(name);
  auto free = [&](const std::string& a) {
    return std::none_of(std::begin(kDerived), std::end(kDerived),
                        [&](const char* suffix) { return taken.count(a + suffix) > 0; });
  };
  std::map<std::string, std::string> attributes;
  for (const auto& [name, joint] : robot.joints_) {  // std::map: name order, deterministic
    std::string a = name;
    for (int k = 1; !free(a); ++k) a = name + "_joint" + (k == 1 ? "" : std::to_string(k));
    for (const char* suffix : kDerived) taken.insert(a + suffix);
    attributes[name] = a;
  }
  return attributes;
}

// Whether a joint's zero lies outside its range: MuJoCo's limit rows then throw it into range within a few
// steps, which flings light links downstream (a Kinova Jaco's joint_2 and joint_3 exclude zero).
bool zero_outside_range(const urdf::Joint& joint) {
  const bool ranged = joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::PRISMATIC;
  return ranged && joint.limits && joint.limits->lower < joint.limits->upper &&
         (joint.limits->lower > 0 || joint.limits->upper < 0);
}

// Where a joint that follows no other starts: at zero, or at the middle of a range that excludes zero, where
// ROS's joint_state_publisher puts it (what the robot's author saw in RViz).
double leader_start(const urdf::Joint& joint) {
  return zero_outside_range(joint) ? (joint.limits->lower + joint.limits->upper) / 2 : 0.0;
}

// Where each joint starts: at zero (or leader_start), or a mimic follower where its mimic puts it (offset +
// multiplier times its leader's start), so that the coupling holds from the first step. Chains follow their
// leaders. A follower starts at offset + multiplier * (its leader's start); a chain that loops back on itself
// stops where it would repeat a joint, counted from the joint asked about.
std::map<std::string, double> joint_starts(const urdf::ModelInterface& robot) {
  std::map<std::string, double> start;
  for (const auto& [name, joint] : robot.joints_) {
    if (start.count(name)) continue;
    // Up the chain of leaders to a joint whose start is known, one that follows nobody, or a repeat.
    std::vector<urdf::JointConstSharedPtr> chain;
    std::set<std::string> seen;
    double known = 0;
    bool loops = false;
    for (urdf::JointConstSharedPtr j = joint; j;) {
      if (auto it = start.find(j->name); it != start.end()) {
        known = it->second;
        break;
      }
      if (!j->mimic) {
        start[j->name] = leader_start(*j);
        break;
      }
      if (!seen.insert(j->name).second) {
        loops = true;
        break;
      }
      chain.push_back(j);
      j = robot.getJoint(j->mimic->joint_name);
    }
    if (loops) {  // each joint of a loop sees its own truncation of it: no shared answer
      double value = 0, scale = 1;
      std::set<std::string> visited;
      for (urdf::JointConstSharedPtr j = joint; j && j->mimic && visited.insert(j->name).second;) {
        value += scale * j->mimic->offset;
        scale *= j->mimic->multiplier;
        j = robot.getJoint(j->mimic->joint_name);
      }
      start[name] = value;
      continue;
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      known = (*it)->mimic->offset + (*it)->mimic->multiplier * known;
      start[(*it)->name] = known;
    }
  }
  return start;
}

// The in-plane direction MuJoCo's importer takes as a planar joint's `_TX` axis: x turned by the shortest
// rotation from z onto the plane's normal.
Eigen::Vector3d planar_x(const Eigen::Vector3d& normal) {
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ(), n = normal.normalized();
  const Eigen::Vector3d cross = z.cross(n);
  if (cross.norm() < 1e-14) return Eigen::Vector3d::UnitX();  // along z, or a half turn about x
  return Eigen::AngleAxisd(std::atan2(cross.norm(), n.z()), cross.normalized()) * Eigen::Vector3d::UnitX();
}

// A joint connector's normal: any direction across the axis, or for a planar joint its `_TX` direction.
Eigen::Vector3d connector_normal(const urdf::Joint& joint) {
  const Eigen::Vector3d axis = joint_axis(joint);
  return joint.type == urdf::Joint::PLANAR ? planar_x(axis) : normal_to(axis);
}

}  // namespace

UrdfImport convert_urdf(const std::string& path, const std::string& urdf_text, const std::string& model_name,
                        const UrdfImportOptions& options) {
  UrdfImport result;
  UrdfDocument doc(urdf_text, path);
  if (!doc.well_formed()) {
    result.findings = std::move(doc.findings());
    return result;
  }
  const std::string lenient = doc.lenient_text();
  result.findings = std::move(doc.findings());
  if (std::any_of(result.findings.begin(), result.findings.end(),
                  [](const UrdfFinding& f) { return f.error; }))
    return result;  // malformed values: located here, before urdfdom would drop what holds them
  std::vector<std::string> errors, warnings;
  urdf::ModelInterfaceSharedPtr robot;
  {
    UrdfdomCapture capture(errors, warnings);
    robot = urdf::parseURDF(lenient);
  }
  for (const std::string& warning : warnings)
    result.findings.push_back({false, doc.offset_of(doc.robot()), "urdfdom: " + warning, {}});
  // urdfdom also logs errors for parts it skips while still returning a robot: each is an error too.
  if (!robot || !robot->getRoot() || !errors.empty()) {
    result.findings.push_back(doc.locate(errors));
    return result;
  }
  result.robot_name = robot->getName();
  Writer w(doc);
  Context c{doc, w, fs::path(path).parent_path(), result.findings, {}, options.packages_final};
  std::vector<urdf::JointSharedPtr> joints;
  for (const auto& [name, joint] : robot->joints_) joints.push_back(joint);  // std::map: name order
  // Names become backtick identifiers: a backtick or a line break cannot be in one.
  if (!identifier_safe(model_name)) {
    result.findings.push_back({true,
                               doc.offset_of(doc.robot()),
                               "the robot's model name `" + model_name +
                                   "` (from the file name or the import's alias) cannot be an OpenPLX name",
                               {}});
  }
  for (const auto& [name, link] : robot->links_) {
    if (!identifier_safe(name)) {
      result.findings.push_back(
          {true,
           doc.offset_of(doc.link(name)),
           "link name contains a backtick or a line break, which an OpenPLX name cannot hold",
           {}});
    }
  }
  for (const auto& joint : joints) {
    if (!identifier_safe(joint->name)) {
      result.findings.push_back(
          {true,
           doc.offset_of(doc.joint(joint->name)),
           "joint name contains a backtick or a line break, which an OpenPLX name cannot hold",
           {}});
    }
  }
  for (const auto& [name, link] : robot->links_) {
    if (link->inertial && link->inertial->mass < 0) {
      const XMLElement* mass = UrdfDocument::child(UrdfDocument::child(doc.link(name), "inertial"), "mass");
      result.findings.push_back(
          {true, doc.offset_of(mass ? mass : doc.link(name)), "link `" + name + "` has a negative mass", {}});
    }
  }
  for (const auto& joint : joints) {
    const XMLElement* element = doc.joint(joint->name);
    if (to_eigen(joint->axis).squaredNorm() < 1e-24 && UrdfDocument::child(element, "axis") &&
        joint->type != urdf::Joint::FIXED && joint->type != urdf::Joint::FLOATING) {
      result.findings.push_back({false,
                                 doc.offset_of(UrdfDocument::child(element, "axis")),
                                 "joint `" + joint->name + "` has a zero axis; the x axis was used",
                                 {}});
    }
    if (!joint->mimic && zero_outside_range(*joint)) {
      result.findings.push_back({false,
                                 doc.offset_of(UrdfDocument::child(element, "limit")),
                                 "joint `" + joint->name + "`'s zero lies outside its limits [" +
                                     num(joint->limits->lower) + ", " + num(joint->limits->upper) +
                                     "]: it starts at their middle, " + num(leader_start(*joint)) +
                                     ", as ROS's joint_state_publisher shows it (from zero, MuJoCo's limit "
                                     "would throw it into range and fling the links below it)",
                                 {}});
    }
    const bool ranged = joint->type == urdf::Joint::REVOLUTE || joint->type == urdf::Joint::PRISMATIC;
    if (ranged && joint->limits && joint->limits->lower > joint->limits->upper) {
      result.findings.push_back({false,
                                 doc.offset_of(UrdfDocument::child(element, "limit")),
                                 "joint `" + joint->name + "` has lower > upper; it was left without a range",
                                 {}});
    }
  }
  if (std::any_of(result.findings.begin(), result.findings.end(),
                  [](const UrdfFinding& f) { return f.error; }))
    return result;
  for (const auto& joint : joints) {
    const XMLElement* limit = UrdfDocument::child(doc.joint(joint->name), "limit");
    if (joint->type == urdf::Joint::PLANAR && limit) {
      result.findings.push_back({false,
                                 doc.offset_of(limit),
                                 "joint `" + joint->name +
                                     "` is planar: URDF limits only revolute and prismatic joints, so its "
                                     "<limit> was ignored (MuJoCo's own importer puts the range on `" +
                                     joint->name + "_TX` alone)",
                                 {}});
    }
  }
  const std::map<std::string, std::string> attribute = joint_attributes(*robot);
  const std::map<std::string, double> start = joint_starts(*robot);
  declare_materials(c, *robot, model_name);
  w.from(nullptr);
  w.line(id(model_name) + " is Physics3D.System:");
  w.connector("world_anchor", Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(),
              "    ");
  // Links in name order (deterministic), each with the connectors of the joints it takes part in.
  std::vector<urdf::LinkSharedPtr> links;
  robot->getLinks(links);
  std::sort(links.begin(), links.end(), [](const auto& a, const auto& b) { return a->name < b->name; });
  const std::string root = robot->getRoot()->name;
  // A root link named `world` is the world itself (the ROS convention MuJoCo's compiler follows): its joints
  // start from connectors fixed in the system.
  const bool world_root = root == "world";
  // A massless root link stays where it is (MuJoCo keeps it massless, welded to the world): a static body.
  const auto root_link = robot->getRoot();
  const bool massless_root = !world_root && (!root_link->inertial || root_link->inertial->mass <= 0);
  const std::map<std::string, Eigen::Isometry3d> zero = zero_poses(*robot);
  // The joints each link takes part in, in name order: a link's connectors without a walk over all joints
  // (which made a 10,000-link chain quadratic).
  std::map<std::string, std::vector<const urdf::Joint*>> joints_of_link;
  const std::vector<const urdf::Joint*> no_joints;
  for (const auto& joint : joints) {
    if (joint->type == urdf::Joint::FLOATING) continue;
    joints_of_link[joint->parent_link_name].push_back(joint.get());
    if (joint->child_link_name != joint->parent_link_name)
      joints_of_link[joint->child_link_name].push_back(joint.get());
  }
  if (world_root) {
    for (const auto& joint : joints) {
      if (joint->parent_link_name != "world") continue;
      w.from(doc.joint(joint->name));
      const Eigen::Vector3d axis = joint_axis(*joint), normal = connector_normal(*joint);
      const urdf::Pose& o = joint->parent_to_joint_origin_transform;
      const Eigen::Quaterniond r = to_eigen(o.rotation);
      w.connector(attribute.at(joint->name) + "_parent", to_eigen(o.position), r * axis, r * normal, "    ");
    }
  }
  for (const auto& link : links) {
    if (world_root && link->name == "world") continue;
    w.from(doc.link(link->name));
    w.line("    " + id(link->name) + " is Physics3D.Bodies.RigidBody:");
    if (massless_root && link->name == root) w.line("        is_dynamic: false");
    if (link->parent_joint && link->parent_joint->type == urdf::Joint::FLOATING) {
      // No mate places a floating joint's child: it starts where the joint's origin puts it.
      w.from(doc.joint(link->parent_joint->name));
      const Eigen::Isometry3d& t = zero.at(link->name);
      w.transform("kinematics.local_transform", t.translation(), Eigen::Quaterniond(t.rotation()),
                  "        ");
    }
    if (link->inertial) {
      inertial(c, *link);
    } else {
      // No <inertial>: the mass MuJoCo's URDF importer gives the link, from its collision geometry
      // (docs/urdf.md, mass laws). The emitter reads this marker; OpenPLX's own bodies never carry it.
      w.line("        urdf_mass is String: \"collisions\"");
    }
    // Geometries keep their URDF names (MuJoCo's compiler drops them) behind a prefix that cannot clash with
    // a body attribute: `collision_<name>`, or `collision_<index>` when unnamed or named twice.
    std::set<std::string> taken;
    auto geometry_name = [&](const char* kind, const std::string& urdf_name, size_t k) {
      const bool usable = !urdf_name.empty() && identifier_safe(urdf_name);
      std::string name = std::string(kind) + "_" + (usable ? urdf_name : std::to_string(k));
      if (!taken.insert(name).second) {
        name = std::string(kind) + "_" + std::to_string(k);
        taken.insert(name);
      }
      return name;
    };
    for (size_t k = 0; k < link->collision_array.size(); ++k) {
      const auto& col = link->collision_array[k];
      if (!col->geometry) continue;
      const XMLElement* shape = shape_element(doc, link->name, "collision", k);
      w.from(shape);
      if (!geometry(c, geometry_name("collision", col->name, k), *col->geometry, col->origin, false, "",
                    doc.is_capsule(shape)))
        return result;
    }
    for (size_t k = 0; k < link->visual_array.size(); ++k) {
      const auto& v = link->visual_array[k];
      if (!v->geometry) continue;
      const XMLElement* shape = shape_element(doc, link->name, "visual", k);
      w.from(shape);
      const std::string material =
          v->material ? c.materials[v->material_name.empty() ? link->name + "/" : v->material_name] : "";
      if (!geometry(c, geometry_name("visual", v->name, k), *v->geometry, v->origin, true, material,
                    doc.is_capsule(shape)))
        return result;
    }
    w.from(doc.link(link->name));
    if (link->name == root)
      w.connector("root_anchor", Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(),
                  "        ");
    const auto own = joints_of_link.find(link->name);
    for (const urdf::Joint* joint : own == joints_of_link.end() ? no_joints : own->second) {
      const Eigen::Vector3d axis = joint_axis(*joint), normal = connector_normal(*joint);
      const std::string& a = attribute.at(joint->name);
      w.from(doc.joint(joint->name));
      if (joint->parent_link_name == link->name) {
        const urdf::Pose& o = joint->parent_to_joint_origin_transform;
        const Eigen::Quaterniond r = to_eigen(o.rotation);
        w.connector(a + "_parent", to_eigen(o.position), r * axis, r * normal, "        ");
      }
      if (joint->child_link_name == link->name)
        w.connector(a + "_child", Eigen::Vector3d::Zero(), axis, normal, "        ");
    }
  }
  if (!world_root && !massless_root) {
    w.from(doc.link(root));
    w.line("    root_lock is Physics3D.Interactions.Lock:");
    w.line("        connectors: [world_anchor, " + id(root) + "." + id("root_anchor") + "]");
  }
  for (const auto& joint : joints) {
    const std::string mate = mate_of(*joint);
    if (mate.empty()) continue;  // floating: a free body
    const XMLElement* element = doc.joint(joint->name);
    const std::string& a = attribute.at(joint->name);
    w.from(element);
    const std::string parent =
        world_root && joint->parent_link_name == "world" ? "" : id(joint->parent_link_name) + ".";
    const std::string connectors =
        "[" + parent + id(a + "_parent") + ", " + id(joint->child_link_name) + "." + id(a + "_child") + "]";
    const bool hinge = mate == "Physics3D.Interactions.Hinge";
    w.line("    " + id(a) + " is " + mate + ":");
    w.line("        connectors: " + connectors);
    if (a != joint->name && joint->name.find_first_of("\"\\") == std::string::npos)
      w.line("        urdf_name is String: \"" + joint->name + "\"");
    if (start.at(joint->name) != 0 && (hinge || mate == "Physics3D.Interactions.Prismatic"))
      w.line(std::string("        ") + (hinge ? "initial_angle: " : "initial_position: ") +
             num(start.at(joint->name)));
    const auto& limits = joint->limits;
    if ((joint->type == urdf::Joint::REVOLUTE || joint->type == urdf::Joint::PRISMATIC) && limits &&
        limits->lower < limits->upper) {
      w.from(UrdfDocument::child(element, "limit"));
      w.line("    " + id(a + "_limits") + " is Physics3D.Interactions." +
             (hinge ? "RotationalRange" : "LinearRange") + ":");
      w.line("        connectors: " + connectors);
      w.line("        start: " + num(limits->lower));
      w.line("        end: " + num(limits->upper));
    }
    const double damping = joint->dynamics ? joint->dynamics->damping : 0,
                 friction = joint->dynamics ? joint->dynamics->friction : 0,
                 effort = limits ? limits->effort : 0, velocity = limits ? limits->velocity : 0;
    if (joint->type != urdf::Joint::FIXED && (damping > 0 || friction > 0 || effort > 0 || velocity > 0)) {
      w.from(UrdfDocument::child(element, joint->dynamics ? "dynamics" : "limit"));
      w.line("    " + id(a + "_properties") + " is Urdf.JointProperties:");
      w.line("        mate: " + id(a));
      if (damping > 0) w.line("        damping: " + num(damping));
      if (friction > 0) w.line("        friction: " + num(friction));
      if (effort > 0) w.line("        effort: " + num(effort));
      if (velocity > 0) w.line("        velocity: " + num(velocity));
    }
  }
  for (const auto& joint : joints) {
    if (!joint->mimic || robot->joints_.count(joint->mimic->joint_name) == 0) continue;
    w.from(UrdfDocument::child(doc.joint(joint->name), "mimic"));
    w.line("    " + id(attribute.at(joint->name) + "_mimic") + " is Urdf.Mimic:");
    w.line("        follower: " + id(attribute.at(joint->name)));
    w.line("        leader: " + id(attribute.at(joint->mimic->joint_name)));
    w.line("        multiplier: " + num(joint->mimic->multiplier));
    w.line("        offset: " + num(joint->mimic->offset));
  }
  result.text = std::move(w.text());
  result.line_origins = std::move(w.origins());
  return result;
}

}  // namespace openplx::frontend
