// SNAP on the seed's three-level example, the worked examples of ../shared/spec/snap.md, chains, trees, a
// closed four-bar linkage and nested systems; and, for every corpus model, that every mate's connector frames
// meet after SNAP up to the mate's free degrees of freedom.
#include "snap/snap.h"

#include <cmath>
#include <filesystem>

#include "snap/resolve_system.h"
#include "tests/support/eval_fixture.h"

namespace {

namespace fe = openplx::frontend;
namespace sn = openplx::snap;
namespace fs = std::filesystem;

constexpr double kTol = 1e-9;

class Snap : public openplx::testing::EvalTest {
 protected:
  bool assemble(const std::string& text, const char* model = nullptr) {
    if (!load(text, model)) return false;
    return assemble_loaded();
  }
  bool assemble_file(const std::string& path, const char* model = nullptr,
                     const std::vector<std::string>& bundles = {}) {
    if (!load_file(path, model, bundles)) return false;
    return assemble_loaded();
  }
  bool assemble_loaded() {
    const size_t errors = sink_.error_count();
    system_ = sn::resolve_system(*evaluator_, root_, sink_);
    result_ = sn::run_snap(system_, sink_);
    return sink_.error_count() == errors;
  }
  int node(const std::string& path) const {
    for (size_t i = 0; i < system_.nodes.size(); ++i) {
      if (system_.nodes[i].path == path) return static_cast<int>(i);
    }
    ADD_FAILURE() << "no node " << path;
    return 0;
  }
  int connector(const std::string& path) const {
    for (size_t i = 0; i < system_.connectors.size(); ++i) {
      if (system_.connectors[i].path == path) return static_cast<int>(i);
    }
    ADD_FAILURE() << "no connector " << path;
    return 0;
  }
  const sn::Transform& world(const std::string& path) { return result_.node_world[node(path)]; }
  const sn::Transform& connector_world(const std::string& path) {
    return result_.connector_world[connector(path)];
  }
  // Every mate meets: a mate that placed a node exactly at its initial values, the others up to their free
  // degrees of freedom.
  void expect_all_mates_meet() {
    for (size_t m = 0; m < system_.mates.size(); ++m) {
      const sn::Mate& mate = system_.mates[m];
      if (!mate.enable_snap || mate.connectors[0] < 0 || mate.connectors[1] < 0) continue;
      const sn::Transform& f0 = result_.connector_world[mate.connectors[0]];
      const sn::Transform& f1 = result_.connector_world[mate.connectors[1]];
      const sn::Residual r = sn::mate_residual(mate, f0, f1);
      EXPECT_LE(r.distance, kTol) << mate.path;
      EXPECT_LE(r.angle, kTol) << mate.path;
      const bool placed = std::find(result_.placed_by.begin(), result_.placed_by.end(),
                                    static_cast<int>(m)) != result_.placed_by.end();
      if (placed) {
        // frame1 = frame0 ∘ J exactly (initial values honoured)
        const sn::Transform expected = openplx::natives::affine_compose(f0, sn::joint_offset(mate));
        EXPECT_LE((expected.position - f1.position).norm(), kTol) << mate.path;
        EXPECT_LE(expected.rotation.angularDistance(f1.rotation), kTol) << mate.path;
      }
    }
  }
  static void expect_near(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tol = kTol) {
    EXPECT_LE((a - b).norm(), tol) << a.transpose() << " vs " << b.transpose();
  }
  static void expect_rotation(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b, double tol = kTol) {
    EXPECT_LE(a.angularDistance(b), tol) << a.coeffs().transpose() << " vs " << b.coeffs().transpose();
  }

  sn::ResolvedSystem system_;
  sn::SnapResult result_;
};

const fs::path kSeedSnap = fs::path(OPENPLX_TEST_DATA_DIR) / "seed_snippets/01_ThreeLevelSnap.openplx";

// The seed's three-level example: in each variant exactly one transform on the lock's chain is undefined, and
// that is the one the pseudocode moves.
TEST_F(Snap, SeedThreeLevelExampleMovesThePseudocodesTransform) {
  const std::pair<const char*, const char*> cases[] = {
      {"SnapRod", "rod_system.rod_system.rod"},
      {"SnapRodParent", "rod_system.rod_system"},
      {"SnapRodParentParent", "rod_system"},
  };
  for (const auto& [model, moved] : cases) {
    SCOPED_TRACE(model);
    ASSERT_TRUE(assemble_file(kSeedSnap.string(), model)) << all_diags();
    const sn::Transform& rod = connector_world("rod_system.rod_system.rod.connector");
    const sn::Transform& wc = connector_world("world_connector");
    expect_near(rod.position, wc.position);
    expect_rotation(rod.rotation, wc.rotation);
    for (const sn::FrameNode& n : system_.nodes) {
      const bool placed = result_.placed_by[&n - system_.nodes.data()] >= 0;
      EXPECT_EQ(placed, n.path == moved) << n.path;
    }
    expect_all_mates_meet();
  }
  accept_all_diags();  // the 0.17.8 names warn; covered by seed_conformance_test
}

// With no transform defined, SNAP forces the rod and its parent to the identity and moves the top system.
TEST_F(Snap, SeedWorldModelForcesInnerTransformsThenMovesTheTop) {
  ASSERT_TRUE(assemble_file(kSeedSnap.string(), "World")) << all_diags();
  EXPECT_TRUE(result_.forced[node("rod_system.rod_system.rod")]);
  EXPECT_TRUE(result_.forced[node("rod_system.rod_system")]);
  EXPECT_GE(result_.placed_by[node("rod_system")], 0);
  expect_all_mates_meet();
  accept_all_diags();
}

const char* kExampleA =
    "Scene is Physics3D.System:\n"
    "    world_mc is Physics3D.Interactions.MateConnector:\n"
    "        main_axis: Math.Vec3.Z_AXIS()\n"
    "        normal: Math.Vec3.X_AXIS()\n"
    "    body is Physics3D.Bodies.RigidBody:\n"
    "        mc is Physics3D.Interactions.MateConnector:\n"
    "            position: Math.Vec3.from_xyz(0, 0, 0.5)\n"
    "            main_axis: Math.Vec3.Z_AXIS()\n"
    "            normal: Math.Vec3.X_AXIS()\n"
    "    hinge is Physics3D.Interactions.Hinge:\n"
    "        initial_angle: THETA\n"
    "        connectors: [world_mc, body.mc]\n";

std::string with_theta(const char* text, const std::string& theta) {
  std::string out = text;
  out.replace(out.find("THETA"), 5, theta);
  return out;
}

TEST_F(Snap, SpecExampleAHingeAboutZ) {
  ASSERT_TRUE(assemble(with_theta(kExampleA, "0.7"))) << all_diags();
  expect_near(world("body").position, {0, 0, -0.5});
  expect_rotation(world("body").rotation,
                  Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ())));
  expect_all_mates_meet();
}

const char* kExampleB =
    "Scene is Physics3D.System:\n"
    "    world_mc is Physics3D.Interactions.MateConnector:\n"
    "        main_axis: Math.Vec3.Y_AXIS()\n"
    "        normal: Math.Vec3.X_AXIS()\n"
    "    body is Physics3D.Bodies.RigidBody:\n"
    "        mc is Physics3D.Interactions.MateConnector:\n"
    "            position: {0, 0, 0.5}\n"
    "            main_axis: Math.Vec3.Y_AXIS()\n"
    "            normal: Math.Vec3.Z_AXIS()\n"
    "    hinge is Physics3D.Interactions.Hinge:\n"
    "        initial_angle: THETA\n"
    "        connectors: [world_mc, body.mc]\n";

TEST_F(Snap, SpecExampleBPendulumAboutY) {
  ASSERT_TRUE(assemble(with_theta(kExampleB, "0"))) << all_diags();
  expect_near(world("body").position, {-0.5, 0, 0});
  expect_rotation(world("body").rotation,
                  Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY())));
  expect_all_mates_meet();
}

TEST_F(Snap, SpecExampleBAtQuarterTurn) {
  ASSERT_TRUE(assemble(with_theta(kExampleB, "Math.PI / 2"))) << all_diags();
  expect_near(world("body").position, {0, 0, 0.5});
  expect_rotation(world("body").rotation,
                  Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY())));
  expect_all_mates_meet();
}

const char* kExampleC =
    "Rod is Physics3D.Bodies.RigidBody:\n"
    "    mc is Physics3D.Interactions.MateConnector:\n"
    "        position: {0, 0, 0.5}\n"
    "        main_axis: Math.Vec3.Z_AXIS()\n"
    "        normal: Math.Vec3.X_AXIS()\n"
    "RodParent is Physics3D.System:\n"
    "    rod is Rod\n"
    "RodParentParent is Physics3D.System:\n"
    "    rod_parent is RodParent\n"
    "EXTRA"
    "Scene is Physics3D.System:\n"
    "    world_mc is Physics3D.Interactions.MateConnector:\n"
    "        main_axis: Math.Vec3.Z_AXIS()\n"
    "        normal: Math.Vec3.X_AXIS()\n"
    "    top is RodParentParent\n"
    "    hinge is Physics3D.Interactions.Hinge:\n"
    "        connectors: [world_mc, top.rod_parent.rod.mc]\n"
    "        initial_angle: 0.3\n";

std::string example_c(const std::string& extra) {
  std::string out = kExampleC;
  out.replace(out.find("EXTRA"), 5, extra);
  return out;
}

TEST_F(Snap, SpecExampleCMovesTheTopSystem) {
  ASSERT_TRUE(assemble(example_c(""))) << all_diags();
  const Eigen::Quaterniond rz(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  expect_near(system_.nodes[node("top")].local.position, {0, 0, -0.5});
  expect_rotation(system_.nodes[node("top")].local.rotation, rz);
  EXPECT_TRUE(result_.forced[node("top.rod_parent.rod")]);
  EXPECT_TRUE(result_.forced[node("top.rod_parent")]);
  expect_all_mates_meet();
}

TEST_F(Snap, SpecExampleCVariantWithADefinedMiddleSystem) {
  ASSERT_TRUE(assemble(example_c("    rod_parent.local_transform.position: {1, 0, 0}\n"))) << all_diags();
  const Eigen::Quaterniond rz(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  expect_near(system_.nodes[node("top")].local.position, rz * Eigen::Vector3d(-1, 0, -0.5));
  expect_near(world("top.rod_parent.rod").position, rz * Eigen::Vector3d(0, 0, -0.5));
  expect_all_mates_meet();
}

// A link with a hinge connector at each end, 1 m apart along z.
const char* kLink =
    "Link is Physics3D.Bodies.RigidBody:\n"
    "    bottom is Physics3D.Interactions.MateConnector:\n"
    "        main_axis: Math.Vec3.Y_AXIS()\n"
    "        normal: Math.Vec3.Z_AXIS()\n"
    "    top is Physics3D.Interactions.MateConnector:\n"
    "        position: {0, 0, 1}\n"
    "        main_axis: Math.Vec3.Y_AXIS()\n"
    "        normal: Math.Vec3.Z_AXIS()\n";

TEST_F(Snap, ChainDeclaredLeafFirstStillAssembles) {
  ASSERT_TRUE(assemble(std::string(kLink) + "Arm is Physics3D.System:\n"
                                            "    base is Physics3D.Interactions.MateConnector:\n"
                                            "        main_axis: Math.Vec3.Y_AXIS()\n"
                                            "        normal: Math.Vec3.Z_AXIS()\n"
                                            "    a is Link\n"
                                            "    b is Link\n"
                                            "    c is Link\n"
                                            "    h3 is Physics3D.Interactions.Hinge:\n"
                                            "        connectors: [b.top, c.bottom]\n"
                                            "    h2 is Physics3D.Interactions.Hinge:\n"
                                            "        connectors: [a.top, b.bottom]\n"
                                            "        initial_angle: Math.PI / 2\n"
                                            "    h1 is Physics3D.Interactions.Hinge:\n"
                                            "        connectors: [base, a.bottom]\n"))
      << all_diags();
  expect_near(world("a").position, {0, 0, 0});
  expect_near(world("b").position, {0, 0, 1});
  // h2 turns b by +90 degrees about y (right-handed): b's top ends at (1, 0, 1).
  expect_near(connector_world("b.top").position, {1, 0, 1});
  expect_near(world("c").position, {1, 0, 1});
  expect_all_mates_meet();
}

TEST_F(Snap, TreeOfBodiesOnOneBase) {
  ASSERT_TRUE(assemble(std::string(kLink) +
                       "Tree is Physics3D.System:\n"
                       "    trunk is Link\n"
                       "    left is Link\n"
                       "    right is Link\n"
                       "    root_hinge is Physics3D.Interactions.Hinge:\n"
                       "        connectors: [Physics3D.Interactions.World, trunk.bottom]\n"
                       "    left_hinge is Physics3D.Interactions.Hinge:\n"
                       "        connectors: [trunk.top, left.bottom]\n"
                       "        initial_angle: 0.5\n"
                       "    right_hinge is Physics3D.Interactions.Hinge:\n"
                       "        connectors: [trunk.top, right.bottom]\n"
                       "        initial_angle: -0.5\n"))
      << all_diags();
  expect_near(connector_world("left.bottom").position, connector_world("trunk.top").position);
  expect_near(connector_world("right.bottom").position, connector_world("trunk.top").position);
  // Both branches are 1 m long and open 0.5 - (-0.5) = 1 rad apart about the shared hinge axis.
  const Eigen::Vector3d fork = connector_world("trunk.top").position;
  const Eigen::Vector3d l = connector_world("left.top").position - fork;
  const Eigen::Vector3d r = connector_world("right.top").position - fork;
  EXPECT_NEAR(l.norm(), 1.0, kTol);
  EXPECT_NEAR(r.norm(), 1.0, kTol);
  EXPECT_NEAR(std::acos(l.dot(r)), 1.0, 1e-7);  // acos loses digits near 1; 1e-7 rad is still exact enough
  expect_all_mates_meet();
}

// A parallelogram four-bar: ground 1 m wide, cranks 1 m tall. Three hinges place the bars; the fourth closes
// the loop and must already meet.
TEST_F(Snap, ClosedFourBarLinkageMeetsAtEveryHinge) {
  ASSERT_TRUE(assemble(std::string(kLink) + "Coupler is Physics3D.Bodies.RigidBody:\n"
                                            "    left is Physics3D.Interactions.MateConnector:\n"
                                            "        main_axis: Math.Vec3.Y_AXIS()\n"
                                            "        normal: Math.Vec3.Z_AXIS()\n"
                                            "    right is Physics3D.Interactions.MateConnector:\n"
                                            "        position: {1, 0, 0}\n"
                                            "        main_axis: Math.Vec3.Y_AXIS()\n"
                                            "        normal: Math.Vec3.Z_AXIS()\n"
                                            "FourBar is Physics3D.System:\n"
                                            "    ground_left is Physics3D.Interactions.MateConnector:\n"
                                            "        main_axis: Math.Vec3.Y_AXIS()\n"
                                            "        normal: Math.Vec3.Z_AXIS()\n"
                                            "    ground_right is Physics3D.Interactions.MateConnector:\n"
                                            "        position: {1, 0, 0}\n"
                                            "        main_axis: Math.Vec3.Y_AXIS()\n"
                                            "        normal: Math.Vec3.Z_AXIS()\n"
                                            "    crank is Link\n"
                                            "    rocker is Link\n"
                                            "    coupler is Coupler\n"
                                            "    h1 is Physics3D.Interactions.Hinge:\n"
                                            "        connectors: [ground_left, crank.bottom]\n"
                                            "        initial_angle: 0.4\n"
                                            "    h2 is Physics3D.Interactions.Hinge:\n"
                                            "        connectors: [crank.top, coupler.left]\n"
                                            "        initial_angle: -0.4\n"
                                            "    h3 is Physics3D.Interactions.Hinge:\n"
                                            "        connectors: [coupler.right, rocker.top]\n"
                                            "        initial_angle: 0.4\n"
                                            "    h4 is Physics3D.Interactions.Hinge:\n"
                                            "        connectors: [ground_right, rocker.bottom]\n"))
      << all_diags();
  for (const char* pair :
       {"crank.top|coupler.left", "coupler.right|rocker.top", "ground_right|rocker.bottom"}) {
    const std::string p(pair);
    const std::string a = p.substr(0, p.find('|')), b = p.substr(p.find('|') + 1);
    expect_near(connector_world(a).position, connector_world(b).position);
  }
  expect_all_mates_meet();
}

// Nested systems with their own local transforms and system-owned connectors: the body snaps to a connector
// owned by an inner system that is itself placed in the scene.
TEST_F(Snap, NestedSystemsWithOwnTransformsAndSystemConnectors) {
  ASSERT_TRUE(assemble(std::string(kLink) +
                       "Bracket is Physics3D.System:\n"
                       "    local_transform.position: {2, 0, 0}\n"
                       "    local_transform.rotation: Math.Quat.angle_axis(Math.PI / 2, Math.Vec3.Z_AXIS())\n"
                       "    mount is Physics3D.Interactions.MateConnector:\n"
                       "        position: {0, 0, 1}\n"
                       "        main_axis: Math.Vec3.Y_AXIS()\n"
                       "        normal: Math.Vec3.Z_AXIS()\n"
                       "Scene is Physics3D.System:\n"
                       "    bracket is Bracket\n"
                       "    link is Link\n"
                       "    lock is Physics3D.Interactions.Lock:\n"
                       "        connectors: [bracket.mount, link.bottom]\n"))
      << all_diags();
  expect_near(world("bracket").position, {2, 0, 0});
  expect_near(connector_world("bracket.mount").position, {2, 0, 1});
  expect_near(world("link").position, {2, 0, 1});
  // The link stands on the mount, turned with the bracket: its top is 1 m above.
  expect_near(connector_world("link.top").position, {2, 0, 2});
  EXPECT_EQ(result_.placed_by[node("bracket")], -1);  // defined: never moved
  expect_all_mates_meet();
}

TEST_F(Snap, OverDeterminedMateIsAWarningWithItsResidual) {
  ASSERT_TRUE(assemble(std::string(kLink) + "Scene is Physics3D.System:\n"
                                            "    a is Physics3D.Interactions.MateConnector:\n"
                                            "        main_axis: Math.Vec3.Y_AXIS()\n"
                                            "        normal: Math.Vec3.Z_AXIS()\n"
                                            "    b is Physics3D.Interactions.MateConnector:\n"
                                            "        position: {0, 0, 3}\n"
                                            "        main_axis: Math.Vec3.Y_AXIS()\n"
                                            "        normal: Math.Vec3.Z_AXIS()\n"
                                            "    link is Link\n"
                                            "    l1 is Physics3D.Interactions.Lock:\n"
                                            "        connectors: [a, link.bottom]\n"
                                            "    l2 is Physics3D.Interactions.Lock:\n"
                                            "        connectors: [b, link.top]\n"))
      << all_diags();
  EXPECT_EQ(expect_diag(fe::DiagCode::SnapInconsistent, 20, 5),  // kLink is 8 lines
            "mate l2 is over-determined: after SNAP its connectors b and link.top are 2.0 m and 0.0 degrees "
            "apart; the simulation will pull them together");
}

TEST_F(Snap, ParallelNormalIsAnErrorAtTheConnector) {
  EXPECT_FALSE(
      assemble("Scene is Physics3D.System:\n"
               "    bad is Physics3D.Interactions.MateConnector:\n"
               "        main_axis: Math.Vec3.Z_AXIS()\n"
               "        normal: {0, 0, 2}\n"));
  expect_diag_containing(fe::DiagCode::InvalidConnector, "normal must not be parallel");
}

TEST_F(Snap, MateWithOneConnectorIsAnError) {
  EXPECT_FALSE(
      assemble("Scene is Physics3D.System:\n"
               "    c is Physics3D.Interactions.MateConnector\n"
               "    hinge is Physics3D.Interactions.Hinge:\n"
               "        connectors: [c]\n"));
  EXPECT_EQ(expect_diag(fe::DiagCode::InvalidMate, 3, 5), "mate hinge needs exactly two connectors, has 1");
}

// Every model of the corpus: after SNAP every mate meets up to its free degrees of freedom.
class SnapCorpus : public Snap {};

TEST_F(SnapCorpus, EveryMateOfEveryCorpusModelMeets) {
  const fs::path agx = fs::path(OPENPLX_CORPUS_DIR) / "agxunity";
  size_t models = 0, mates = 0;
  for (const auto& entry : fs::directory_iterator(agx)) {
    if (entry.path().extension() != ".openplx") continue;
    const std::string name = entry.path().stem().string();
    if (name == "extended_pendulum_from_agx") continue;  // its AGX import is an error (corpus_eval_test)
    SCOPED_TRACE(name);
    const char* model = name == "simple_lidar" ? "ValidLidar" : nullptr;
    std::vector<std::string> bundles;
    if (name == "use_test_bundle") bundles.push_back((agx / "TestBundle").string());
    ASSERT_TRUE(assemble_file(entry.path().string(), model, bundles)) << all_diags();
    expect_all_mates_meet();
    ++models;
    mates += system_.mates.size();
  }
  EXPECT_EQ(models, 16u);
  EXPECT_GE(mates, 12u);
  accept_all_diags();
}

}  // namespace
