// The MJCF document of a resolved system: <compiler> and <option> (time step, gravity), then the lowering
// passes in order (lowering.h), then empty sections dropped and flexible equalities softened.
#include "mjcf_emitter/emitter.h"

#include "mjcf_emitter/lowering.h"
#include "mjcf_emitter/mujoco3_collision.h"
#include "mjcf_emitter/viewer_defaults.h"

namespace openplx::mjcf {

namespace {

// MuJoCo's noslip post-solver (docs/mapping.md "Velocity motors", "Clutches and brakes"). Isolated friction
// rows settle in one sweep and stop the sweeps after the next; a chain of coupled rows uses them all.
constexpr int kNoslipIterations = 10;
// Its stopping test divides the improvement by the mean joint inertia, which the motors' heavy reference
// joints inflate up to a billionfold (velocity_motors.cpp): the default 1e-6 stops it after one sweep
// whatever is left.
constexpr double kNoslipTolerance = 1e-15;
// The main solver's stopping test is divided alike: at its default 1e-8 it stopped a 7-link arm of
// velocity motors short after noslip's sweeps, and the arm sagged at 0.12 rad/s; at 1e-12 it does not (the
// same iterations per step, 1 plus the sweeps).
constexpr double kSolverTolerance = 1e-12;

// A fixed tendon with friction loss is a friction-row drive: a velocity motor, a clutch, a brake or a
// differential's slip limit (its loss may be 0 until an input engages or enables it).
bool has_friction_row_drives(Element& root) {
  const Element* tendons = root.child("tendon");
  if (!tendons) return false;
  return std::any_of(tendons->children().begin(), tendons->children().end(),
                     [](const auto& t) { return t->name() == "fixed" && t->get("frictionloss"); });
}

}  // namespace

Emitted Lowering::run() {
  Emitted out;
  Element& root = out.document;
  root.set("model", options_.model_name);
  root.add("compiler")
      .set("angle", "radian")
      .set("autolimits", "true")
      .set("inertiafromgeom", "auto")
      .set("inertiagrouprange", "0 5")
      .set("balanceinertia", "false")
      .set("fusestatic", "false")
      .set("discardvisual", "false");
  Element& option = root.add("option")
                        .set("timestep", options_.timestep)
                        .set("gravity", gravity())
                        .set("integrator", "Euler");
  // Room for contacts, sized once the tracks pass (tracks.cpp) knows the links it made.
  size_ = &root.add("size");
  for (const sn::Unsupported& u : system_.unsupported) {
    warn(u.where, "`" + u.path + "` is a " + u.type +
                      ", which has no MuJoCo 2.2.2 counterpart; it and its parts "
                      "were left out");
  }
  choose_tree();
  emit_geom_classes(root);
  assets_ = &root.add("asset");
  emit_visual_materials();
  Element& world = root.add("worldbody");
  world_ = &world;
  emit_world_geoms(world);
  emit_terrains();
  const size_t errors_before_bodies = sink_.error_count();
  emit_bodies(world);
  // A body left out (a chain deeper than MuJoCo reads) leaves every later pass warning about elements whose
  // bodies are missing: thousands of misleading lines after the one error that matters.
  if (sink_.error_count() > errors_before_bodies) return out;
  emit_loop_closures(root);
  emit_tracks(root);
  emit_distance_mates(root);
  emit_drivetrain(root);
  emit_joint_couplings(root);
  emit_compliant_dofs(root);
  emit_contact_pairs(root);
  emit_collision_filters(root);
  emit_actuators(root);
  emit_initial_state(root);
  bind_signals(root, out.signals);
  if (assets_->children().empty()) drop_empty(root, "asset");
  for (const char* section : {"tendon", "equality", "contact", "actuator", "sensor"})
    drop_empty(root, section);
  // A friction row leaks h (1 - d) of the acceleration it holds back each step (d <= 0.9999, MuJoCo's
  // stiffest); noslip re-solves friction rows without that softness. It also re-solves contact friction and
  // costs time, so only models with friction-row drives get it.
  if (has_friction_row_drives(root))
    option.set("tolerance", kSolverTolerance)
        .set("noslip_iterations", kNoslipIterations)
        .set("noslip_tolerance", kNoslipTolerance);
  finish_velocity_stand_ins(root);
  collect_rigid_rows(root);
  out.laws = laws_;
  if (options_.manifest_text)
    out.manifest_json = manifest_json(options_.model_name, options_.prefix, out.signals, out.laws);
  stiffen_equalities(root);
  finish_with_draft(root);
  enforce_moving_body_inertia();
  exclude_initial_overlaps(root);
  // After the drafts: they compile in MuJoCo 2.2.2, which rejects these 3.x settings.
  if (options_.mujoco == EmitOptions::MuJoCo::V3) add_mujoco3_collision_settings(root);
  // A light, framing and colours for viewers (viewer_defaults.h); after the draft, whose <statistic> it
  // completes.
  add_viewer_defaults(root, options_.prefix, options_.light);
  out.converted_meshes = std::move(converted_meshes_);
  return out;
}

// Simulation.Environment's uniform gravity field, else standard gravity.
Eigen::Vector3d Lowering::gravity() {
  const Eigen::Vector3d standard(0, 0, -9.81);
  switch (system_.gravity.kind) {
    case sn::Gravity::Kind::Standard:
      return standard;
    case sn::Gravity::Kind::NonUniform:
      warn(system_.nodes[system_.root].where,
           "`gravity` is not a uniform field; MuJoCo has only uniform gravity, so "
           "standard gravity was used");
      return standard;
    case sn::Gravity::Kind::Uniform:
      break;
  }
  return system_.gravity.vector;
}

Emitted emit_mjcf(const snap::ResolvedSystem& system, const EmitOptions& options,
                  frontend::DiagnosticSink& sink) {
  const size_t non_finite = non_finite_numbers_written();
  Emitted out = Lowering(system, options, sink).run();
  // A backstop: the value checks (snap, the evaluator) refuse bad numbers at the user's line; one that still
  // got through is our bug, and an error rather than a file MuJoCo would choke on.
  if (non_finite_numbers_written() != non_finite) {
    const std::string where = out.document.first_non_finite();
    sink.report(fe::DiagCode::MjcfInternal,
                system.root >= 0 ? system.nodes[system.root].where : fe::SourceRange{},
                "internal error: the MJCF would hold a number that is not finite" +
                    (where.empty() ? std::string() : " (" + where + ")") +
                    "; nothing was written. Please report this model");
  }
  return out;
}

}  // namespace openplx::mjcf
