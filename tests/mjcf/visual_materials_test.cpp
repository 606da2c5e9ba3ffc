// Bodies look as their OpenPLX visual materials say: each distinct material a named, prefixed MuJoCo
// <material> with the colour, gloss, reflectance and opacity the model gives, what MuJoCo cannot take warned
// at the user's line.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <fstream>
#include <regex>

#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"

namespace {

using openplx::testing::ScratchDir;

// A red paint and a half see-through blue glass, on two bodies; a third body shares the red paint. The
// glass's alpha map is pixels in the model, which MuJoCo 2.2.2 cannot read.
constexpr const char* kTwoMaterials =
    "RedPaint is Visuals.Materials.Material:\n"                    // 1
    "    with Visuals.Materials.SurfaceFeatures.BaseColor\n"       // 2
    "    with Visuals.Materials.SurfaceFeatures.Roughness\n"       // 3
    "    base_color_tint: {0.8, 0.1, 0.1, 1}\n"                    // 4
    "    roughness: 0.3\n"                                         // 5
    "\n"                                                           // 6
    "BlueGlass is Visuals.Materials.Material:\n"                   // 7
    "    with Visuals.Materials.SurfaceFeatures.BaseColor\n"       // 8
    "    with Visuals.Materials.SurfaceFeatures.Metallic\n"        // 9
    "    with Visuals.Materials.SurfaceFeatures.Transparency\n"    // 10
    "    base_color_tint: {0.1, 0.2, 0.9, 0.8}\n"                  // 11
    "    metallic: 0.7\n"                                          // 12
    "    alpha: 0.5\n"                                             // 13
    "    alpha_map becomes Visuals.Textures.Texture:\n"            // 14
    "        data.width: 1\n"                                      // 15
    "        data.height: 1\n"                                     // 16
    "        data.data: \"/wAA/w==\"\n"                            // 17
    "\n"                                                           // 18
    "Block is Physics3D.Bodies.RigidBody:\n"                       // 19
    "    inertia.mass: 1.0\n"                                      // 20
    "    geometry is Physics3D.Geometries.Box:\n"                  // 21
    "        size: {0.2, 0.2, 0.2}\n"                              // 22
    "\n"                                                           // 23
    "Scene is Physics3D.System:\n"                                 // 24
    "    red_paint is RedPaint\n"                                  // 25
    "    red is Block:\n"                                          // 26
    "        kinematics.local_transform.position: {-0.5, 0, 0}\n"  // 27
    "        look is Visuals.Geometries.Box:\n"                    // 28
    "            size: {0.2, 0.2, 0.2}\n"                          // 29
    "            material: red_paint\n"                            // 30
    "    blue is Block:\n"                                         // 31
    "        kinematics.local_transform.position: {0.5, 0, 0}\n"   // 32
    "        look is Visuals.Geometries.Box:\n"                    // 33
    "            size: {0.2, 0.2, 0.2}\n"                          // 34
    "            material becomes BlueGlass\n"                     // 35
    "    also_red is Block:\n"                                     // 36
    "        kinematics.local_transform.position: {0, 0, 1}\n"     // 37
    "        look is Visuals.Geometries.Box:\n"                    // 38
    "            size: {0.2, 0.2, 0.2}\n"                          // 39
    "            material: red_paint\n";                           // 40

TEST(VisualMaterials, EachBodyWearsItsOwnMaterial) {
  const ScratchDir dir;
  const std::string model = (dir / "two_materials.openplx").string();
  std::ofstream(model) << kTwoMaterials;
  const std::string xml = (dir / "two_materials.xml").string();
  const openplx::testing::Conversion c = openplx::testing::cli({model, "-o", xml, "--prefix", "p/"});
  ASSERT_EQ(c.status, 0) << c.errors;
  char error[1000] = "";
  mjModel* m = mj_loadXML(xml.c_str(), nullptr, error, sizeof(error));
  ASSERT_NE(m, nullptr) << error;
  auto material_of = [&](const char* geom) {
    const int g = mj_name2id(m, mjOBJ_GEOM, geom);
    EXPECT_GE(g, 0) << geom;
    return g < 0 ? -1 : m->geom_matid[g];
  };
  const int red = material_of("p/red.look"), blue = material_of("p/blue.look");
  ASSERT_GE(red, 0);
  ASSERT_GE(blue, 0);
  EXPECT_NE(red, blue);
  // One material for one OpenPLX material instance, whichever body shows it.
  EXPECT_EQ(material_of("p/also_red.look"), red);
  EXPECT_EQ(std::string(mj_id2name(m, mjOBJ_MATERIAL, red)).rfind("p/", 0), 0u);
  EXPECT_EQ(std::string(mj_id2name(m, mjOBJ_MATERIAL, blue)).rfind("p/", 0), 0u);
  // MuJoCo stores floats: 1e-6 is their resolution near 1.
  const float* r = m->mat_rgba + 4 * red;
  const float* b = m->mat_rgba + 4 * blue;
  const float red_rgba[] = {0.8f, 0.1f, 0.1f, 1}, blue_rgba[] = {0.1f, 0.2f, 0.9f, 0.4f};  // 0.8 x alpha 0.5
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(r[k], red_rgba[k], 1e-6) << k;
    EXPECT_NEAR(b[k], blue_rgba[k], 1e-6) << k;
  }
  EXPECT_NEAR(m->mat_shininess[red], 0.7, 1e-6);  // 1 - roughness
  EXPECT_NEAR(m->mat_reflectance[blue], 0.7, 1e-6);
  // The collision boxes stay hidden (group 3) behind the visuals that carry the colour.
  EXPECT_EQ(m->geom_group[mj_name2id(m, mjOBJ_GEOM, "p/red.geometry")], 3);
  mj_deleteModel(m);
  // The alpha map MuJoCo cannot read is warned at the user's file, by name; the alpha factor still holds.
  EXPECT_TRUE(std::regex_search(c.errors, std::regex("two_materials.openplx:[0-9]+:[0-9]+: warning: `[^`]*"
                                                     "alpha_map` is an inline texture")))
      << c.errors;
}

}  // namespace
