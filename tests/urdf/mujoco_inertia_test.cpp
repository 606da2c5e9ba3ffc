// Inertias as MuJoCo 2.2.2 judges them, and URDF links' masses as its URDF importer gives them
// (frontend/urdf/mujoco_principal_inertia.h, mjcf_emitter/bodies.cpp). The eigen-decomposition is MuJoCo's
// own to the bit; a tensor MuJoCo refuses is repaired with a warning at its line and the output loads; the
// mesh law for links without <inertial> is MuJoCo's importer's by default and exact with
// --urdf-exact-mesh-mass. (The parity test compares every robot of tests/urdf/robots body by body.)
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "frontend/urdf/mujoco_principal_inertia.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;
namespace mi = openplx::mujoco_inertia;

const fs::path kRobots = fs::path(OPENPLX_TEST_DATA_DIR) / "urdf" / "robots";
const fs::path kRefusedPlate =
    fs::path(OPENPLX_TEST_DATA_DIR) / "urdf" / "inertia" / "plate_mujoco_refuses.urdf";

struct Converted {
  int status;
  std::string errors;
};

Converted convert(const std::vector<std::string>& args) {
  std::ostringstream out, errors;
  const int status = openplx::cli::run(args, out, errors);
  return {status, errors.str()};
}

struct Loaded {
  mjModel* model = nullptr;
  std::string error;
  ~Loaded() {
    if (model) mj_deleteModel(model);
  }
};

void load(const fs::path& file, Loaded& loaded) {
  char error[1000] = "";
  loaded.model = mj_loadXML(file.c_str(), nullptr, error, sizeof(error));
  loaded.error = error;
}

double body_mass(const mjModel* m, const char* name) {
  const int b = mj_name2id(m, mjOBJ_BODY, name);
  EXPECT_GE(b, 0) << name;
  return b >= 0 ? m->body_mass[b] : -1;
}

// Our Jacobi iteration against libmujoco's mju_eig3, bit for bit: diagonal tensors, flat plates on the edge
// of A + B >= C, turned tensors, rods and zeros.
TEST(MuJoCoInertia, PrincipalMomentsAreMuJoCosToTheBit) {
  std::mt19937 random(31);
  std::uniform_real_distribution<double> unit(-1, 1);
  size_t different = 0;
  for (int k = 0; k < 100000; ++k) {
    Eigen::Vector3d moments(std::abs(unit(random)), std::abs(unit(random)), 0);
    moments.z() = k % 3 == 0 ? moments.x() + moments.y() : k % 7 == 0 ? 0.0 : std::abs(unit(random));
    Eigen::Matrix3d t = moments.asDiagonal();
    if (k % 2) {
      const Eigen::Matrix3d r =
          Eigen::AngleAxisd(3 * unit(random),
                            Eigen::Vector3d(unit(random), unit(random), unit(random)).normalized())
              .toRotationMatrix();
      t = r * t * r.transpose();
    }
    const double full[9] = {t(0, 0), t(0, 1), t(0, 2), t(0, 1), t(1, 1), t(1, 2), t(0, 2), t(1, 2), t(2, 2)};
    double values[3], vectors[9], quat[4];
    mju_eig3(values, vectors, quat, full);
    const mi::Principal ours = mi::principal_moments(t);
    if (std::memcmp(values, ours.moments.data(), sizeof(values)) != 0 ||
        std::memcmp(quat, ours.axes.data(), sizeof(quat)) != 0)
      ++different;
  }
  EXPECT_EQ(different, 0u);
}

// MuJoCo's importer refuses this plate: its own eigen-decomposition lands 1 ulp below A + B >= C (a check
// with a relative tolerance of 1e-9 passed it, and the output did not load). Ours warns at <inertia>, sets
// the moments to their mean, and the output loads with them.
TEST(MuJoCoInertia, ATensorMuJoCoRefusesIsRepairedAtItsInertiaLine) {
  Loaded theirs;
  load(kRefusedPlate, theirs);
  ASSERT_EQ(theirs.model, nullptr);
  EXPECT_NE(theirs.error.find("A + B >= C"), std::string::npos) << theirs.error;

  const openplx::testing::ScratchDir dir;
  const fs::path out = dir / "plate.xml";
  const Converted c = convert({kRefusedPlate.string(), "-o", out.string()});
  ASSERT_EQ(c.status, 0) << c.errors;
  EXPECT_NE(c.errors.find("plate_mujoco_refuses.urdf:9:7: warning: link `plate` has a non-physical inertia: "
                          "principal moments 0.5000000000000001, 0.24999999999999997, 0.25000000000000006"),
            std::string::npos)
      << c.errors;
  EXPECT_NE(c.errors.find("set to their mean 0.3333333333333334"), std::string::npos) << c.errors;
  Loaded ours;
  load(out, ours);
  ASSERT_NE(ours.model, nullptr) << ours.error;
  const int plate = mj_name2id(ours.model, mjOBJ_BODY, "plate");
  for (int k = 0; k < 3; ++k) EXPECT_EQ(ours.model->body_inertia[3 * plate + k], 0.33333333333333343);
}

// The same plate written in OpenPLX passes the front end's check (a relative 1e-12) but not MuJoCo's: the
// emitter checks the numbers it writes as MuJoCo will and warns at the `inertia.tensor` line.
TEST(MuJoCoInertia, AnOpenPlxTensorMuJoCoWouldRefuseIsRepairedAtItsAttribute) {
  const openplx::testing::ScratchDir dir;
  const fs::path model = dir / "plate.openplx", out = dir / "plate.xml";
  std::ofstream(model)
      << "Plate is Physics3D.Bodies.RigidBody:\n"
         "    inertia.mass: 1.0\n"
         "    inertia.tensor: Physics3D.Bodies.Inertia.symmetric_tensor({0.25000717128216643, "
         "0.2500017571351395, 0.49999107158269401}, -3.5497763155000239e-06, "
         "0.0013389385771653797, -0.00066277303539172955)\n";
  const Converted c = convert({model.string(), "-o", out.string()});
  ASSERT_EQ(c.status, 0) << c.errors;
  EXPECT_NE(
      c.errors.find("plate.openplx:3:5: warning: `inertia.tensor`: its principal moments "
                    "0.5000000000000001, 0.24999999999999997, 0.25000000000000006, as MuJoCo 2.2.2 computes "
                    "them, break the triangle inequality"),
      std::string::npos)
      << c.errors;
  Loaded ours;
  load(out, ours);
  ASSERT_NE(ours.model, nullptr) << ours.error;
  for (int k = 0; k < 3; ++k) EXPECT_EQ(ours.model->body_inertia[3 + k], 0.3333333333333334);
}

// Links without <inertial>: by default the mass MuJoCo's importer gives them (its legacy mesh volumes, which
// the parity test compares body by body); --urdf-exact-mesh-mass takes exact volumes: the non-convex
// bracket is 0.002 m^3 and the scaled wedge with its box 0.0031 m^3 of water. Visual geometry weighs
// nothing either way (the root's box and the tool's sphere).
TEST(MuJoCoInertia, MeshLinksTakeMuJoCosLegacyVolumesOrExactOnesOnRequest) {
  const openplx::testing::ScratchDir dir;
  const fs::path legacy = dir / "legacy.xml", exact = dir / "exact.xml";
  const fs::path urdf = kRobots / "mesh_links.urdf";
  ASSERT_EQ(convert({urdf.string(), "-o", legacy.string()}).status, 0);
  const Converted c = convert({urdf.string(), "-o", exact.string(), "--urdf-exact-mesh-mass"});
  ASSERT_EQ(c.status, 0) << c.errors;
  Loaded a, b;
  load(legacy, a);
  load(exact, b);
  ASSERT_NE(a.model, nullptr) << a.error;
  ASSERT_NE(b.model, nullptr) << b.error;
  EXPECT_NEAR(body_mass(b.model, "bracket"), 2.0, 1e-6);
  EXPECT_NEAR(body_mass(b.model, "wedge"), 3.1, 1e-6);
  EXPECT_GT(std::abs(body_mass(a.model, "bracket") - 2.0), 0.1);  // legacy != exact for this mesh
  for (const mjModel* m : {a.model, b.model}) {
    EXPECT_NEAR(body_mass(m, "base"), 1000 * 0.4 * 0.4 * 0.1, 1e-9);
    EXPECT_EQ(body_mass(m, "tool"), 0.0);
  }
}

}  // namespace
