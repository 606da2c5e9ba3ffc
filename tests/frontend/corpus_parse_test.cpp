// Every .openplx file of the external corpus and every reconstructed seed snippet parses without a single
// diagnostic, and its AST dump equals the reviewed golden file (regenerate: tools/update-golden).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "frontend/syntax/ast_dump.h"
#include "frontend/syntax/parser.h"

namespace fe = openplx::frontend;
namespace fs = std::filesystem;

namespace {

struct Input {
  fs::path file;
  std::string golden_name;  // path under tests/golden/ast
};

// GoogleTest prints a parameter in test listings (and so in ctest's names): the golden path, not raw bytes.
void PrintTo(const Input& input, std::ostream* os) {
  *os << input.golden_name;
}

std::vector<Input> collect(const fs::path& root, const std::string& prefix) {
  std::vector<Input> inputs;
  if (!fs::is_directory(root)) return inputs;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (entry.is_regular_file() && entry.path().extension() == ".openplx") {
      inputs.push_back({entry.path(), prefix + fs::relative(entry.path(), root).generic_string() + ".ast"});
    }
  }
  std::sort(inputs.begin(), inputs.end(), [](const Input& a, const Input& b) { return a.file < b.file; });
  return inputs;
}

std::vector<Input> all_inputs() {
  std::vector<Input> inputs = collect(OPENPLX_CORPUS_DIR, "corpus/");
  std::vector<Input> seed = collect(fs::path(OPENPLX_TEST_DATA_DIR) / "seed_snippets", "seed_snippets/");
  inputs.insert(inputs.end(), seed.begin(), seed.end());
  return inputs;
}

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

class CorpusParse : public ::testing::TestWithParam<Input> {};

TEST_P(CorpusParse, ParsesCleanlyAndMatchesGolden) {
  const Input& input = GetParam();
  fe::SourceManager sources;
  fe::DiagnosticSink sink;
  std::string error;
  auto id = sources.load(input.file.string(), error);
  ASSERT_TRUE(id) << error;
  fe::Document doc = fe::parse_file(sources, *id, sink);
  std::ostringstream diags;
  fe::print_diagnostics(diags, sources, sink.diagnostics());
  EXPECT_TRUE(sink.diagnostics().empty()) << diags.str();
  EXPECT_FALSE(doc.decls.empty());

  std::ostringstream dump;
  fe::dump_ast(dump, sources.file(*id), doc);
  const fs::path golden = fs::path(OPENPLX_TEST_DATA_DIR) / "golden/ast" / input.golden_name;
  ASSERT_TRUE(fs::exists(golden)) << golden << " missing; run tools/update-golden";
  EXPECT_EQ(dump.str(), read(golden))
      << "AST of " << input.file << " changed; review, then tools/update-golden";
}

std::string test_name(const ::testing::TestParamInfo<Input>& info) {
  std::string name = info.param.golden_name;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(AllFiles, CorpusParse, ::testing::ValuesIn(all_inputs()), test_name);

// Guards against a vacuous pass: the enumeration must see the whole corpus and all seed snippets.
TEST(CorpusParseInventory, SeesEveryFile) {
  auto inputs = all_inputs();
  size_t agxunity = 0, seed = 0;
  for (const Input& input : inputs) {
    agxunity += input.golden_name.rfind("corpus/agxunity/", 0) == 0;
    seed += input.golden_name.rfind("seed_snippets/", 0) == 0;
  }
  EXPECT_EQ(agxunity, 19u);  // 17 scene files + TestBundle/{config,Test}.openplx
  EXPECT_EQ(seed, 31u);      // every openplx-fenced snippet of ../shared/seed
}

}  // namespace
