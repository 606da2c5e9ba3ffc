// tests/corpus must stay a verbatim copy of ../shared/corpus (the source of truth) when both exist. Robots
// moved into the corpus from ../shared/urdf-next (the staging folder) may be vendored before a checkout's
// ../shared/corpus has them: such extra files must then equal their staged originals.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

std::map<std::string, std::string> read_tree(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file() || entry.path().filename() == "VENDORED.md") continue;
    std::ifstream in(entry.path(), std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    files[fs::relative(entry.path(), root).generic_string()] = text.str();
  }
  return files;
}

TEST(CorpusSync, VendoredCopyMatchesSharedCorpus) {
  const fs::path shared = OPENPLX_SHARED_CORPUS_DIR;
  if (!fs::is_directory(shared)) GTEST_SKIP() << "no ../shared/corpus in this checkout";
  const auto expected = read_tree(shared);
  const auto actual = read_tree(OPENPLX_VENDORED_CORPUS_DIR);
  ASSERT_FALSE(expected.empty());
  for (const auto& [path, text] : expected) {
    auto it = actual.find(path);
    ASSERT_NE(it, actual.end()) << path << " is missing from tests/corpus; run tools/sync-corpus.sh";
    EXPECT_EQ(it->second, text) << path << " differs; run tools/sync-corpus.sh";
  }
  const fs::path staged = fs::path(OPENPLX_SHARED_CORPUS_DIR).parent_path() / "urdf-next";
  const auto staging = fs::is_directory(staged) ? read_tree(staged) : std::map<std::string, std::string>{};
  for (const auto& [path, text] : actual) {
    if (expected.count(path)) continue;
    const std::string prefix = "urdf/";
    auto original = path.rfind(prefix, 0) == 0 ? staging.find(path.substr(prefix.size())) : staging.end();
    EXPECT_TRUE(original != staging.end() && original->second == text)
        << path << ": tests/corpus has a file ../shared/corpus lacks; run tools/sync-corpus.sh";
  }
}

}  // namespace
