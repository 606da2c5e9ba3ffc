// --pose: an emitted model placed in a bigger scene moves as one rigid piece (every body, equality anchors
// in world coordinates, keyframes), and two placed copies of the cart-pole included in one scene with a
// floor stand where they were put and touch each other and the floor without passing through.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "mjcf_emitter/xml.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace fs = std::filesystem;
namespace mjcf = openplx::mjcf;

namespace {

// A MuJoCo name, or `fallback` for an unnamed element.
const char* name_or(const char* name, const char* fallback) {
  return name ? name : fallback;
}

class Placement : public ::testing::Test {
 protected:
  // Converts a sample into the test's folder; "" when the converter failed.
  std::string convert(const std::string& sample, const std::string& name, std::vector<std::string> extra) {
    const std::string out = (dir_ / (name + ".xml")).string();
    std::vector<std::string> args{std::string(OPENPLX_SAMPLES_DIR) + "/" + sample, "-o", out};
    args.insert(args.end(), extra.begin(), extra.end());
    std::ostringstream o, e;
    const int status = openplx::cli::run(args, o, e);
    EXPECT_EQ(status, 0) << e.str();
    return status == 0 ? out : "";
  }
  mjModel* load(const std::string& path) {
    char error[1000] = "";
    mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof(error));
    EXPECT_NE(m, nullptr) << path << ": " << error;
    return m;
  }

  openplx::testing::ScratchDir scratch_;
  fs::path dir_ = scratch_.path();
};

Eigen::Vector3d vec(const double* v) {
  return {v[0], v[1], v[2]};
}
Eigen::Quaterniond quat(const double* q) {
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
}

// The largest equality constraint violation at `d`'s state (after mj_forward).
double equality_residual(const mjData* d) {
  double worst = 0;
  for (int n = 0; n < d->nefc; ++n)
    if (d->efc_type[n] == mjCNSTR_EQUALITY) worst = std::max(worst, std::abs(d->efc_pos[n]));
  return worst;
}

// Every body of the placed model is the unplaced one moved by the pose, at the model's defaults and at its
// initial keyframe; equality constraints hold as well as before; free bodies' velocities turn with it.
void expect_placed_rigidly(mjModel* plain, mjModel* placed, const Eigen::Vector3d& t,
                           const Eigen::Quaterniond& r) {
  ASSERT_EQ(plain->nbody, placed->nbody);
  ASSERT_EQ(plain->nkey, placed->nkey);
  mjData* a = mj_makeData(plain);
  mjData* b = mj_makeData(placed);
  for (int key = -1; key < plain->nkey; ++key) {
    if (key >= 0) {
      mj_resetDataKeyframe(plain, a, key);
      mj_resetDataKeyframe(placed, b, key);
    }
    mj_forward(plain, a);
    mj_forward(placed, b);
    for (int i = 1; i < plain->nbody; ++i) {
      const char* body = mj_id2name(plain, mjOBJ_BODY, i);
      EXPECT_LT((vec(b->xpos + 3 * i) - (t + r * vec(a->xpos + 3 * i))).norm(), 1e-9) << body;
      EXPECT_LT((r * quat(a->xquat + 4 * i)).angularDistance(quat(b->xquat + 4 * i)), 1e-9) << body;
    }
    for (int j = 0; j < plain->njnt; ++j) {
      if (plain->jnt_type[j] != mjJNT_FREE) continue;
      const int v = plain->jnt_dofadr[j];
      EXPECT_LT((vec(b->qvel + v) - r * vec(a->qvel + v)).norm(), 1e-9);      // world linear velocity
      EXPECT_LT((vec(b->qvel + v + 3) - vec(a->qvel + v + 3)).norm(), 1e-9);  // angular, body frame
    }
    EXPECT_LT(equality_residual(b), equality_residual(a) + 1e-9);
  }
  mj_deleteData(a);
  mj_deleteData(b);
}

TEST_F(Placement, EveryBodyMovesWithThePose) {
  const Eigen::Vector3d t(3, -2, 0.5);
  const Eigen::Quaterniond r(Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.2, 0.3, 1).normalized()));
  const std::string pose = "3 -2 0.5 " + mjcf::number(r.w()) + " " + mjcf::number(r.x()) + " " +
                           mjcf::number(r.y()) + " " + mjcf::number(r.z());
  // Free and mocap bodies (vehicle_circle), a loop closure (four_bar), slider and hinge (cart_pole), motors.
  for (const std::string sample : {"vehicle_circle", "four_bar", "cart_pole", "two_joint_arm"}) {
    SCOPED_TRACE(sample);
    const std::string plain = convert(sample + ".openplx", sample, {});
    const std::string placed = convert(sample + ".openplx", sample + "_placed", {"--pose", pose});
    ASSERT_FALSE(plain.empty() || placed.empty());
    mjModel* a = load(plain);
    mjModel* b = load(placed);
    ASSERT_TRUE(a && b);
    expect_placed_rigidly(a, b, t, r);
    mj_deleteModel(a);
    mj_deleteModel(b);
  }
}

TEST_F(Placement, BadPosesAreUsageErrors) {
  std::ostringstream o, e;
  const std::string model = std::string(OPENPLX_SAMPLES_DIR) + "/cart_pole.openplx";
  for (const std::string bad : {"1 2", "1 2 3 4", "a b c", "1 2 3 0 0 0 0", "1 2 3 nan 0 0 1"}) {
    e.str("");
    EXPECT_EQ(openplx::cli::run({model, "-o", (dir_ / "x.xml").string(), "--pose", bad}, o, e), 2) << bad;
    EXPECT_NE(e.str().find("--pose"), std::string::npos) << e.str();
  }
  EXPECT_FALSE(fs::exists(dir_ / "x.xml"));
}

// Two cart-poles on one rail facing each other (the right one turned half a turn about z), their carts'
// bottoms on a floor: they start where placed, the poles fall towards each other and onto the floor, the
// carts pushed together meet, and nothing passes through anything.
TEST_F(Placement, TwoCopiesCollideWithEachOtherAndTheFloor) {
  ASSERT_FALSE(
      convert("cart_pole.openplx", "left", {"--prefix", "left/", "--no-keyframe", "--pose", "-0.4 0 0.06"})
          .empty());
  ASSERT_FALSE(convert("cart_pole.openplx", "right",
                       {"--prefix", "right/", "--no-keyframe", "--pose", "0.4 0 0.06 0 0 0 1"})
                   .empty());
  std::ofstream(dir_ / "scene.xml") << R"(<mujoco model="two_cart_poles">
  <include file="left.xml"/>
  <include file="right.xml"/>
  <worldbody>
    <light name="sun" directional="true" pos="0 0 4" dir="0 0 -1"/>
    <geom name="floor" type="plane" size="5 5 0.1" rgba="0.3 0.35 0.3 1"/>
  </worldbody>
</mujoco>
)";
  mjModel* m = load((dir_ / "scene.xml").string());
  ASSERT_NE(m, nullptr);
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  const int left_cart = mj_name2id(m, mjOBJ_BODY, "left/cart");
  const int right_cart = mj_name2id(m, mjOBJ_BODY, "right/cart");
  ASSERT_GE(left_cart, 0);
  ASSERT_GE(right_cart, 0);
  EXPECT_LT((vec(d->xpos + 3 * left_cart) - Eigen::Vector3d(-0.4, 0, 0.06)).norm(), 1e-12);
  EXPECT_LT((vec(d->xpos + 3 * right_cart) - Eigen::Vector3d(0.4, 0, 0.06)).norm(), 1e-12);
  EXPECT_LT(quat(d->xquat + 4 * right_cart).angularDistance(Eigen::Quaterniond(0, 0, 0, 1)), 1e-12);
  // The right copy's rail runs along -x: its cart position reads +0 where placed.
  const int floor = mj_name2id(m, mjOBJ_GEOM, "floor");
  auto copy_of = [&](int geom) {
    const std::string body = name_or(mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[geom]), "");
    return body.rfind("left/", 0) == 0 ? 1 : body.rfind("right/", 0) == 0 ? 2 : 0;
  };
  double deepest_at_start = 0;
  for (int c = 0; c < d->ncon; ++c) deepest_at_start = std::min(deepest_at_start, d->contact[c].dist);
  EXPECT_GT(deepest_at_start, -1e-9) << "something overlaps where it was placed";

  // Both pushed towards the middle (the right copy is turned, so both push forward).
  d->ctrl[mj_name2id(m, mjOBJ_ACTUATOR, "left/drive")] = 5;
  d->ctrl[mj_name2id(m, mjOBJ_ACTUATOR, "right/drive")] = 5;
  int between_copies = 0, with_floor = 0;
  double deepest = 0;
  std::string deepest_pair;
  while (d->time < 3) {
    mj_step(m, d);
    for (int c = 0; c < d->ncon; ++c) {
      const mjContact& k = d->contact[c];
      const int a = copy_of(k.geom1), b = copy_of(k.geom2);
      if (a && b && a != b) ++between_copies;
      if ((k.geom1 == floor && b) || (k.geom2 == floor && a)) ++with_floor;
      if (k.dist < deepest) {
        deepest = k.dist;
        deepest_pair = std::string(name_or(mj_id2name(m, mjOBJ_GEOM, k.geom1), "?")) + " and " +
                       name_or(mj_id2name(m, mjOBJ_GEOM, k.geom2), "?") +
                       " at t = " + std::to_string(d->time);
      }
    }
  }
  EXPECT_GT(between_copies, 0);
  EXPECT_GT(with_floor, 0);
  // A pole's tip lands at about 5 m/s, 1 cm a step: MuJoCo's soft contacts (default solref) give way some
  // centimetres at the impact, then push it back out.
  EXPECT_GT(deepest, -0.05) << "contacts sank deeper than 5 cm: " << deepest_pair;
  double deepest_at_rest = 0;
  for (int c = 0; c < d->ncon; ++c) deepest_at_rest = std::min(deepest_at_rest, d->contact[c].dist);
  EXPECT_GT(deepest_at_rest, -0.002) << "at rest, something stays more than 2 mm inside another";
  // The carts met and stopped there: centres at least a cart's length apart (0.3 m) less the contacts' give.
  const double gap = (vec(d->xpos + 3 * right_cart) - vec(d->xpos + 3 * left_cart)).x();
  EXPECT_GT(gap, 0.3 - 0.01);
  EXPECT_LT(gap, 0.8);  // they moved towards each other
  std::printf(
      "contacts between copies %d, with the floor %d, deepest %.4g m (%s), at rest %.4g m, carts %.4f m "
      "apart\n",
      between_copies, with_floor, deepest, deepest_pair.c_str(), deepest_at_rest, gap);
  mj_deleteData(d);
  mj_deleteModel(m);
}

}  // namespace
