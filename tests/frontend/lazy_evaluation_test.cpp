// Evaluator::evaluate_layouts evaluates one instance per slot layout and leaves the others to be evaluated
// when read. Held here to the eager evaluation it replaced: every model we have converts to the same bytes
// (MJCF, signal manifest, diagnostics, exit status) both ways, and errors in shared layouts are still
// reported at every instance.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "frontend/pipeline.h"
#include "snap/resolve_system.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace fs = std::filesystem;

namespace {

struct Conversion {
  int status = 0;
  std::string diagnostics, mjcf, manifest;
};

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

Conversion convert(const fs::path& model, const fs::path& dir, bool eager) {
  if (eager) {
    ::setenv("OPENPLX_EVALUATE_EVERYTHING", "1", 1);
  } else {
    ::unsetenv("OPENPLX_EVALUATE_EVERYTHING");
  }
  const fs::path out = dir / (std::string(eager ? "eager_" : "lazy_") + model.stem().string() + ".xml");
  std::ostringstream stdout_text, stderr_text;
  Conversion c;
  c.status = openplx::cli::run({model.string(), "-o", out.string()}, stdout_text, stderr_text);
  ::unsetenv("OPENPLX_EVALUATE_EVERYTHING");
  c.diagnostics = stderr_text.str();
  c.mjcf = read(out);
  c.manifest = read(openplx::cli::manifest_path(out.string()));
  return c;
}

// A model evaluated lazily (as the converter does) and its resolved system.
struct Resolved {
  openplx::frontend::SourceManager sources;
  openplx::frontend::DiagnosticSink sink;
  openplx::frontend::Evaluation evaluation;
  openplx::snap::ResolvedSystem system;
};

void resolve_lazily(const fs::path& model, Resolved& out) {
  ::unsetenv("OPENPLX_EVALUATE_EVERYTHING");
  out.evaluation = openplx::frontend::evaluate_file({model.string(), std::nullopt, {}, std::nullopt},
                                                    out.sources, out.sink);
  ASSERT_NE(out.evaluation.root, openplx::frontend::kNoObject);
  out.system = openplx::snap::resolve_system(*out.evaluation.evaluator, out.evaluation.root, out.sink);
}

std::vector<fs::path> models() {
  std::vector<fs::path> found;
  for (const char* root : {OPENPLX_SAMPLES_DIR, OPENPLX_VENDORED_CORPUS_DIR "/agxunity"}) {
    for (const fs::directory_entry& entry : fs::directory_iterator(root)) {
      if (entry.path().extension() == ".openplx") found.push_back(entry.path());
    }
  }
  std::sort(found.begin(), found.end());
  return found;
}

TEST(LazyEvaluation, EveryModelConvertsToTheSameBytesAsEagerEvaluation) {
  openplx::testing::ScratchDir scratch;
  const std::vector<fs::path> all = models();
  ASSERT_GE(all.size(), 20u);
  size_t converted = 0;
  for (const fs::path& model : all) {
    SCOPED_TRACE(model.string());
    const Conversion lazy = convert(model, scratch.path(), false);
    const Conversion eager = convert(model, scratch.path(), true);
    EXPECT_EQ(lazy.status, eager.status);
    EXPECT_EQ(lazy.diagnostics, eager.diagnostics);
    EXPECT_EQ(lazy.mjcf, eager.mjcf);
    EXPECT_EQ(lazy.manifest, eager.manifest);
    converted += lazy.status == 0 && !lazy.mjcf.empty();
  }
  EXPECT_GE(converted, 15u);  // most of them are whole machines, not error cases
}

// `text` fails to convert with "Missing assignment" at each of `paths`, as it does when evaluated eagerly.
void expect_missing_assignments(const std::string& text, std::initializer_list<const char*> paths) {
  openplx::testing::ScratchDir scratch;
  const fs::path model = scratch.path() / "model.openplx";
  std::ofstream(model) << text;
  const Conversion lazy = convert(model, scratch.path(), false);
  EXPECT_EQ(lazy.status, 1);
  for (const char* path : paths) {
    EXPECT_NE(lazy.diagnostics.find(std::string("Missing assignment ") + path), std::string::npos) << path;
  }
  EXPECT_EQ(lazy.diagnostics, convert(model, scratch.path(), true).diagnostics);
}

// A layout whose first instance reports something is checked at every instance, so each reports at its
// own path: here three holders share one layout and its part misses an assignment.
TEST(LazyEvaluation, ErrorsInASharedLayoutAreReportedAtEveryInstance) {
  expect_missing_assignments(
      "Part:\n    x is Real\nHolder:\n    part is Part\nScene:\n    a is Holder\n    b is Holder\n"
      "    c is Holder\n",
      {"Scene.a.part.x", "Scene.b.part.x", "Scene.c.part.x"});
}

// A default no entry touches (a hinge's flexibility and dissipation parts) has its type's values wherever it
// is: it is checked once per type and read there, not made again for every instance.
TEST(LazyEvaluation, UntouchedDefaultsOfOneTypeAreMadeOnce) {
  openplx::testing::ScratchDir scratch;
  const fs::path model = scratch.path() / "hinges.openplx";
  {
    std::ofstream out(model);
    out << "Link is Physics3D.Bodies.RigidBody:\n"
           "    inertia.mass: 1\n"
           "    top is Physics3D.Interactions.MateConnector:\n"
           "        main_axis: Math.Vec3.Y_AXIS()\n"
           "        normal: Math.Vec3.Z_AXIS()\n"
           "Scene is Physics3D.System:\n";
    for (int i = 0; i < 4; ++i) {
      out << "    l" << i << " is Link\n    w" << i << " is Physics3D.Interactions.MateConnector:\n"
          << "        position: {" << i << ", 0, 2}\n        main_axis: Math.Vec3.Y_AXIS()\n"
          << "        normal: Math.Vec3.Z_AXIS()\n    h" << i << " is Physics3D.Interactions.Hinge:\n"
          << "        connectors: [l" << i << ".top, w" << i << "]\n";
    }
  }
  namespace fe = openplx::frontend;
  Resolved resolved;
  ASSERT_NO_FATAL_FAILURE(resolve_lazily(model, resolved));
  ASSERT_FALSE(resolved.sink.has_errors());
  ASSERT_EQ(resolved.system.mates.size(), 4u);
  size_t flexibilities = 0, dissipations = 0, marshallings = 0;
  const fe::ObjectGraph& graph = resolved.evaluation.evaluator->graph();
  for (fe::ObjectId id = 0; id < graph.objects.size(); ++id) {
    const std::string& type = graph.at(id).type->qualified;
    flexibilities += type == "Physics3D.Interactions.Flexibility.DefaultHingeFlexibility";
    dissipations += type == "Physics3D.Interactions.Dissipation.DefaultHingeDissipation";
    marshallings += type == "Physics.Signals.Marshalling";
  }
  EXPECT_EQ(flexibilities, 1u);
  EXPECT_EQ(dissipations, 1u);
  // A hinge's four scalar signals declare fields in their marshalling (entries on a part): made in the
  // checked hinge only, since the same entries bind it in the other three and nothing there has a role.
  EXPECT_EQ(marshallings, 4u);
  // And the four mates read the same parameters as eager evaluation gives them.
  const Conversion lazy = convert(model, scratch.path(), false);
  const Conversion eager = convert(model, scratch.path(), true);
  EXPECT_EQ(lazy.status, 0);
  EXPECT_EQ(lazy.mjcf, eager.mjcf);
  EXPECT_EQ(lazy.manifest, eager.manifest);
}

// A default that reports something is made and checked at every instance, so each reports at its own path:
// here the holders have layouts of their own (each assigns `v`), and their default part misses `x`.
TEST(LazyEvaluation, ErrorsInAnUntouchedDefaultAreReportedAtEveryInstance) {
  expect_missing_assignments(
      "Part:\n    x is Real\nHolder:\n    part is Part\n    v is Real: 0\nScene:\n    a is Holder:\n"
      "        v: 1\n    b is Holder:\n        v: 2\n",
      {"Scene.a.part.x", "Scene.b.part.x"});
}

// A vector written the same way for every instance (`size: {0.1, 0.2, 0.3}`, `Math.Vec3.from_xyz(...)`) is
// read once per entry and not made in the other instances; one whose entry reads its instance (`{width,
// 0, 0}`) or whose parts an instance assigns (`top.position.z: 2`) is still each instance's own.
TEST(LazyEvaluation, VectorsWrittenAlikeAreReadOnceAndKeepEachInstancesOwnValue) {
  openplx::testing::ScratchDir scratch;
  const fs::path model = scratch.path() / "alike.openplx";
  std::ofstream(model) << "Link is Physics3D.Bodies.RigidBody:\n"
                          "    inertia.mass: 1\n"
                          "    width is Real: 0.1\n"
                          "    geometry is Physics3D.Geometries.Box:\n"
                          "        size: {0.1, 0.2, 0.3}\n"
                          "    top is Physics3D.Interactions.MateConnector:\n"
                          "        position: Math.Vec3.from_xyz(0, 0, 0.5)\n"
                          "    side is Physics3D.Interactions.MateConnector:\n"
                          "        position: {width, 0, 0}\n"
                          "Scene is Physics3D.System:\n"
                          "    a is Link\n"
                          "    b is Link:\n"
                          "        top.position.z: 2\n"
                          "        width: 3\n"
                          "    c is Link\n"
                          "    d is Link:\n"
                          "        width: 5\n";
  namespace fe = openplx::frontend;
  Resolved resolved;
  ASSERT_NO_FATAL_FAILURE(resolve_lazily(model, resolved));
  ASSERT_FALSE(resolved.sink.has_errors());
  const openplx::snap::ResolvedSystem& system = resolved.system;
  std::map<std::string, Eigen::Vector3d> at;
  for (const auto& c : system.connectors) at[c.path] = c.local.position;
  for (const auto& g : system.geometries) at[g.path] = g.size;
  const std::map<std::string, Eigen::Vector3d> expected = {
      {"a.top", {0, 0, 0.5}},          {"b.top", {0, 0, 2}},
      {"c.top", {0, 0, 0.5}},          {"d.top", {0, 0, 0.5}},
      {"a.side", {0.1, 0, 0}},         {"b.side", {3, 0, 0}},
      {"c.side", {0.1, 0, 0}},         {"d.side", {5, 0, 0}},
      {"a.geometry", {0.1, 0.2, 0.3}}, {"b.geometry", {0.1, 0.2, 0.3}},
      {"c.geometry", {0.1, 0.2, 0.3}}, {"d.geometry", {0.1, 0.2, 0.3}}};
  for (const auto& [path, vector] : expected) {
    ASSERT_TRUE(at.count(path)) << path;
    EXPECT_TRUE(at[path].isApprox(vector)) << path << ": " << at[path].transpose();
  }
  // a and c share a layout: c's size and top position were read from a's entries, not made again.
  const fe::Object& c = resolved.evaluation.evaluator->graph().at(system.geometries[2].object);
  ASSERT_EQ(system.geometries[2].path, "c.geometry");
  EXPECT_EQ(c.find("size")->state, fe::Slot::State::Pending);
}

}  // namespace
