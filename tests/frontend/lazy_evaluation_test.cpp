// Evaluator::evaluate_layouts evaluates one instance per slot layout and leaves the others to be evaluated
// when read. Held here to the eager evaluation it replaced: every model we have converts to the same bytes
// (MJCF, signal manifest, diagnostics, exit status) both ways, and errors in shared layouts are still
// reported at every instance.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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

// A layout whose first instance reports something is checked at every instance, so each reports at its
// own path: here three holders share one layout and its part misses an assignment.
TEST(LazyEvaluation, ErrorsInASharedLayoutAreReportedAtEveryInstance) {
  openplx::testing::ScratchDir scratch;
  const fs::path model = scratch.path() / "shared.openplx";
  std::ofstream(model) << "Part:\n"
                          "    x is Real\n"
                          "Holder:\n"
                          "    part is Part\n"
                          "Scene:\n"
                          "    a is Holder\n"
                          "    b is Holder\n"
                          "    c is Holder\n";
  const Conversion lazy = convert(model, scratch.path(), false);
  EXPECT_EQ(lazy.status, 1);
  for (const char* path : {"Scene.a.part.x", "Scene.b.part.x", "Scene.c.part.x"}) {
    EXPECT_NE(lazy.diagnostics.find(std::string("Missing assignment ") + path), std::string::npos) << path;
  }
  EXPECT_EQ(lazy.diagnostics, convert(model, scratch.path(), true).diagnostics);
}

}  // namespace
