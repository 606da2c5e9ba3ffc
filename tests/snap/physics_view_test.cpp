// The physics view read from evaluated corpus models: bodies with mass properties, geometries with their
// materials, mates with their types, the 1-dof interactions attached to each mate, and signals.
#include "snap/physics_view.h"

#include <filesystem>

#include "tests/support/eval_fixture.h"

namespace {

namespace fe = openplx::frontend;
namespace sn = openplx::snap;
namespace fs = std::filesystem;

const fs::path kAgx = fs::path(OPENPLX_CORPUS_DIR) / "agxunity";

class PhysicsView : public openplx::testing::EvalTest {
 protected:
  void view_of(const std::string& file, const char* model = nullptr) {
    ASSERT_TRUE(load_file((kAgx / file).string(), model)) << all_diags();
    view_ = sn::build_physics_view(*evaluator_, root_, sink_);
  }
  const sn::FrameNode& node(const std::string& path) {
    for (const sn::FrameNode& n : view_.nodes) {
      if (n.path == path) return n;
    }
    ADD_FAILURE() << "no node " << path;
    return view_.nodes.front();
  }
  sn::PhysicsView view_;
};

TEST_F(PhysicsView, MultiInteractionAttachesSevenInteractionsPerMate) {
  view_of("multi_interaction.openplx");
  ASSERT_EQ(view_.mates.size(), 2u);
  using K = sn::Interaction1D::Kind;
  for (size_t m = 0; m < view_.mates.size(); ++m) {
    std::map<K, int> kinds;
    for (const sn::Interaction1D& i : view_.interactions) {
      if (i.mate == static_cast<int>(m)) ++kinds[i.kind];
    }
    const bool hinge = view_.mates[m].type == sn::MateType::Hinge;
    EXPECT_EQ(kinds[hinge ? K::RotationalVelocityMotor : K::LinearVelocityMotor], 2) << view_.mates[m].path;
    EXPECT_EQ(kinds[hinge ? K::RotationalRange : K::LinearRange], 2) << view_.mates[m].path;
    EXPECT_EQ(kinds[hinge ? K::TorsionSpring : K::LinearSpring], 2) << view_.mates[m].path;
  }
  EXPECT_EQ(view_.interactions.size(), 12u);
}

TEST_F(PhysicsView, BodiesCarryMassAndGeometries) {
  view_of("multi_interaction.openplx");
  const sn::FrameNode& rod = node("hingePendulum.rod");
  EXPECT_EQ(rod.kind, sn::FrameNode::Kind::Body);
  EXPECT_EQ(rod.body.mass, 10.0);
  EXPECT_TRUE(rod.body.dynamic);
  size_t boxes = 0;
  for (const sn::Geometry& g : view_.geometries) {
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

TEST_F(PhysicsView, MaterialsAndKinematicBodies) {
  view_of("material_scene.openplx");
  std::map<std::string, double> density;
  for (const sn::Geometry& g : view_.geometries) {
    ASSERT_NE(g.material, fe::kNoObject) << g.path;
    density[g.path] = evaluator_->value(g.material, "density")->as_real();
  }
  EXPECT_EQ(density["Box1.geometry"], 1500.0);
  EXPECT_EQ(density["Box2.geometry"], 2000.0);
  EXPECT_EQ(density["BoxInline.geometry"], 500.0);
  EXPECT_EQ(view_.mates.size(), 1u);
  EXPECT_EQ(view_.interactions.size(), 1u);
  EXPECT_EQ(view_.interactions[0].mate, 0);  // GroundMotor drives GroundHinge
}

TEST_F(PhysicsView, SignalsWithTheirSources) {
  view_of("signal_test.openplx");
  std::map<std::string, const sn::Signal*> by_path;
  for (const sn::Signal& s : view_.signals) by_path[s.path] = &s;
  ASSERT_TRUE(by_path.count("motorSpeedInput"));
  EXPECT_TRUE(by_path["motorSpeedInput"]->input);
  EXPECT_EQ(by_path["motorSpeedInput"]->source, object("motor"));
  ASSERT_TRUE(by_path.count("angularVelocity"));
  EXPECT_FALSE(by_path["angularVelocity"]->input);
  EXPECT_EQ(by_path["angularVelocity"]->source, object("hinge"));
  ASSERT_TRUE(by_path.count("hinge.angle_output"));  // added by the bundle, disabled by default
  EXPECT_FALSE(by_path["hinge.angle_output"]->enabled);
}

}  // namespace
