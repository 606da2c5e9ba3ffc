// A scene of several converted files is lit like a scene of one: rendered offscreen by MuJoCo 2.2.2 itself
// (offscreen_render.h), the floor of samples/controller/two_carts_scene.xml, whose two cart-poles are
// converted as samples/controller/CMakeLists.txt does, has the colour of the same scene holding one of them,
// and the colour MuJoCo's lighting gives a matte floor under the scene's own light and the headlight.
// OPENPLX_RENDER_DIR=folder keeps the pictures there (PPM) for looking at.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "tests/render/offscreen_render.h"
#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace fs = std::filesystem;
using openplx::testing::OffscreenRenderer;
using openplx::testing::Rendered;
using openplx::testing::ScratchDir;

constexpr int kWidth = 320, kHeight = 240;
// Two levels of 255: the floor's specular highlight (Blinn-Phong, MuJoCo's default shininess 0.5: exponent
// 64, under 0.1 % of the light away from the mirror direction) and rounding to 8 bits.
constexpr double kLevels = 2;

std::string read(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

// The same view for every picture: the headlight shines along it, so it must not move between them.
mjvCamera fixed_camera() {
  mjvCamera camera;
  mjv_defaultCamera(&camera);
  camera.type = mjCAMERA_FREE;
  camera.lookat[2] = 0.3;
  camera.distance = 3;
  camera.azimuth = 90;
  camera.elevation = -30;
  return camera;
}

// What OpenGL's fixed-function lighting, as MuJoCo sets it up, gives a matte horizontal surface of colour
// `rgba` facing up: rgba times the sum of every light's ambient part and its diffuse part times the cosine
// of its incidence, the headlight shining along the camera's view. Directional lights only (no attenuation).
std::vector<double> matte_floor(const mjModel* m, const mjData* d, const float* rgba, const mjvCamera& cam) {
  const double pi = std::acos(-1.0);
  const double view_z = std::sin(cam.elevation * pi / 180);  // the view's vertical component
  double light = 0;
  if (m->vis.headlight.active)
    light += m->vis.headlight.ambient[0] + m->vis.headlight.diffuse[0] * std::max(0.0, -view_z);
  for (int i = 0; i < m->nlight; ++i) {
    EXPECT_TRUE(m->light_directional[i]) << "light " << i << " is not directional";
    light += m->light_ambient[3 * i] + m->light_diffuse[3 * i] * std::max(0.0, -d->light_xdir[3 * i + 2]);
  }
  std::vector<double> colour;
  for (int c = 0; c < 3; ++c) colour.push_back(255 * std::min(1.0, rgba[c] * light));
  return colour;
}

struct Picture {
  Rendered image;
  int floor = -1;  // the floor geom's id
  int lights = 0;
  std::vector<double> matte_floor;  // what the scene's lights give the floor
};

Picture render_scene(OffscreenRenderer& renderer, const fs::path& scene) {
  char error[1000] = "";
  mjModel* m = mj_loadXML(scene.c_str(), nullptr, error, sizeof(error));
  EXPECT_NE(m, nullptr) << scene << ": " << error;
  if (!m) return {};
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  const mjvCamera camera = fixed_camera();
  Picture p;
  p.image = renderer.render(m, d, camera);
  p.floor = mj_name2id(m, mjOBJ_GEOM, "floor");
  p.lights = m->nlight;
  if (p.floor >= 0) p.matte_floor = matte_floor(m, d, m->geom_rgba + 4 * p.floor, camera);
  if (const char* keep = std::getenv("OPENPLX_RENDER_DIR"))
    p.image.write_ppm(
        (fs::path(keep) / (std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
                           "_" + scene.stem().string() + ".ppm"))
            .string());
  mj_deleteData(d);
  mj_deleteModel(m);
  return p;
}

// The pixels showing the floor in both pictures (the second cart and its shadow left out).
std::vector<bool> floor_in_both(const Picture& a, const Picture& b) {
  std::vector<bool> mask(a.image.geom.size());
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = a.image.geom[i] == a.floor && b.image.geom[i] == b.floor;
  return mask;
}

std::string rgb(const std::vector<double>& c) {
  std::ostringstream s;
  s << "(" << c[0] << ", " << c[1] << ", " << c[2] << ")";
  return s.str();
}

class SceneLighting : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string why_not;
    bool no_server = false;
    renderer_ = OffscreenRenderer::open(kWidth, kHeight, why_not, no_server);
    // Only a machine without any X server skips; ./test.sh installs Xvfb, so there it always renders.
    if (!renderer_ && no_server) GTEST_SKIP() << "no OpenGL context to render in: " << why_not;
    ASSERT_TRUE(renderer_) << "no OpenGL context to render in: " << why_not;
  }

  // Both cart-poles converted as samples/controller/CMakeLists.txt does, plus `extra` options, beside
  // the sample's scene and the same scene holding the left one alone.
  void convert_the_sample_scene(const fs::path& dir, const std::vector<std::string>& extra) {
    const std::string model = std::string(OPENPLX_SAMPLES_DIR) + "/cart_pole.openplx";
    for (const auto& [side, y] : {std::pair{"left", "0.3"}, {"right", "-0.3"}}) {
      std::vector<std::string> args{model,
                                    "-o",
                                    (dir / (std::string(side) + "_cart_pole.xml")).string(),
                                    "--prefix",
                                    std::string(side) + "/",
                                    "--no-keyframe",
                                    "--pose",
                                    std::string("0 ") + y + " 0.06"};
      args.insert(args.end(), extra.begin(), extra.end());
      const openplx::testing::Conversion c = openplx::testing::cli(args);
      ASSERT_EQ(c.status, 0) << c.errors;
    }
    const std::string scene = read(fs::path(OPENPLX_SAMPLES_DIR) / "controller/two_carts_scene.xml");
    write(dir / "two_carts_scene.xml", scene);
    std::istringstream lines(scene);
    std::string one, line;
    while (std::getline(lines, line))
      if (line.find("<include file=\"right_cart_pole.xml\"/>") == std::string::npos) one += line + "\n";
    ASSERT_LT(one.size(), scene.size()) << "the right cart's include was not found";
    write(dir / "one_cart_scene.xml", one);
  }

  std::unique_ptr<OffscreenRenderer> renderer_;
};

TEST_F(SceneLighting, TwoIncludedCartPolesLightTheFloorAsOneDoes) {
  const ScratchDir dir;
  convert_the_sample_scene(dir.path(), {});
  const Picture two = render_scene(*renderer_, dir / "two_carts_scene.xml");
  const Picture one = render_scene(*renderer_, dir / "one_cart_scene.xml");
  ASSERT_GE(two.floor, 0);
  ASSERT_GE(one.floor, 0);
  // The scene's own sun, nothing from the included files.
  EXPECT_EQ(two.lights, 1);
  EXPECT_EQ(one.lights, 1);
  const std::vector<bool> mask = floor_in_both(two, one);
  const std::vector<double> floor_two = two.image.median_colour(two.floor, mask);
  const std::vector<double> floor_one = one.image.median_colour(one.floor, mask);
  ASSERT_EQ(floor_two.size(), 3u) << "no pixel shows the floor in both pictures";
  std::cout << "floor: two carts " << rgb(floor_two) << ", one cart " << rgb(floor_one)
            << ", the scene's lights give " << rgb(two.matte_floor) << "\n";
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(floor_two[c], floor_one[c], 1)
        << "two carts " << rgb(floor_two) << ", one " << rgb(floor_one);
    EXPECT_NEAR(floor_two[c], two.matte_floor[c], kLevels)
        << "floor " << rgb(floor_two) << ", the scene's lights give " << rgb(two.matte_floor);
  }
}

// The measurement tells the difference: with a light in every included file (what --no-keyframe gave
// before files made for a scene left lights out), the two-cart floor is far brighter than the one-cart one.
TEST_F(SceneLighting, ALightInEveryIncludedFileAddsUp) {
  const ScratchDir dir;
  convert_the_sample_scene(dir.path(), {"--lights", "on"});
  const Picture two = render_scene(*renderer_, dir / "two_carts_scene.xml");
  const Picture one = render_scene(*renderer_, dir / "one_cart_scene.xml");
  ASSERT_GE(two.floor, 0);
  ASSERT_GE(one.floor, 0);
  EXPECT_EQ(two.lights, 3);
  const std::vector<bool> mask = floor_in_both(two, one);
  const std::vector<double> floor_two = two.image.median_colour(two.floor, mask);
  const std::vector<double> floor_one = one.image.median_colour(one.floor, mask);
  ASSERT_EQ(floor_two.size(), 3u);
  std::cout << "floor: two carts " << rgb(floor_two) << ", one cart " << rgb(floor_one)
            << ", the scene's lights give " << rgb(two.matte_floor) << "\n";
  // Each emitted light adds its diffuse 0.6 straight down: 0.6 x 0.35 x 255 = 54 levels of red.
  EXPECT_GT(floor_two[0] - floor_one[0], 40) << "two carts " << rgb(floor_two) << ", one " << rgb(floor_one);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(floor_two[c], two.matte_floor[c], kLevels);
}

// A model converted on its own keeps its light: on a floor of a scene that brings none, the floor is lit
// by the model's light and the headlight, as a viewer shows the model alone.
TEST_F(SceneLighting, AStandaloneConversionBringsItsOwnLight) {
  const ScratchDir dir;
  const std::string model = std::string(OPENPLX_SAMPLES_DIR) + "/cart_pole.openplx";
  const openplx::testing::Conversion c =
      openplx::testing::cli({model, "-o", (dir / "cart_pole.xml").string()});
  ASSERT_EQ(c.status, 0) << c.errors;
  write(dir / "floor_scene.xml",
        "<mujoco>\n  <include file=\"cart_pole.xml\"/>\n  <worldbody>\n"
        "    <geom name=\"floor\" type=\"plane\" pos=\"0 0 -0.06\" size=\"5 5 0.1\" rgba=\"0.35 0.4 0.35 "
        "1\"/>\n"
        "  </worldbody>\n</mujoco>\n");
  const Picture p = render_scene(*renderer_, dir / "floor_scene.xml");
  ASSERT_GE(p.floor, 0);
  EXPECT_EQ(p.lights, 1);
  const std::vector<double> floor = p.image.median_colour(p.floor);
  ASSERT_EQ(floor.size(), 3u);
  std::cout << "floor " << rgb(floor) << ", its lights give " << rgb(p.matte_floor) << "\n";
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(floor[c], p.matte_floor[c], kLevels) << rgb(floor) << " against " << rgb(p.matte_floor);
  // And the cart is drawn lit, neither black nor washed out to white.
  char error[1000] = "";
  mjModel* m = mj_loadXML((dir / "floor_scene.xml").c_str(), nullptr, error, sizeof(error));
  ASSERT_NE(m, nullptr) << error;
  const int cart = mj_name2id(m, mjOBJ_GEOM, "cart.geometry");
  mj_deleteModel(m);
  const std::vector<double> cart_colour = p.image.median_colour(cart);
  ASSERT_EQ(cart_colour.size(), 3u);
  EXPECT_GT(cart_colour[0], 60) << rgb(cart_colour);
  EXPECT_LT(cart_colour[0], 250) << rgb(cart_colour);
}

}  // namespace
