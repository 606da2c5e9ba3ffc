#include "mjcf_emitter/check.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <unordered_map>

#include "mjcf_emitter/xml.h"
#include "mujoco_support/instability.h"

namespace openplx::mjcf {

namespace {

// More steps than this are not taken (a tiny --timestep with a long --check-time): about a minute.
constexpr long kMaxCheckSteps = 2'000'000;

std::string short_number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", value);
  return text;
}

// MuJoCo names back to the OpenPLX (or URDF) items they were emitted from, and those items' declarations.
class Locator {
 public:
  Locator(const MuJoCoLibrary& mj, const mjModel* m, const snap::ResolvedSystem& system, std::string prefix,
          std::string root_name)
      : mj_(mj), m_(m), prefix_(std::move(prefix)), root_name_(std::move(root_name)) {
    for (const snap::FrameNode& n : system.nodes)
      nodes_.emplace(n.path.empty() ? root_name_ : n.path, n.where);
    for (const snap::Mate& mate : system.mates) mates_.emplace(mate.path, mate.where);
    for (const snap::Interaction1D& i : system.interactions) interactions_.emplace(i.path, i.where);
    if (system.root >= 0) root_ = system.nodes[static_cast<size_t>(system.root)].where;
  }

  // The MuJoCo name without the prefix: the OpenPLX path ("" for an unnamed element).
  std::string path(int type, int id) const {
    const char* name = id >= 0 ? mj_.id2name(m_, type, id) : nullptr;
    if (!name) return "";
    std::string_view text(name);
    if (text.substr(0, prefix_.size()) == prefix_) text.remove_prefix(prefix_.size());
    return std::string(text);
  }

  frontend::SourceRange root() const { return root_; }

  // A body's declaration, else its nearest declared ancestor's (bodies the emitter adds, e.g. track links).
  frontend::SourceRange body(int b) const {
    for (; b > 0; b = m_->body_parentid[b]) {
      if (auto it = nodes_.find(path(mjOBJ_BODY, b)); it != nodes_.end()) return it->second;
    }
    return root_;
  }

  // A joint's mate (Cylindrical's ".slide"/".hinge" and other suffixes stripped), else a free joint's body.
  frontend::SourceRange joint(int j) const {
    if (j < 0 || j >= m_->njnt) return root_;
    std::string name = path(mjOBJ_JOINT, j);
    while (!name.empty()) {
      if (auto it = mates_.find(name); it != mates_.end()) return it->second;
      if (auto it = nodes_.find(name); it != nodes_.end()) return it->second;
      const size_t dot = name.rfind('.');
      if (dot == std::string::npos) break;
      name.resize(dot);
    }
    return body(m_->jnt_bodyid[j]);
  }

  frontend::SourceRange dof(int d) const { return d >= 0 && d < m_->nv ? joint(m_->dof_jntid[d]) : root_; }

  frontend::SourceRange actuator(int a) const {
    if (a < 0 || a >= m_->nu) return root_;
    if (auto it = interactions_.find(path(mjOBJ_ACTUATOR, a)); it != interactions_.end()) return it->second;
    const bool on_joint =
        m_->actuator_trntype[a] == mjTRN_JOINT || m_->actuator_trntype[a] == mjTRN_JOINTINPARENT;
    return on_joint ? joint(m_->actuator_trnid[2 * a]) : root_;
  }

  // Where a warning points: its DOF's joint, qpos's joint or actuator; the root for buffers.
  frontend::SourceRange warning(int w, int info) const {
    switch (w) {
      case mjWARN_BADQPOS:
        return joint(joint_of_qpos(m_, info));
      case mjWARN_BADQVEL:
      case mjWARN_BADQACC:
      case mjWARN_INERTIA:
        return dof(info);
      case mjWARN_BADCTRL:
        return actuator(info);
      default:
        return root_;
    }
  }

  // "`path`", "the world".
  std::string body_name(const std::string& mujoco_name) const {
    if (mujoco_name == "world") return "the world";
    std::string_view text(mujoco_name);
    if (text.substr(0, prefix_.size()) == prefix_) text.remove_prefix(prefix_.size());
    return "`" + std::string(text) + "`";
  }
  // A MuJoCo name of any element without the prefix.
  std::string unprefixed(const std::string& mujoco_name) const {
    std::string_view text(mujoco_name);
    if (text.substr(0, prefix_.size()) == prefix_) text.remove_prefix(prefix_.size());
    return std::string(text);
  }
  frontend::SourceRange body_by_name(const std::string& mujoco_name) const {
    return mujoco_name == "world" ? root_ : body(mj_.name2id(m_, mjOBJ_BODY, mujoco_name.c_str()));
  }

 private:
  const MuJoCoLibrary& mj_;
  const mjModel* m_;
  std::string prefix_, root_name_;
  std::unordered_map<std::string, frontend::SourceRange> nodes_, mates_, interactions_;
  frontend::SourceRange root_;
};

// The declaration of the item emitted as MuJoCo element `path` (unprefixed): a body, a mate or an
// interaction of that path, else of the nearest enclosing path (`arm.collision_0` is on body `arm`). Found
// without a compiled model, for the elements of a model MuJoCo refused.
frontend::SourceRange declaration_of(const snap::ResolvedSystem& system, std::string path) {
  while (!path.empty()) {
    for (const snap::FrameNode& n : system.nodes)
      if (n.path == path) return n.where;
    for (const snap::Mate& m : system.mates)
      if (m.path == path) return m.where;
    for (const snap::Interaction1D& i : system.interactions)
      if (i.path == path) return i.where;
    const size_t dot = path.rfind('.');
    if (dot == std::string::npos) break;
    path.resize(dot);
  }
  return {};
}

// The MuJoCo name of the element MuJoCo's compiler names in `error`: "Object name = NAME, id = ..." (MuJoCo
// 2.2.2), "Element name 'NAME'", or else the `name` of the element at "line = L" of the MJCF file.
std::string element_named_in(const std::string& error, const std::string& xml_path) {
  for (const auto& [before, after] : {std::pair{"Object name = ", ","}, std::pair{"Element name '", "'"}}) {
    const size_t at = error.find(before);
    if (at == std::string::npos) continue;
    const size_t begin = at + std::string_view(before).size();
    const size_t end = error.find(after, begin);
    if (end != std::string::npos && end > begin) return error.substr(begin, end - begin);
  }
  const size_t at = error.find("line = ");
  if (at == std::string::npos) return "";
  const int line = std::atoi(error.c_str() + at + 7);
  std::ifstream in(xml_path);
  std::string text;
  for (int k = 0; k < line && std::getline(in, text); ++k) {
  }
  const size_t name = text.find(" name=\"");
  if (line < 1 || name == std::string::npos) return "";
  const size_t begin = name + 7, end = text.find('"', begin);
  return end == std::string::npos ? "" : text.substr(begin, end - begin);
}

std::string without_prefix(const std::string& name, const std::string& prefix) {
  return name.compare(0, prefix.size(), prefix) == 0 ? name.substr(prefix.size()) : name;
}

std::string overlap_report(const Locator& names, const InitialOverlap& o) {
  std::string why;
  if (!o.geom1.empty() && !o.geom2.empty())
    why = "collision geometries `" + names.unprefixed(o.geom1) + "` and `" + names.unprefixed(o.geom2) + "`";
  if (o.parent_and_child) {
    why +=
        std::string(why.empty() ? "" : "; ") + "they are joined" +
        (o.joint.empty() ? std::string() : " by `" + names.unprefixed(o.joint) + "`") +
        ", but MuJoCo leaves out a body's contacts with its parent only when the parent is not fixed to the "
        "world";
  }
  if (!why.empty()) why = " (" + why + ")";
  const std::string depth = length_text(o.depth);
  if (o.body1 == "world" || o.body2 == "world") {
    const std::string& body = o.body1 == "world" ? o.body2 : o.body1;
    return names.body_name(body) + " starts " + depth + " deep in the world's collision geometry" + why +
           ": MuJoCo pushes it out from the first step, and how hard differs between MuJoCo versions. Start "
           "it "
           "clear of that geometry (--exclude-initial-overlaps leaves contacts with the world's geometry: "
           "without them the body would fall through the ground)";
  }
  return names.body_name(o.body1) + " and " + names.body_name(o.body2) + " overlap by " + depth +
         " at the start" + why +
         ": MuJoCo pushes them apart from the first step, so they do not move as the model says, and "
         "differently "
         "in each MuJoCo version. If they are meant to overlap, exclude their contacts: "
         "--exclude-initial-overlaps does so for every pair that overlaps at the start (in OpenPLX, a "
         "Simulation.DisableCollisionPair); otherwise move them apart";
}

// Steps the model for `options.simulate_time` from `d`'s state, stopping at the first warning that means
// the motion is no longer the model's.
void simulate(const MuJoCoLibrary& mj, MuJoCoMessages& messages, const mjModel* m, mjData* d,
              const Locator& names, const std::string& prefix, const CheckOptions& options,
              CheckResult& result) {
  const double h = m->opt.timestep;
  const double wanted = std::ceil(options.simulate_time / h - 1e-9);
  const long steps = static_cast<long>(std::min<double>(wanted, kMaxCheckSteps));
  WarnedState captured;
  messages.on_warning = [&](const char*) { captured.capture(m, d); };
  const std::string during = "--check simulated the model from its initial state: ";
  std::set<int> noted;
  for (long step = 0; step < steps; ++step) {
    const WarningCounts before = WarningCounts::of(d);
    const double t = d->time;
    const size_t texts = messages.warnings.size();
    captured.clear();
    std::string error;
    if (!messages.call(
            d, [&] { mj.step(m, d); }, error)) {
      result.instabilities.push_back(
          {during + "at t = " + short_number(t) + " s MuJoCo stopped with an error: " + error, names.root()});
      break;
    }
    ++result.steps;
    if (options.progress) options.progress(d->time, options.simulate_time);
    const bool went_back = d->time < t + 0.5 * h;  // mj_resetData: time 0, then the step's own h
    bool wrong = false;
    for (int w : before.risen(d, went_back)) {
      const WarningSeverity severity = warning_severity(w);
      if (severity == WarningSeverity::Ignore ||
          (severity == WarningSeverity::Note && !noted.insert(w).second))
        continue;
      WarningFacts facts = captured.facts(d, w, t);
      facts.emitted_timestep = options.emitted_timestep;
      facts.prefix = prefix;
      LocatedProblem problem{during + describe_warning(m, facts), names.warning(w, facts.info)};
      if (severity == WarningSeverity::Wrong) {
        wrong = true;
        result.instabilities.push_back(std::move(problem));
      } else {
        result.mujoco_warnings.push_back(std::move(problem));
      }
    }
    if (wrong) {
      result.simulated_time = captured.valid ? captured.time : t;
      messages.on_warning = nullptr;
      return;
    }
    // A message no counter explains (the counted ones are told above, in our words).
    if (messages.warnings.size() > texts && before.risen(d, went_back).empty()) {
      for (size_t k = texts; k < messages.warnings.size(); ++k)
        result.mujoco_warnings.push_back({"MuJoCo warns during --check's simulation at t = " +
                                              short_number(t) + " s: " + messages.warnings[k],
                                          names.root()});
    }
  }
  result.simulated_time = d->time;
  messages.on_warning = nullptr;
  if (wanted > kMaxCheckSteps) {
    result.mujoco_warnings.push_back({"--check simulated only " + short_number(result.simulated_time) +
                                          " s of " + short_number(options.simulate_time) +
                                          " s: that would take more than " + std::to_string(kMaxCheckSteps) +
                                          " steps of " + short_number(h) + " s",
                                      names.root()});
  }
}

}  // namespace

std::string length_text(double metres) {
  if (metres >= 1) return short_number(metres) + " m";
  if (metres >= 0.01) return short_number(metres * 100) + " cm";
  return short_number(metres * 1000) + " mm";
}

std::vector<InitialOverlap> overlapping_bodies(const MuJoCoLibrary& mj, const mjModel* m, const mjData* d,
                                               double min_depth) {
  std::map<std::pair<std::string, std::string>, InitialOverlap> deepest;
  for (int c = 0; c < d->ncon; ++c) {
    const mjContact& contact = d->contact[c];
    const double depth = -contact.dist;
    if (!(depth > min_depth)) continue;
    const int g1 = contact.geom1, g2 = contact.geom2;
    const int b1 = m->geom_bodyid[g1], b2 = m->geom_bodyid[g2];
    if (b1 == b2) continue;
    const char* n1 = mj.id2name(m, mjOBJ_BODY, b1);
    const char* n2 = mj.id2name(m, mjOBJ_BODY, b2);
    InitialOverlap o;
    o.body1 = b1 == 0 ? "world" : n1 ? n1 : "body " + std::to_string(b1);
    o.body2 = b2 == 0 ? "world" : n2 ? n2 : "body " + std::to_string(b2);
    const char* geom1 = mj.id2name(m, mjOBJ_GEOM, g1);
    const char* geom2 = mj.id2name(m, mjOBJ_GEOM, g2);
    o.geom1 = geom1 ? geom1 : "";
    o.geom2 = geom2 ? geom2 : "";
    o.depth = depth;
    const int child = m->body_parentid[b1] == b2 ? b1 : m->body_parentid[b2] == b1 ? b2 : -1;
    if (child > 0) {
      o.parent_and_child = true;
      const char* joint =
          m->body_jntnum[child] > 0 ? mj.id2name(m, mjOBJ_JOINT, m->body_jntadr[child]) : nullptr;
      o.joint = joint ? joint : "";
    }
    if (o.body2 < o.body1) {
      std::swap(o.body1, o.body2);
      std::swap(o.geom1, o.geom2);
    }
    InitialOverlap& kept = deepest[{o.body1, o.body2}];
    if (o.depth > kept.depth) kept = std::move(o);
  }
  std::vector<InitialOverlap> out;
  out.reserve(deepest.size());
  for (auto& [pair, overlap] : deepest) out.push_back(std::move(overlap));
  return out;
}

void reset_to_initial_state(const MuJoCoLibrary& mj, const mjModel* m, mjData* d,
                            const std::string& key_name) {
  const int key = mj.name2id(m, mjOBJ_KEY, key_name.c_str());
  if (key >= 0) {
    mj.resetDataKeyframe(m, d, key);
  } else {
    mj.resetData(m, d);
  }
  mj.forward(m, d);
}

CheckResult check_mjcf(const std::string& xml_path, const snap::ResolvedSystem& system,
                       const snap::SnapResult& snap, const std::string& prefix, const std::string& root_name,
                       const CheckOptions& options) {
  CheckResult result;
  const MuJoCoLibrary* mj = mujoco_library(result.load_error);
  if (!mj) return result;
  MuJoCoMessages messages(*mj);
  char error[1000] = "";
  mjModel* model = mj->loadXML(xml_path.c_str(), nullptr, error, sizeof(error));
  if (!model) {
    result.load_error = error;
    const std::string element = element_named_in(error, xml_path);
    if (!element.empty()) result.load_error_where = declaration_of(system, without_prefix(element, prefix));
    return result;
  }
  result.loaded = true;
  const Locator names(*mj, model, system, prefix, root_name);
  for (const std::string& text : messages.warnings)
    result.mujoco_warnings.push_back({"MuJoCo warns while loading the MJCF: " + text, names.root()});
  if (error[0])
    result.mujoco_warnings.push_back(
        {"MuJoCo warns while loading the MJCF: " + std::string(error), names.root()});
  messages.warnings.clear();
  mjData* data = nullptr;
  std::string mujoco_error;
  if (!messages.call(
          nullptr, [&] { data = mj->makeData(model); }, mujoco_error) ||
      !data ||
      !messages.call(
          data, [&] { mj->forward(model, data); }, mujoco_error)) {
    result.instabilities.push_back({"--check: MuJoCo stopped with an error: " + mujoco_error, names.root()});
    if (data) mj->deleteData(data);
    mj->deleteModel(model);
    return result;
  }
  for (size_t n = 0; n < system.nodes.size(); ++n) {
    const snap::FrameNode& node = system.nodes[n];
    if (node.kind != snap::FrameNode::Kind::Body) continue;
    const std::string name = prefix + (node.path.empty() ? root_name : node.path);
    const int id = mj->name2id(model, mjOBJ_BODY, name.c_str());
    if (id < 0) {
      result.problems.push_back("body " + name + " is missing from the MJCF");
      result.problem_where.push_back(node.where);
      continue;
    }
    const Eigen::Vector3d pos(data->xpos[3 * id], data->xpos[3 * id + 1], data->xpos[3 * id + 2]);
    const Eigen::Quaterniond quat(data->xquat[4 * id], data->xquat[4 * id + 1], data->xquat[4 * id + 2],
                                  data->xquat[4 * id + 3]);
    const double dp = (pos - snap.node_world[n].position).norm();
    const double dq = quat.angularDistance(snap.node_world[n].rotation);
    result.max_position_error = std::max(result.max_position_error, dp);
    result.max_rotation_error = std::max(result.max_rotation_error, dq);
    // Not `dp > tolerance`: a NaN must fail too.
    if (!(dp <= options.tolerance) || !(dq <= options.tolerance)) {
      result.problems.push_back("body " + name + " is " + number(dp) + " m and " + number(dq) +
                                " rad away from its SNAP pose");
      result.problem_where.push_back(node.where);
    }
  }
  // Equality residuals: the constraint rows' violations after mj_forward.
  for (int i = 0; i < data->nefc; ++i) {
    if (data->efc_type[i] != mjCNSTR_EQUALITY) continue;
    const double r = std::abs(data->efc_pos[i]);
    result.max_equality_residual = std::max(result.max_equality_residual, r);
    if (!(r <= std::max(options.tolerance, 1e-7))) {
      const int eq = data->efc_id[i];
      const char* eq_name = mj->id2name(model, mjOBJ_EQUALITY, eq);
      result.problems.push_back(std::string("equality ") + (eq_name ? eq_name : std::to_string(eq)) +
                                " starts violated by " + number(r));
      result.problem_where.push_back(eq_name ? declaration_of(system, without_prefix(eq_name, prefix))
                                             : frontend::SourceRange{});
    }
  }
  // From the initial keyframe on: the overlaps it starts with, then its motion.
  const std::string key = prefix + "initial";
  if (messages.call(
          data, [&] { reset_to_initial_state(*mj, model, data, key); }, mujoco_error)) {
    result.overlaps = overlapping_bodies(*mj, model, data);
    for (const InitialOverlap& o : result.overlaps)
      result.overlap_reports.push_back(
          {overlap_report(names, o), names.body_by_name(o.body1 == "world" ? o.body2 : o.body1)});
    if (options.simulate_time > 0 && result.problems.empty())
      simulate(*mj, messages, model, data, names, prefix, options, result);
  } else {
    result.instabilities.push_back(
        {"--check: MuJoCo stopped with an error at the initial state: " + mujoco_error, names.root()});
  }
  mj->deleteData(data);
  mj->deleteModel(model);
  return result;
}

}  // namespace openplx::mjcf
