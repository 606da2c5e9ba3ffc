// The 0.17.8 documentation excerpts (../shared/seed, reconstructed in tests/seed_snippets) against our
// bundles: the seed's example models evaluate, and every model the seed defines exists in our bundles with
// every attribute and method the seed lists (current names where the API renamed them).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "frontend/bundles/bundles.h"
#include "frontend/semantics/deprecations.h"
#include "frontend/syntax/parser.h"
#include "tests/support/eval_fixture.h"

namespace fe = openplx::frontend;
namespace fs = std::filesystem;

namespace {

const fs::path kSeed = fs::path(OPENPLX_TEST_DATA_DIR) / "seed_snippets";

class SeedModels : public openplx::testing::EvalTest {};

TEST_F(SeedModels, ThreeLevelSnapExampleEvaluates) {
  for (const char* model : {"World", "SnapRod", "SnapRodParent", "SnapRodParentParent"}) {
    EXPECT_TRUE(load_file((kSeed / "01_ThreeLevelSnap.openplx").string(), model)) << model << '\n'
                                                                                  << all_diags();
  }
  // The 0.17.8 names it uses load with warnings that name the current ones.
  expect_diag_containing(fe::DiagCode::DeprecatedName, "use `Physics3D.Interactions.MateConnector`");
  expect_diag_containing(fe::DiagCode::DeprecatedName, "use `Physics3D.Geometries.Box`");
  expect_diag_containing(fe::DiagCode::DeprecatedName, "`charges` is the 0.17.8 name; use `connectors`");
  expect_diag_containing(fe::DiagCode::DeprecatedName, "use `Math.Quat.angle_axis`");
  expect_diag_containing(fe::DiagCode::DeprecatedName, "use `Math.Quat.from_to`");
  accept_all_diags();  // the same warnings repeat for each of the four loads
  EXPECT_EQ(value("world_lock.connectors"), "[-> rod_system.rod_system.rod.connector, -> world_connector]");
  EXPECT_EQ(value("rod_system.rod_system.rod.connector.position"), "{0.0, 0.0, -0.6}");
}

// Type names are looked up once per document and text, except a 0.17.8 name: every place it is written
// gets its warning.
TEST_F(SeedModels, AnOldNameIsWarnedAboutWhereverItIsWritten) {
  ASSERT_TRUE(
      load("Scene is Physics3D.System:\n"
           "    a is Physics3D.Charges.Box\n"
           "    b is Physics3D.Charges.Box\n"
           "    c is Physics3D.Geometries.Box\n"
           "    d is Physics3D.Geometries.Box\n"))
      << all_diags();
  EXPECT_EQ(count(fe::DiagCode::DeprecatedName), 2u) << all_diags();
  accept_all_diags();
}

TEST_F(SeedModels, TerrainShovelAndLinkDataEvaluate) {
  ASSERT_TRUE(load(
      "Scene is Physics3D.System:\n"
      "    terrain is Terrain.Terrain:\n"
      "        num_elements_x: 151\n"
      "        num_elements_y: 201\n"
      "        element_size: 0.10\n"
      "        max_depth: 5.0\n"
      "        kinematics.local_transform.position.x: (terrain.num_elements_x-1)/2*terrain.element_size\n"
      "    link is Robotics.Links.LinkData\n"))
      << all_diags();
  EXPECT_DOUBLE_EQ(real("terrain.kinematics.local_transform.position.x"), 7.5);
  EXPECT_EQ(value("link.start_main_axis"), "{0.0, 0.0, 1.0}");
  EXPECT_EQ(value("link.start_normal"), "{1.0, 0.0, 0.0}");
  EXPECT_EQ(value("link.end_main_axis"), "{0.0, 0.0, 1.0}");
}

// Seed pages whose model lives elsewhere in the current generation.
const std::map<std::string, std::string> kMovedPages = {
    // 0.20 restructured Vehicles: rollers are TrackSystem wheels.
    {"Vehicles/Tracks/CylindricalRoller", "Vehicles.TrackSystem.Components.TrackWheels.Roller"},
};

struct Declared {
  std::set<std::string> attributes;
  std::set<std::string> methods;
};

Declared declared_in(const fe::ModelInfo* model) {
  Declared out;
  for (const fe::ModelInfo* m : model->linearization()) {
    for (const fe::Entry& e : m->entries) {
      if (e.kind == fe::Entry::Kind::Declare && e.path.size() == 1) out.attributes.emplace(e.path[0]);
    }
    for (const fe::MethodInfo& method : m->methods) out.methods.emplace(method.member->path.parts[0].text);
  }
  return out;
}

TEST_F(SeedModels, BundlesDefineEverySeedModelWithItsMembers) {
  fe::Program program(sources_, sink_);
  program.set_bundles(fe::discover_bundles(fe::bundle_search_path({}), sources_, sink_));
  size_t checked_models = 0, checked_members = 0;
  for (const auto& entry : fs::directory_iterator(kSeed)) {
    if (entry.path().extension() != ".openplx") continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    std::smatch match;
    const std::string content = text.str();
    if (!std::regex_search(content, match, std::regex(R"(0\.17\.8/([A-Za-z0-9/]+))"))) continue;
    const std::string page = match[1];
    if (page.find('/') == std::string::npos) continue;  // whole-bundle example pages (SNAP, URDF import)
    fe::DiagnosticSink local;
    fe::SourceManager local_sources;
    fe::FileId id = local_sources.add(entry.path().string(), content);
    fe::Document doc = fe::parse_file(local_sources, id, local);
    ASSERT_FALSE(local.has_errors()) << entry.path();
    for (const fe::Decl& decl : doc.decls) {
      if (decl.kind != fe::DeclKind::Model && decl.kind != fe::DeclKind::Trait) continue;
      std::string ns = page.substr(0, page.rfind('/'));
      std::replace(ns.begin(), ns.end(), '/', '.');
      std::string qualified = ns + "." + std::string(decl.name.text);
      if (auto moved = kMovedPages.find(page); moved != kMovedPages.end()) qualified = moved->second;
      const size_t dot = qualified.rfind('.');
      if (auto renamed = fe::renamed_model(qualified.substr(0, dot), qualified.substr(dot + 1)))
        qualified = *renamed;
      SCOPED_TRACE(entry.path().filename().string() + ": " + qualified);
      fe::ModelInfo* model = program.builtin_model(qualified);
      ASSERT_NE(model, nullptr) << "no bundle model " << qualified;
      ASSERT_TRUE(program.resolve(model)) << all_diags();
      const Declared ours = declared_in(model);
      ++checked_models;
      for (const fe::Member& m : decl.body) {
        if (m.kind == fe::MemberKind::Attribute) {
          std::string name(m.path.parts[0].text);
          if (auto current = fe::renamed_attribute(name)) name = *current;
          EXPECT_TRUE(ours.attributes.count(name)) << "attribute " << name << " missing";
          ++checked_members;
        } else if (m.kind == fe::MemberKind::Method) {
          const std::string name(m.path.parts[0].text);
          EXPECT_TRUE(ours.methods.count(name)) << "method " << name << " missing";
          ++checked_members;
        }
      }
    }
  }
  EXPECT_GE(checked_models, 28u);
  EXPECT_GE(checked_members, 100u);
  accept_all_diags();
}

}  // namespace
