// Replays every saved fuzz input (crashes once found, now fixed) and the fuzz seeds through the fuzz body,
// so a regression shows up in the normal test run and under the sanitizer pass: .urdf files through the URDF
// body, .signals.json through the manifest body, .runtime through the runtime-input body, mesh_* files
// through the mesh body, the rest through the lexer, parser and evaluator.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/fuzz/fuzz_evaluate.h"
#include "tests/fuzz/fuzz_lex_parse.h"
#include "tests/fuzz/fuzz_mesh.h"
#include "tests/fuzz/fuzz_runtime.h"
#include "tests/fuzz/fuzz_urdf.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace fs = std::filesystem;

TEST(FuzzRegression, SavedInputsRunClean) {
  const openplx::testing::ScratchDir scratch;  // the URDF inputs are read from a file
  size_t count = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(OPENPLX_TEST_DATA_DIR) / "fuzz/regressions")) {
    if (!entry.is_regular_file() || entry.path().filename() == "README.md") continue;
    std::ifstream in(entry.path(), std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    const std::string data = text.str();
    const auto* bytes = reinterpret_cast<const uint8_t*>(data.data());
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() == ".urdf") {
      openplx::fuzz::urdf_one(bytes, data.size(), scratch.path());
    } else if (name.ends_with(".signals.json")) {  // manifest_fuzzer's
      openplx::fuzz::manifest_one(bytes, data.size(), scratch.path());
    } else if (entry.path().extension() == ".runtime") {  // runtime_input_fuzzer's
      openplx::fuzz::runtime_input_one(bytes, data.size(), scratch.path());
    } else if (name.starts_with("mesh_")) {  // mesh_fuzzer's: each a hostile file, so a problem
      EXPECT_NE(openplx::fuzz::mesh_one(bytes, data.size(), scratch.path()), "") << name;
    } else {
      openplx::fuzz::lex_parse_one(bytes, data.size());
      openplx::fuzz::evaluate_one(bytes, data.size());
    }
    ++count;
  }
  EXPECT_GT(count, 0u);
}

// The mesh fuzzer's seeds are sound meshes: else the fuzzer would start from nothing but errors.
TEST(FuzzRegression, MeshSeedsAreSound) {
  const openplx::testing::ScratchDir scratch;
  size_t count = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(OPENPLX_TEST_DATA_DIR) / "fuzz/mesh_seeds")) {
    if (entry.path().filename() == "README.md") continue;
    std::ifstream in(entry.path(), std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    const std::string data = text.str();
    EXPECT_EQ(
        openplx::fuzz::mesh_one(reinterpret_cast<const uint8_t*>(data.data()), data.size(), scratch.path()),
        "")
        << entry.path().filename();
    ++count;
  }
  EXPECT_GE(count, 9u);
}

// The runtime bodies return early when their sample does not compile: then they would test nothing.
TEST(FuzzRegression, RuntimeSamplesCompile) {
  for (const char* sample : {"cart_pole.openplx", "drivetrain_machine.openplx"}) {
    const openplx::fuzz::CompiledSample compiled = openplx::fuzz::compile_sample(sample);
    EXPECT_NE(compiled.model, nullptr) << sample;
    EXPECT_NE(compiled.manifest.find("\"fingerprint\": \"v1 bodies="), std::string::npos) << sample;
    if (compiled.model) mj_deleteModel(compiled.model);
  }
}

}  // namespace
