// Every .openplx file under the corpus's agxunity folder evaluates completely with the standard bundles
// (what `openplx2mjcf FILE --dump=values` does), except the ones the corpus README says must fail.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "frontend/evaluation/value_format.h"
#include "frontend/pipeline.h"

namespace fe = openplx::frontend;
namespace fs = std::filesystem;

namespace {

const fs::path kAgx = fs::path(OPENPLX_CORPUS_DIR) / "agxunity";

std::vector<std::string> corpus_files() {
  std::vector<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(kAgx)) {
    if (entry.path().extension() == ".openplx")
      files.push_back(fs::relative(entry.path(), kAgx).generic_string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

struct CorpusRun {
  fe::SourceManager sources;
  fe::DiagnosticSink sink;
  fe::Evaluation evaluation;
  std::string values;
  std::string diagnostics;
};

void evaluate(CorpusRun& run, const std::string& file, std::optional<std::string> model = std::nullopt,
              std::vector<std::string> bundle_dirs = {}) {
  fe::LoadRequest request{(kAgx / file).string(), std::move(model), std::move(bundle_dirs), std::nullopt};
  run.evaluation = fe::evaluate_file(request, run.sources, run.sink);
  std::ostringstream diags;
  fe::print_diagnostics(diags, run.sources, run.sink.diagnostics());
  run.diagnostics = diags.str();
  if (run.evaluation.root != fe::kNoObject) {
    std::ostringstream values;
    fe::dump_values(values, *run.evaluation.evaluator, run.evaluation.root);
    run.values = values.str();
  }
}

class CorpusEval : public ::testing::TestWithParam<std::string> {};

TEST_P(CorpusEval, Evaluates) {
  const std::string& file = GetParam();
  CorpusRun run;
  if (file == "extended_pendulum_from_agx.openplx") {
    // It imports an AGX archive: exactly one error, at the import line, naming the format.
    evaluate(run, file);
    ASSERT_EQ(run.sink.diagnostics().size(), 1u) << run.diagnostics;
    const fe::Diagnostic& d = run.sink.diagnostics()[0];
    EXPECT_EQ(d.code, fe::DiagCode::UnsupportedImport);
    EXPECT_EQ(run.sources.file(d.range.file).line_col(d.range.begin).line, 1u);
    EXPECT_NE(d.message.find(".agx"), std::string::npos);
    return;
  }
  if (file == "use_test_bundle.openplx") {
    evaluate(run, file, std::nullopt, {(kAgx / "TestBundle").string()});
  } else if (file == "simple_lidar.openplx") {
    evaluate(run, file, "ValidLidar");
  } else {
    evaluate(run, file);
  }
  EXPECT_EQ(run.sink.error_count(), 0u) << run.diagnostics;
  EXPECT_NE(run.evaluation.root, fe::kNoObject);
  EXPECT_FALSE(run.values.empty());
}

std::string test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(AgxUnity, CorpusEval, ::testing::ValuesIn(corpus_files()), test_name);

TEST(CorpusEvalInventory, SeesEveryFile) {
  EXPECT_EQ(corpus_files().size(), 19u);
}

// The signals the bundles add show up with their defaults.
TEST(CorpusEvalValues, SignalTestShowsBundleSignalsWithDefaults) {
  CorpusRun run;
  evaluate(run, "signal_test.openplx");
  ASSERT_EQ(run.sink.error_count(), 0u) << run.diagnostics;
  EXPECT_NE(run.values.find("hinge.angle_output.enabled = false\n"), std::string::npos) << run.values;
  EXPECT_NE(run.values.find("motorSpeedInput.source = -> motor\n"), std::string::npos) << run.values;
  EXPECT_NE(run.values.find("angularVelocity.source = -> hinge\n"), std::string::npos) << run.values;
  EXPECT_NE(run.values.find("boxRPY.source = -> box\n"), std::string::npos) << run.values;
}

}  // namespace
