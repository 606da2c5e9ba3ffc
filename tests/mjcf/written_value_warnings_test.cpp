// A value MuJoCo cannot take is warned where the user wrote it: at the assignment's own line and column,
// named as it is written there. A value assigned in a declaration that two instances share (a material, a
// texture, a contact model used twice) is one warning named by that declaration, not one per instance nor
// one named after whichever instance came first. AGX annotations are listed for the models the converted
// root holds only. A metallic map MuJoCo drops leaves the reflectance where the user's own value puts it.
#include <mujoco/mujoco.h>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

// A 4 x 2 RGBA PNG (red), as texture_test.cpp writes it.
const char kPngHex[] =
    "89504e470d0a1a0a0000000d49484452000000040000000208060000007fa87d630000001249444154789c63f8cfc0f01f1933a0"
    "0b"
    "00000f210ff10437c69f0000000049454e44ae426082";

void write_png(const std::string& path) {
  std::string bytes;
  for (size_t k = 0; kPngHex[k] && kPngHex[k + 1]; k += 2)
    bytes.push_back(static_cast<char>(std::stoi(std::string(kPngHex + k, 2), nullptr, 16)));
  std::ofstream(path, std::ios::binary) << bytes;
}

// Line numbers are the test's subject: each line of the file is written on its own line here.
const char kCrates[] =
    "import @\"check.png\" as Checkerboard\n"                                                 // 1
    "const Point is Checkerboard with Visuals.Textures.Sampler, Visuals.Textures.Swizzle:\n"  // 2
    "    filter_mode: Visuals.Textures.FilterMode.Point\n"                                    // 3
    "    wrap_mode: Visuals.Textures.WrapMode.Clamp\n"                                        // 4
    "    swizzle: \"r\"\n"                                                                    // 5
    "    offset_u: 0.5\n"                                                                     // 6
    "const Shine is Checkerboard\n"                                                           // 7
    "Paint is Visuals.Materials.Material with Visuals.Materials.SurfaceFeatures.BaseColor, "
    "Visuals.Materials.SurfaceFeatures.Metallic:\n"             // 8
    "    with Visuals.Materials.SurfaceFeatures.Roughness\n"    // 9
    "    base_color_map: Point\n"                               // 10
    "    metallic_map: Shine\n"                                 // 11
    "    roughness: 0.25\n"                                     // 12
    "    roughness_map: Shine\n"                                // 13
    "const Steel is Physics.Geometries.Material\n"              // 14
    "Grip is Physics.Interactions.SurfaceContact.Model:\n"      // 15
    "    material_1: Steel\n"                                   // 16
    "    material_2: Steel\n"                                   // 17
    "    normal_restitution: 0.5\n"                             // 18
    "    tangential_restitution: 0.2\n"                         // 19
    "Crate is Physics3D.Bodies.RigidBody:\n"                    // 20
    "    .agx_merge_split: true\n"                              // 21
    "    inertia.mass: 1\n"                                     // 22
    "    shape is Physics3D.Geometries.Box:\n"                  // 23
    "        size: {1, 1, 1}\n"                                 // 24
    "        material: Steel\n"                                 // 25
    "    paint is Paint\n"                                      // 26
    "    look is Visuals.Geometries.Box:\n"                     // 27
    "        size: {1, 1, 1}\n"                                 // 28
    "        material: paint\n"                                 // 29
    "Unused is Physics3D.System:\n"                             // 30
    "    .agx_solver: 1\n"                                      // 31
    "Scene is Physics3D.System:\n"                              // 32
    "    a is Crate\n"                                          // 33
    "    b is Crate:\n"                                         // 34
    "        kinematics.local_transform.position: {3, 0, 0}\n"  // 35
    "    grip_a is Grip\n"                                      // 36
    "    grip_b is Grip\n";                                     // 37

struct Converted {
  int status;
  std::string errors, xml;
};

Converted convert(const openplx::testing::ScratchDir& dir, const std::string& text) {
  write_png((dir / "check.png").string());
  std::ofstream(dir / "crates.openplx") << text;
  std::ostringstream out, errors;
  Converted c;
  c.status = openplx::cli::run({(dir / "crates.openplx").string(), "-o", (dir / "crates.xml").string()}, out,
                               errors);
  c.errors = errors.str();
  c.xml = (dir / "crates.xml").string();
  return c;
}

size_t count(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST(WrittenValueWarnings, EachAtItsAssignmentOnceNamedByTheSharedDeclaration) {
  const openplx::testing::ScratchDir dir;
  const Converted c = convert(dir, kCrates);
  ASSERT_EQ(c.status, 0) << c.errors;
  const std::string file = (dir / "crates.openplx").string();
  const std::string expected[] = {
      file +
          ":3:5: warning: `Point.filter_mode` has no MuJoCo counterpart (textures are filtered linearly, "
          "mipmapped); `Paint.base_color_map` is filtered linearly [mjcf-unmapped]",
      file +
          ":4:5: warning: `Point.wrap_mode` has no MuJoCo counterpart (textures repeat); "
          "`Paint.base_color_map` repeats [mjcf-unmapped]",
      file +
          ":5:5: warning: `Point.swizzle` (\"r\") has no MuJoCo counterpart; all channels of "
          "`Paint.base_color_map` were used [mjcf-unmapped]",
      file +
          ":6:5: warning: `Point.offset_u` has no MuJoCo counterpart (textures have no offset); "
          "`Paint.base_color_map` starts at 0 [mjcf-unmapped]",
      file + ":11:5: warning: `Paint.metallic_map` is a texture MuJoCo 2.2.2 materials have no slot for",
      file + ":13:5: warning: `Paint.roughness_map` is a texture MuJoCo 2.2.2 materials have no slot for",
      file +
          ":18:5: warning: `Grip.normal_restitution` has no MuJoCo 2.2.2 parameter; its contacts are "
          "emitted without restitution [mjcf-unmapped]",
      file + ":19:5: warning: `Grip.tangential_restitution` has no MuJoCo 2.2.2 parameter",
      file +
          ":21:5: warning: AGX annotation `.agx_merge_split` has no MuJoCo counterpart; it was ignored "
          "[agx-annotation]"};
  for (const std::string& warning : expected)
    EXPECT_EQ(count(c.errors, warning), 1u) << warning << "\n" << c.errors;
  // Nothing else at those lines (no second instance's copy), nothing of the model the root does not use,
  // and nothing named after an instance.
  for (const char* line : {":3:", ":4:", ":5:", ":6:", ":11:", ":13:", ":18:", ":19:", ":21:"})
    EXPECT_EQ(count(c.errors, file + line), 1u) << line << "\n" << c.errors;
  EXPECT_EQ(c.errors.find(":31:5:"), std::string::npos) << c.errors;
  EXPECT_EQ(c.errors.find("agx_solver"), std::string::npos) << c.errors;
  for (const char* instance : {"`a.", "`b.", "`grip_a.", "`grip_b."})
    EXPECT_EQ(c.errors.find(instance), std::string::npos) << instance << "\n" << c.errors;
}

// The metallic map is dropped; `metallic` is the Metallic trait's default factor 1, which only scales the
// map: the reflectance stays MuJoCo's default 0 (a factor of 1 alone is a mirror). The roughness map is
// dropped too, but `roughness: 0.25` is the user's: shininess 1 - 0.25. Both crates' materials alike.
TEST(WrittenValueWarnings, DroppedMetallicMapLeavesTheReflectance) {
  const openplx::testing::ScratchDir dir;
  const Converted c = convert(dir, kCrates);
  ASSERT_EQ(c.status, 0) << c.errors;
  EXPECT_NE(
      c.errors.find("the reflectance is MuJoCo's default (0), not the Metallic trait's default factor 1"),
      std::string::npos)
      << c.errors;
  EXPECT_NE(c.errors.find("`roughness` alone sets the shininess"), std::string::npos) << c.errors;
  char error[1000] = "";
  mjModel* m = mj_loadXML(c.xml.c_str(), nullptr, error, sizeof(error));
  ASSERT_NE(m, nullptr) << error;
  ASSERT_EQ(m->nmat, 3);  // the model's two, then the collision geometry's default (viewer_defaults.h)
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(m->mat_reflectance[k], 0.0f);
    EXPECT_FLOAT_EQ(m->mat_shininess[k], 0.75f);
    EXPECT_GE(m->mat_texid[k], 0);  // the base colour map is kept
  }
  mj_deleteModel(m);
  // A metallic value the user writes beside the map sets the reflectance alone.
  std::string text = kCrates;
  text.replace(text.find("    metallic_map: Shine\n"), 0, "    metallic: 0.4\n");
  const openplx::testing::ScratchDir other;
  const Converted written = convert(other, text);
  ASSERT_EQ(written.status, 0) << written.errors;
  EXPECT_NE(written.errors.find(":12:5: warning: `Paint.metallic_map` is a texture"), std::string::npos)
      << written.errors;
  EXPECT_NE(written.errors.find("`metallic` alone sets the reflectance"), std::string::npos)
      << written.errors;
  m = mj_loadXML(written.xml.c_str(), nullptr, error, sizeof(error));
  ASSERT_NE(m, nullptr) << error;
  for (int k = 0; k < 2; ++k) EXPECT_FLOAT_EQ(m->mat_reflectance[k], 0.4f);  // the model's two
  mj_deleteModel(m);
}

// A value assigned in the converted root's own model is named by its path from the root, at its line.
TEST(WrittenValueWarnings, TheRootsOwnAssignmentIsNamedByItsPath) {
  const openplx::testing::ScratchDir dir;
  std::string text = kCrates;
  text +=
      "    grip_c is Grip:\n"               // 38
      "        normal_restitution: 0.9\n";  // 39
  const Converted c = convert(dir, text);
  ASSERT_EQ(c.status, 0) << c.errors;
  const std::string file = (dir / "crates.openplx").string();
  EXPECT_EQ(
      count(c.errors, file + ":39:9: warning: `grip_c.normal_restitution` has no MuJoCo 2.2.2 parameter"), 1u)
      << c.errors;
  EXPECT_EQ(count(c.errors, file + ":18:5:"), 1u) << c.errors;  // the two that keep Grip's value
}

// An attribute MuJoCo has no counterpart for, assigned in a contact model two instances share: one warning
// at the assignment, named by the declaration.
TEST(WrittenValueWarnings, UnmappedAttributeOfASharedDeclarationIsNamedByIt) {
  const openplx::testing::ScratchDir dir;
  const Converted c = convert(dir,
                              "const Steel is Physics.Geometries.Material\n"          // 1
                              "Grip is Physics.Interactions.SurfaceContact.Model:\n"  // 2
                              "    with AGX.ContactReductionBinResolution\n"          // 3
                              "    bin_resolution: 2\n"                               // 4
                              "    material_1: Steel\n"                               // 5
                              "    material_2: Steel\n"                               // 6
                              "    normal_restitution: 0\n"                           // 7
                              "    tangential_restitution: 0\n"                       // 8
                              "Ball is Physics3D.Bodies.RigidBody:\n"                 // 9
                              "    inertia.mass: 1\n"                                 // 10
                              "    geometry is Physics3D.Geometries.Sphere:\n"        // 11
                              "        radius: 0.1\n"                                 // 12
                              "        material: Steel\n"                             // 13
                              "Scene is Physics3D.System:\n"                          // 14
                              "    ball is Ball\n"                                    // 15
                              "    grip_a is Grip\n"                                  // 16
                              "    grip_b is Grip\n");                                // 17
  ASSERT_EQ(c.status, 0) << c.errors;
  const std::string file = (dir / "crates.openplx").string();
  EXPECT_EQ(count(c.errors, file + ":4:5: warning: `Grip.bin_resolution` (AGX.ContactReductionBinResolution) "
                                   "has no MuJoCo counterpart here; it was ignored [mjcf-unmapped]"),
            1u)
      << c.errors;
  EXPECT_EQ(count(c.errors, file + ":4:"), 1u) << c.errors;
}

// A value nothing can simulate in a declaration two instances share: one error, named by the declaration.
TEST(WrittenValueWarnings, AnInvalidValueOfASharedDeclarationIsOneError) {
  const openplx::testing::ScratchDir dir;
  const Converted c = convert(dir,
                              "Rod is Physics3D.Bodies.RigidBody:\n"  // 1
                              "    inertia.mass: -1\n"                // 2
                              "Scene is Physics3D.System:\n"          // 3
                              "    left is Rod\n"                     // 4
                              "    right is Rod\n");                  // 5
  EXPECT_EQ(c.status, 1) << c.errors;
  const std::string file = (dir / "crates.openplx").string();
  EXPECT_EQ(count(c.errors, file + ":2:5: error: `Rod.inertia.mass` is -1.0"), 1u) << c.errors;
  EXPECT_EQ(count(c.errors, "is -1"), 1u) << c.errors;
}

}  // namespace
