// The resolved system read from evaluated models: bodies with mass properties, geometries with their
// materials, mates with their types and parameters, the 1-dof interactions attached to each mate with their
// parameters, contact models, collision groups, gravity and signals with their sources.
#include "snap/resolve_system.h"

#include <filesystem>

#include "tests/support/eval_fixture.h"

namespace {

namespace fe = openplx::frontend;
namespace sn = openplx::snap;
namespace fs = std::filesystem;

const fs::path kAgx = fs::path(OPENPLX_CORPUS_DIR) / "agxunity";

class ResolvedSystem : public openplx::testing::EvalTest {
 protected:
  void system_of(const std::string& file, const char* model = nullptr) {
    ASSERT_TRUE(load_file((kAgx / file).string(), model)) << all_diags();
    system_ = sn::resolve_system(*evaluator_, root_, sink_);
  }
  const sn::FrameNode& node(const std::string& path) {
    for (const sn::FrameNode& n : system_.nodes) {
      if (n.path == path) return n;
    }
    ADD_FAILURE() << "no node " << path;
    return system_.nodes.front();
  }
  sn::ResolvedSystem system_;
};

TEST_F(ResolvedSystem, MultiInteractionAttachesSevenInteractionsPerMate) {
  system_of("multi_interaction.openplx");
  ASSERT_EQ(system_.mates.size(), 2u);
  using K = sn::Interaction1D::Kind;
  for (size_t m = 0; m < system_.mates.size(); ++m) {
    std::map<K, int> kinds;
    for (const sn::Interaction1D& i : system_.interactions) {
      if (i.mate == static_cast<int>(m)) ++kinds[i.kind];
    }
    const bool hinge = system_.mates[m].type == sn::MateType::Hinge;
    EXPECT_EQ(kinds[hinge ? K::RotationalVelocityMotor : K::LinearVelocityMotor], 2) << system_.mates[m].path;
    EXPECT_EQ(kinds[hinge ? K::RotationalRange : K::LinearRange], 2) << system_.mates[m].path;
    EXPECT_EQ(kinds[hinge ? K::TorsionSpring : K::LinearSpring], 2) << system_.mates[m].path;
  }
  EXPECT_EQ(system_.interactions.size(), 12u);
}

TEST_F(ResolvedSystem, BodiesCarryMassAndGeometries) {
  system_of("multi_interaction.openplx");
  const sn::FrameNode& rod = node("hingePendulum.rod");
  EXPECT_EQ(rod.kind, sn::FrameNode::Kind::Body);
  EXPECT_EQ(rod.body.mass, 10.0);
  EXPECT_TRUE(rod.body.dynamic);
  size_t boxes = 0;
  for (const sn::Geometry& g : system_.geometries) {
    if (g.path == "hingePendulum.rod.geometry") {
      EXPECT_EQ(g.shape, sn::Geometry::Shape::Box);
      EXPECT_EQ(g.size, Eigen::Vector3d(0.1, 0.1, 1));
      ++boxes;
    }
    if (g.path == "hingePendulum.rod.arrow") {
      EXPECT_EQ(g.local.position, Eigen::Vector3d(0, 0, 0.5));
      EXPECT_NEAR(g.local.rotation.angularDistance(
                      Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitY()))),
                  0.0, 1e-12);
      ++boxes;
    }
  }
  EXPECT_EQ(boxes, 2u);
}

TEST_F(ResolvedSystem, MaterialsAndKinematicBodies) {
  system_of("material_scene.openplx");
  std::map<std::string, double> density;
  for (const sn::Geometry& g : system_.geometries) {
    ASSERT_GE(g.material, 0) << g.path;
    density[g.path] = system_.materials[g.material].density;
  }
  EXPECT_EQ(density["Box1.geometry"], 1500.0);
  EXPECT_EQ(density["Box2.geometry"], 2000.0);
  EXPECT_EQ(density["BoxInline.geometry"], 500.0);
  EXPECT_EQ(system_.mates.size(), 1u);
  EXPECT_EQ(system_.interactions.size(), 1u);
  EXPECT_EQ(system_.interactions[0].mate, 0);  // GroundMotor drives GroundHinge
}

TEST_F(ResolvedSystem, SignalsWithTheirSources) {
  system_of("signal_test.openplx");
  std::map<std::string, const sn::Signal*> by_path;
  for (const sn::Signal& s : system_.signals) by_path[s.path] = &s;
  ASSERT_TRUE(by_path.count("motorSpeedInput"));
  EXPECT_TRUE(by_path["motorSpeedInput"]->input);
  ASSERT_EQ(by_path["motorSpeedInput"]->source_kind, sn::SignalSource::Interaction);
  EXPECT_EQ(system_.interactions[by_path["motorSpeedInput"]->source].object, object("motor"));
  ASSERT_TRUE(by_path.count("angularVelocity"));
  EXPECT_FALSE(by_path["angularVelocity"]->input);
  ASSERT_EQ(by_path["angularVelocity"]->source_kind, sn::SignalSource::Mate);
  EXPECT_EQ(system_.mates[by_path["angularVelocity"]->source].path, "hinge");
  ASSERT_TRUE(by_path.count("hinge.angle_output"));  // added by the bundle, disabled by default
  EXPECT_FALSE(by_path["hinge.angle_output"]->enabled);
}

// Every number the mapping reads is in the system, as the model gives it.
TEST_F(ResolvedSystem, MateAndInteractionParametersAreTyped) {
  ASSERT_TRUE(
      load("Rod is Physics3D.Bodies.RigidBody:\n"
           "    inertia.mass: 1\n"
           "    c is Physics3D.Interactions.MateConnector:\n"
           "        main_axis: Math.Vec3.Z_AXIS()\n"
           "        normal: Math.Vec3.X_AXIS()\n"
           "Scene is Physics3D.System:\n"
           "    w is Physics3D.Interactions.MateConnector:\n"
           "        main_axis: Math.Vec3.Z_AXIS()\n"
           "        normal: Math.Vec3.X_AXIS()\n"
           "    rod is Rod\n"
           "    hinge is Physics3D.Interactions.Hinge:\n"
           "        connectors: [w, rod.c]\n"
           "        enabled: false\n"
           "        friction becomes Physics.Interactions.Dissipation.DryConstantNormalForceFriction:\n"
           "            coefficient: 0.5\n"
           "            normal_force: 4\n"
           "    lock is Physics3D.Interactions.Lock:\n"
           "        connectors: [w, rod.c]\n"
           "        flexibility becomes Physics3D.Interactions.Flexibility.LinearElasticLockFlexibility:\n"
           "            default_stiffness: 2000\n"
           "    range is Physics3D.Interactions.RotationalRange:\n"
           "        connectors: [w, rod.c]\n"
           "        start: -0.5\n"
           "        end: 0.25\n"
           "    motor is Physics3D.Interactions.RotationalVelocityMotor:\n"
           "        connectors: [w, rod.c]\n"
           "        target_speed: 2\n"
           "        max_effort: 7\n"))
      << all_diags();
  system_ = sn::resolve_system(*evaluator_, root_, sink_);
  ASSERT_EQ(system_.mates.size(), 2u);
  const sn::Mate& hinge = system_.mates[0];
  EXPECT_FALSE(hinge.enabled);
  // The bundles give every mate a default (rigid) flexibility model.
  EXPECT_NE(hinge.flexibility_type.find(".Default"), std::string::npos) << hinge.flexibility_type;
  for (const sn::DofCompliance& dof : hinge.dofs) EXPECT_EQ(dof.stiffness, 0.0);
  EXPECT_EQ(hinge.friction.type, "Physics.Interactions.Dissipation.DryConstantNormalForceFriction");
  EXPECT_EQ(hinge.friction.coefficient, 0.5);
  EXPECT_EQ(hinge.friction.normal_force, 4.0);
  const sn::Mate& lock = system_.mates[1];
  EXPECT_TRUE(lock.enabled);
  EXPECT_TRUE(lock.flexible);
  EXPECT_EQ(lock.flexibility_type, "Physics3D.Interactions.Flexibility.LinearElasticLockFlexibility");
  for (const sn::DofCompliance& dof : lock.dofs) EXPECT_EQ(dof.stiffness, 2000.0);
  ASSERT_EQ(system_.interactions.size(), 2u);
  const sn::Interaction1D& range = system_.interactions[0];
  EXPECT_EQ(range.kind, sn::Interaction1D::Kind::RotationalRange);
  EXPECT_EQ(range.start, -0.5);
  EXPECT_EQ(range.end, 0.25);
  const sn::Interaction1D& motor = system_.interactions[1];
  EXPECT_EQ(motor.kind, sn::Interaction1D::Kind::RotationalVelocityMotor);
  EXPECT_EQ(motor.mate, 0);
  EXPECT_EQ(motor.target_speed, std::optional<double>(2.0));
  EXPECT_EQ(motor.max_effort, 7.0);
  EXPECT_EQ(motor.min_effort, -sn::kInf);
  EXPECT_EQ(system_.gravity.kind, sn::Gravity::Kind::Standard);
}

TEST_F(ResolvedSystem, ContactModelsShareMaterialIndicesWithGeometries) {
  system_of("material_scene.openplx");
  ASSERT_FALSE(system_.contact_models.empty());
  for (const sn::ContactModel& cm : system_.contact_models) {
    ASSERT_GE(cm.material1, 0) << cm.path;
    ASSERT_GE(cm.material2, 0) << cm.path;
    EXPECT_LT(cm.material1, static_cast<int>(system_.materials.size()));
    // Each material a contact model names is the very material some geometry has.
    bool found = false;
    for (const sn::Geometry& g : system_.geometries) found = found || g.material == cm.material1;
    EXPECT_TRUE(found) << cm.path;
  }
  const auto box2 = std::find_if(system_.contact_models.begin(), system_.contact_models.end(),
                                 [](const sn::ContactModel& cm) { return cm.path == "GroundBox2CM"; });
  ASSERT_NE(box2, system_.contact_models.end());
  EXPECT_TRUE(box2->enabled);
  EXPECT_EQ(box2->friction, 0.5);
  EXPECT_EQ(box2->normal_restitution, 0.4);
  EXPECT_EQ(box2->tangential_restitution, 0.3);
}

}  // namespace
