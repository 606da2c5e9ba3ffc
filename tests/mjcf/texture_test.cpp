// Image textures: `import @"x.png" as T` is a Visuals texture reading the file; a material's base colour map
// becomes a MuJoCo 2-D <texture> the material repeats scale_u x scale_v times, loaded by MuJoCo at the
// image's size. What MuJoCo lacks (other maps, swizzles, filter and wrap modes) is a warning at the user's
// line, never an abort; JPEG (which MuJoCo 2.2.2 cannot read) is an error that says so.
#include <mujoco/mujoco.h>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

// A 4 x 2 RGBA PNG (red), written by hand: signature, IHDR, one zlib IDAT, IEND.
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

std::string scene(const std::string& texture_lines, const std::string& material_lines) {
  return "import @\"check.png\" as Checkerboard\n" + texture_lines +
         "Scene is Physics3D.System:\n"
         "    paint is Visuals.Materials.Material with Visuals.Materials.SurfaceFeatures.BaseColor, "
         "Visuals.Materials.SurfaceFeatures.Metallic:\n" +
         material_lines +
         "    body is Physics3D.Bodies.RigidBody:\n"
         "        inertia.mass: 1\n"
         "        shape is Physics3D.Geometries.Box:\n"
         "            size: {1, 1, 1}\n"
         "        look is Visuals.Geometries.Box:\n"
         "            size: {1, 1, 1}\n"
         "            material: paint\n";
}

struct Converted {
  int status;
  std::string errors, xml;
};

Converted convert(const openplx::testing::ScratchDir& dir, const std::string& text) {
  write_png((dir / "check.png").string());
  std::ofstream(dir / "scene.openplx") << text;
  std::ostringstream out, errors;
  Converted c;
  c.status =
      openplx::cli::run({(dir / "scene.openplx").string(), "-o", (dir / "scene.xml").string()}, out, errors);
  c.errors = errors.str();
  c.xml = (dir / "scene.xml").string();
  return c;
}

TEST(Textures, ImportedPngIsAMaterialTextureAtItsSize) {
  const openplx::testing::ScratchDir dir;
  const Converted c = convert(dir, scene("const Tiled is Checkerboard with Visuals.Textures.Sampler:\n"
                                         "    scale_u: 2\n"
                                         "    scale_v: 3\n",
                                         "        base_color_map: Tiled\n"));
  ASSERT_EQ(c.status, 0) << c.errors;
  EXPECT_EQ(c.errors, "");
  char error[1000] = "";
  mjModel* m = mj_loadXML(c.xml.c_str(), nullptr, error, sizeof(error));
  ASSERT_NE(m, nullptr) << error;
  ASSERT_EQ(m->ntex, 1);
  EXPECT_EQ(m->tex_width[0], 4);
  EXPECT_EQ(m->tex_height[0], 2);
  ASSERT_EQ(m->nmat, 2);  // the model's, then the collision geometry's default (viewer_defaults.h)
  EXPECT_EQ(m->mat_texid[0], 0);
  EXPECT_EQ(m->mat_texrepeat[0], 2.0f);
  EXPECT_EQ(m->mat_texrepeat[1], 3.0f);
  mj_deleteModel(m);
}

TEST(Textures, WhatMuJoCoLacksIsWarnedAtTheUsersLine) {
  const openplx::testing::ScratchDir dir;
  const Converted c = convert(dir, scene("const Point is Checkerboard with Visuals.Textures.Sampler, "
                                         "Visuals.Textures.Swizzle:\n"
                                         "    filter_mode: Visuals.Textures.FilterMode.Point\n"
                                         "    wrap_mode: Visuals.Textures.WrapMode.Clamp\n"
                                         "    swizzle: \"r\"\n"
                                         "const Red is Checkerboard\n",
                                         "        base_color_map: Point\n"
                                         "        metallic_map: Red\n"));
  ASSERT_EQ(c.status, 0) << c.errors;
  const std::string file = (dir / "scene.openplx").string();
  // Each setting at its own assignment in the texture's declaration, named by it (`Point`, which any
  // material may use), with the map it samples; the metallic map at the material's assignment of it.
  for (const std::string& expected :
       {file + ":5:5: warning: `Point.swizzle` (\"r\") has no MuJoCo counterpart; all channels of "
               "`paint.base_color_map` were used",
        file +
            ":3:5: warning: `Point.filter_mode` has no MuJoCo counterpart (textures are filtered linearly, "
            "mipmapped); `paint.base_color_map` is filtered linearly",
        file + ":4:5: warning: `Point.wrap_mode` has no MuJoCo counterpart (textures repeat); "
               "`paint.base_color_map` repeats",
        file + ":10:9: warning: `paint.metallic_map` is a texture MuJoCo 2.2.2 materials have no slot for"}) {
    EXPECT_NE(c.errors.find(expected), std::string::npos) << expected << "\n" << c.errors;
  }
  EXPECT_EQ(c.errors.find(":2:1:"), std::string::npos) << c.errors;  // not at the texture's declaration
  char error[1000] = "";
  mjModel* m = mj_loadXML(c.xml.c_str(), nullptr, error, sizeof(error));
  ASSERT_NE(m, nullptr) << error;
  EXPECT_EQ(m->ntex, 1);  // the base colour map only
  // The dropped metallic map leaves the reflectance at MuJoCo's default: the Metallic trait's factor 1
  // (the user wrote none) only scales the map, and alone would be a mirror.
  ASSERT_EQ(m->nmat, 2);  // the model's, then the collision geometry's default (viewer_defaults.h)
  EXPECT_EQ(m->mat_reflectance[0], 0.0f);
  mj_deleteModel(m);
}

TEST(Textures, JpegIsAnErrorThatSaysWhy) {
  const openplx::testing::ScratchDir dir;
  std::ofstream(dir / "photo.jpg") << "not really a jpeg";
  std::ofstream(dir / "scene.openplx") << "import @\"photo.jpg\" as Photo\nScene is Physics3D.System\n";
  std::ostringstream out, errors;
  EXPECT_NE(
      openplx::cli::run({(dir / "scene.openplx").string(), "-o", (dir / "scene.xml").string()}, out, errors),
      0);
  EXPECT_NE(errors.str().find("MuJoCo 2.2.2 reads PNG textures only"), std::string::npos) << errors.str();
  EXPECT_FALSE(std::ifstream(dir / "scene.xml").good());  // no partial output
}

}  // namespace
