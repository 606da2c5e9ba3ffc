// The natives of non-Math bundles, called the way models call them, against hand values.
#include "tests/support/eval_fixture.h"

namespace {

namespace fe = openplx::frontend;

class BundleNatives : public openplx::testing::EvalTest {};

TEST_F(BundleNatives, SymmetricInertiaTensorMirrorsTheOffDiagonals) {
  ASSERT_TRUE(
      load("Root:\n"
           "    t is Math.Matrix3x3: Physics3D.Bodies.Inertia.symmetric_tensor({1, 2, 3}, 0.1, 0.2, 0.3)\n"))
      << all_diags();
  const double expected[3][3] = {{1, 0.1, 0.2}, {0.1, 2, 0.3}, {0.2, 0.3, 3}};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(real("t.e" + std::to_string(r) + std::to_string(c)), expected[r][c]) << r << c;
    }
  }
}

TEST_F(BundleNatives, ColorFromRgbIsOpaque) {
  ASSERT_TRUE(
      load("Root:\n    c is Visuals.Properties.Color: Visuals.Properties.Color.from_rgb(0.25, 0.5, 1)\n"))
      << all_diags();
  EXPECT_EQ(real("c.r"), 0.25);
  EXPECT_EQ(real("c.g"), 0.5);
  EXPECT_EQ(real("c.b"), 1.0);
  EXPECT_EQ(real("c.a"), 1.0);
}

TEST_F(BundleNatives, MaterialIsDefaultUntilItsDensityIsAssigned) {
  ASSERT_TRUE(
      load("const Steel is Physics.Geometries.Material:\n"
           "    density: 7800\n"
           "Root:\n"
           "    plain is Physics.Geometries.Material\n"
           "    a is Bool: plain.is_default_material()\n"
           "    b is Bool: Steel.is_default_material()\n"))
      << all_diags();
  EXPECT_EQ(value("a"), "true");
  EXPECT_EQ(value("b"), "false");
}

TEST_F(BundleNatives, LidarMarshallingCountsBytesPerPoint) {
  ASSERT_TRUE(load(
      "Root:\n"
      "    m is Physics.Signals.Marshalling: Sensors.Signals.LidarOutput.marshalling_from_fields("
      "[Sensors.Signals.LidarOutputField.Position3D_F32, Sensors.Signals.LidarOutputField.Intensity_F32])\n"))
      << all_diags();
  EXPECT_EQ(value("m.size"), "16");  // 3 x 4 bytes of position + 4 bytes of intensity
  EXPECT_EQ(value("m.is_dynamic"), "true");
  EXPECT_EQ(value("m.array_type"), "2");
}

TEST_F(BundleNatives, CeilAndFloor) {
  ASSERT_TRUE(
      load("Root:\n"
           "    a is Real: Math.Functions.ceil(2.1)\n"
           "    b is Real: Math.Functions.floor(-2.1)\n"
           "    teeth is Int: Math.Functions.ceil(1.0 / 0.5)\n"))
      << all_diags();
  EXPECT_EQ(real("a"), 3.0);
  EXPECT_EQ(real("b"), -3.0);
  EXPECT_EQ(value("teeth"), "2");
}

TEST_F(BundleNatives, ShovelTeethComeFromItsCuttingEdge) {
  ASSERT_TRUE(
      load("Root is Physics3D.System:\n"
           "    body is Physics3D.Bodies.RigidBody\n"
           "    shovel is Terrain.Shovel:\n"
           "        body: body\n"
           "        cutting_edge: Math.Line.from_points({-0.6, 0, 0}, {0.6, 0, 0})\n"))
      << all_diags();
  EXPECT_EQ(value("shovel.number_teeth"), "3");  // ceil(1.2 / 0.5)
}

}  // namespace
