// tests/corpus must stay a verbatim copy of ../shared/corpus (the source of truth) when both exist.
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
  EXPECT_EQ(actual.size(), expected.size()) << "tests/corpus has extra files; run tools/sync-corpus.sh";
}

}  // namespace
