// Meshes given by vertices become inline MJCF meshes whose mass MuJoCo computes from their volume; mate
// flexibility that MuJoCo cannot express is reported at the mate, never dropped silently.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include "tests/support/mjcf_fixture.h"
#include "tests/support/soft_lock_scene.h"

namespace {

namespace fe = openplx::frontend;
using Meshes = openplx::testing::MjcfTest;

// A 1 kg, 1 m rod hanging from a hinge about y at its top; tests append lines to the hinge's block.
const char* const kRodOnHinge =
    "Rod is Physics3D.Bodies.RigidBody:\n"
    "    inertia.mass: 1\n"
    "    geometry is Physics3D.Geometries.Box:\n"
    "        size: {0.05, 0.05, 1}\n"
    "    top is Physics3D.Interactions.MateConnector:\n"
    "        position.z: 0.5\n"
    "        main_axis: Math.Vec3.Y_AXIS()\n"
    "        normal: Math.Vec3.Z_AXIS()\n"
    "Scene is Physics3D.System:\n"
    "    pivot is Physics3D.Interactions.MateConnector:\n"
    "        main_axis: Math.Vec3.Y_AXIS()\n"
    "        normal: Math.Vec3.Z_AXIS()\n"
    "    rod is Rod\n"
    "    hinge is Physics3D.Interactions.Hinge:\n"
    "        connectors: [pivot, rod.top]\n";

// A 0.2 m cube given by its 8 corners, uniform density 1000 kg/m^3 (the default): 8 kg, I = m a^2 / 6.
TEST_F(Meshes, ConvexMeshByVerticesHasTheMassOfItsVolume) {
  ASSERT_TRUE(
      load("Cube is Physics3D.Bodies.RigidBody:\n"
           "    hull is Physics3D.Geometries.ConvexMesh:\n"
           "        vertices: [{-0.1, -0.1, -0.1}, {0.1, -0.1, -0.1}, {-0.1, 0.1, -0.1}, {0.1, 0.1, -0.1},\n"
           "                   {-0.1, -0.1, 0.1}, {0.1, -0.1, 0.1}, {-0.1, 0.1, 0.1}, {0.1, 0.1, 0.1}]\n"
           "Scene is Physics3D.System:\n"
           "    cube is Cube\n"))
      << all_diags();
  const std::string path = emit("cube");
  EXPECT_FALSE(sink_.has_errors()) << all_diags();
  accept_all_diags();
  mjModel* m = load_mujoco(path);
  ASSERT_NE(m, nullptr);
  const int cube = mj_name2id(m, mjOBJ_BODY, "cube");
  // MuJoCo keeps mesh vertices in single precision: relative errors near 1e-7.
  EXPECT_NEAR(m->body_mass[cube], 8.0, 8.0 * 1e-6);
  EXPECT_NEAR(m->body_inertia[3 * cube], 8.0 * 0.04 / 6, 8.0 * 0.04 / 6 * 1e-6);
  EXPECT_EQ(m->nmesh, 1);
  mj_deleteModel(m);
}

// A TriMesh keeps its triangles but collides as its convex hull: said once, at the geometry.
TEST_F(Meshes, TriMeshWarnsThatItCollidesAsItsHull) {
  ASSERT_TRUE(
      load("Tet is Physics3D.Bodies.RigidBody:\n"
           "    shape is Physics3D.Geometries.TriMesh:\n"
           "        vertices: [{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}]\n"
           "        indices: [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]\n"
           "Scene is Physics3D.System:\n"
           "    tet is Tet\n"))
      << all_diags();
  const std::string path = emit("tet");
  expect_diag_containing(fe::DiagCode::MjcfUnmapped, "`tet.shape` is a triangle mesh");
  mjModel* m = load_mujoco(path);
  ASSERT_NE(m, nullptr);
  // Volume 1/6 m^3 at 1000 kg/m^3 (single-precision vertices).
  EXPECT_NEAR(m->body_mass[mj_name2id(m, mjOBJ_BODY, "tet")], 1000.0 / 6, 1000.0 / 6 * 1e-6);
  mj_deleteModel(m);
}

TEST_F(Meshes, TooFewVerticesAreLeftOutWithAWarning) {
  ASSERT_TRUE(
      load("Flat is Physics3D.Bodies.RigidBody:\n"
           "    inertia.mass: 1\n"
           "    shape is Physics3D.Geometries.ConvexMesh:\n"
           "        vertices: [{0, 0, 0}, {1, 0, 0}, {0, 1, 0}]\n"
           "Scene is Physics3D.System:\n"
           "    flat is Flat\n"))
      << all_diags();
  emit("flat");
  expect_diag_containing(fe::DiagCode::MjcfUnmapped, "`flat.shape.vertices` has fewer than 4 points");
  accept_all_diags();
}

TEST_F(Meshes, MateFlexibilityIsReportedAtTheMate) {
  ASSERT_TRUE(load(
      kRodOnHinge +
      std::string(
          "        flexibility becomes Physics3D.Interactions.Flexibility.LinearElasticHingeFlexibility\n")))
      << all_diags();
  emit("soft");
  EXPECT_EQ(
      expect_diag_containing(fe::DiagCode::MjcfUnmapped, "`hinge.flexibility`"),
      "`hinge.flexibility` (Physics3D.Interactions.Flexibility.LinearElasticHingeFlexibility) has no MuJoCo "
      "2.2.2 mapping here; the joint's constrained directions are rigid");
  accept_all_diags();
}

// A hinge with dry friction at a constant normal force holds a pendulum whose gravity torque stays below the
// friction limit: 0.5 x 4 = 2 N m against 1 kg x 9.81 x 0.5 m x sin(0.3) = 1.45 N m. Normal-force-dependent
// friction is warned.
TEST_F(Meshes, ConstantNormalForceFrictionBecomesFrictionloss) {
  for (const bool constant : {true, false}) {
    SCOPED_TRACE(constant ? "constant normal force" : "cone friction");
    const std::string friction =
        constant ? "        friction becomes Physics.Interactions.Dissipation."
                   "DryConstantNormalForceFriction:\n"
                   "            coefficient: 0.5\n"
                   "            normal_force: 4\n"
                 : "        friction becomes Physics.Interactions.Dissipation.DryConeFriction\n";
    ASSERT_TRUE(load(kRodOnHinge + std::string("        initial_angle: 0.3\n") + friction)) << all_diags();
    const std::string path = emit(constant ? "friction" : "cone");
    if (!constant) {
      expect_diag_containing(fe::DiagCode::MjcfUnmapped,
                             "`hinge.friction` (Physics.Interactions.Dissipation.DryConeFriction)");
      continue;
    }
    accept_all_diags();
    mjModel* m = load_mujoco(path);
    ASSERT_NE(m, nullptr);
    EXPECT_DOUBLE_EQ(m->dof_frictionloss[0], 2.0);
    mjData* d = mj_makeData(m);
    for (int k = 0; k < 500; ++k) mj_step(m, d);
    // Held by friction: it creeps at most by the soft friction constraint's give.
    EXPECT_NEAR(d->qpos[0], 0.3, 0.01);
    mj_deleteData(d);
    mj_deleteModel(m);
  }
}

// A flexible Lock closing a loop becomes a weld whose solref makes it the physical spring it is: a 2 kg box
// on a vertical slide (the tree joint) hangs from a Lock of stiffness 2000 N/m to the world and settles
// m g / k = 9.81 mm low. MuJoCo's row behaves as k = ks / ((1 - d) dA) by construction of the solref (the
// mapping guide measured that law to 0.1 %); the lightly damped spring (default damping: relaxation time of
// two steps) has settled after 5 s to well within the 2 % allowed here.
TEST_F(Meshes, FlexibleLoopClosureIsAPhysicalSpring) {
  ASSERT_TRUE(load(openplx::testing::kSoftLockScene)) << all_diags();
  const std::string path = emit("soft_lock");
  EXPECT_FALSE(sink_.has_errors()) << all_diags();
  accept_all_diags();
  EXPECT_NE(xml_.find("<weld name=\"lock\""), std::string::npos) << xml_;
  EXPECT_NE(xml_.find("solimp=\"0.05 0.05 0.001 0.5 2\""), std::string::npos) << xml_;
  mjModel* m = load_mujoco(path);
  ASSERT_NE(m, nullptr);
  mjData* d = mj_makeData(m);
  while (d->time < 5.0) mj_step(m, d);
  const double expected = -2 * 9.81 / 2000;
  EXPECT_NEAR(d->qpos[0], expected, 0.02 * std::abs(expected));
  mj_deleteData(d);
  mj_deleteModel(m);
}

}  // namespace
