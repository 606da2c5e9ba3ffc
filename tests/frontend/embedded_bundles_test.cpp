// The project's bundles are compiled in (embedded_bundles.h) and read from there, at their path on disk;
// a user's bundles (-B, OPENPLX_BUNDLE_PATH) are read from disk as ever.
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "frontend/bundles/bundle_index.h"
#include "frontend/bundles/bundles.h"
#include "frontend/bundles/embedded_bundles.h"
#include "frontend/pipeline.h"
#include "frontend/semantics/program.h"
#include "tests/support/eval_fixture.h"

namespace {

namespace fe = openplx::frontend;
namespace fs = std::filesystem;
namespace embedded = openplx::frontend::embedded;

const fs::path kBundles = (fs::path(OPENPLX_TEST_DATA_DIR).parent_path() / "bundles").lexically_normal();

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every folder ("" for the root) and every .openplx file with its text, by path relative to the root.
struct Tree {
  std::set<std::string> dirs;
  std::map<std::string, std::string_view> files;
};

void walk(const embedded::Dir& dir, const std::string& path, Tree& tree) {
  tree.dirs.insert(path);
  const std::string prefix = path.empty() ? "" : path + "/";
  for (const embedded::File& file : embedded::files(dir))
    tree.files.emplace(prefix + std::string(file.name), file.text);
  for (const embedded::Dir& sub : embedded::subdirs(dir)) walk(sub, prefix + std::string(sub.name), tree);
}

Tree embedded_tree() {
  Tree tree;
  walk(embedded::root(), "", tree);
  return tree;
}

// The copy's file at `relative`, or nullptr.
const embedded::File* embedded_file(const fs::path& relative) {
  const embedded::Dir* dir = &embedded::root();
  for (const fs::path& part : relative.parent_path()) {
    if (!(dir = embedded::find_subdir(*dir, part.string()))) return nullptr;
  }
  return embedded::find_file(*dir, relative.filename().string());
}

TEST(EmbeddedBundles, AreTheBundlesFolderFileForFile) {
  ASSERT_TRUE(fs::is_directory(kBundles)) << kBundles;
  Tree disk;
  disk.dirs.insert("");
  std::map<std::string, std::string> texts;
  for (const auto& entry : fs::recursive_directory_iterator(kBundles)) {
    const std::string relative = entry.path().lexically_relative(kBundles).generic_string();
    const std::string name = entry.path().filename().string();
    if (entry.is_directory()) {
      disk.dirs.insert(relative);
    } else if (name.size() > 8 && name.ends_with(".openplx")) {
      texts[relative] = read(entry.path());
    }
  }
  const Tree copy = embedded_tree();
  const char* stale = "the embedded copy differs from bundles/: rebuild";
  EXPECT_EQ(copy.dirs, disk.dirs) << stale;
  EXPECT_GT(copy.files.size(), 200u);
  for (const auto& [path, text] : texts) {
    auto it = copy.files.find(path);
    if (it == copy.files.end()) {
      ADD_FAILURE() << path << " is not embedded; " << stale;
    } else {
      EXPECT_EQ(it->second, text) << path << ": " << stale;
    }
  }
  for (const auto& [path, text] : copy.files) EXPECT_TRUE(texts.count(path)) << path << ": " << stale;
}

TEST(EmbeddedBundles, HoldWhatTheScanFindsInEachFile) {
  for (const auto& [path, text] : embedded_tree().files) {
    const fe::FileDeclarations scanned =
        fe::scan_declarations(text, text.starts_with("\xEF\xBB\xBF") ? 3 : 0);
    const fe::FileDeclarations copy = embedded::declarations(*embedded_file(path));
    EXPECT_EQ(copy.names, scanned.names) << path;
    EXPECT_EQ(copy.complete, scanned.complete) << path;
    EXPECT_EQ(copy.lazy, scanned.lazy) << path;
  }
}

TEST(EmbeddedBundles, OnlyTheProjectsFolderIsReadFromTheCopy) {
  const std::vector<fe::BundleRoot> roots = fe::bundle_search_path({kBundles.string(), "/elsewhere"});
  ASSERT_EQ(roots.size(), 3u);
  EXPECT_EQ(roots[0].dir, kBundles.generic_string());
  EXPECT_TRUE(roots[0].embedded);
  EXPECT_FALSE(roots[1].embedded);  // the same folder, given with -B
  EXPECT_FALSE(roots[2].embedded);
  for (const fe::BundleRoot& root : fe::bundle_search_path({kBundles.string()}, false)) {
    EXPECT_FALSE(root.embedded) << root.dir;  // --no-default-bundles -B DIR
  }
}

class EmbeddedBundleLoading : public openplx::testing::EvalTest {
 protected:
  // Loads Physics3D's RigidBody (and the folders it needs) from `roots`.
  fe::ModelInfo* load_rigid_body(const std::vector<fe::BundleRoot>& roots) {
    program_ = std::make_unique<fe::Program>(sources_, sink_);
    program_->set_bundles(fe::discover_bundles(roots, sources_, sink_));
    fe::ModelInfo* body = program_->builtin_model("Physics3D.Bodies.RigidBody");
    if (body) program_->resolve(body);
    return body;
  }
};

TEST_F(EmbeddedBundleLoading, TheProjectsBundlesAreNotReadFromDisk) {
  fe::ModelInfo* body = load_rigid_body(fe::bundle_search_path({}));
  ASSERT_NE(body, nullptr) << all_diags();
  EXPECT_EQ(sources_.file(body->doc->doc.file).path(),
            (kBundles / "Physics3D/Bodies/RigidBody.openplx").generic_string());
  // Each bundle file read is named at its place on disk, and its text is the copy's own (not a read).
  size_t bundle_files = 0;
  for (fe::FileId id = 0; id < sources_.size(); ++id) {
    const fe::SourceFile& file = sources_.file(id);
    if (file.path().starts_with("<")) continue;
    const fs::path relative = fs::path(file.path()).lexically_relative(kBundles);
    const embedded::File* copy = embedded_file(relative);
    ASSERT_NE(copy, nullptr) << file.path();
    EXPECT_EQ(file.text().data(), copy->text.data()) << file.path();
    ++bundle_files;
  }
  EXPECT_GT(bundle_files, 10u);
}

TEST_F(EmbeddedBundleLoading, TheFolderIsNotListedEither) {
  // An empty folder standing for the project's: everything comes from the copy, named under the folder.
  fe::ModelInfo* body = load_rigid_body({{dir(), true}});
  ASSERT_NE(body, nullptr) << all_diags();
  EXPECT_EQ(sources_.file(body->doc->doc.file).path(), dir() + "/Physics3D/Bodies/RigidBody.openplx");
  EXPECT_TRUE(fs::is_empty(dir()));
}

TEST_F(EmbeddedBundleLoading, AnEditedCopyGivenWithBIsReadFromDisk) {
  const fs::path copy = dir_ / "bundles";
  fs::copy(kBundles, copy, fs::copy_options::recursive);
  std::ofstream(copy / "Math" / "Constants.openplx", std::ios::app) << "TAU is Real: 6.25\n";
  const std::string main = write("main.openplx", "M:\n    tau is Real: Math.TAU\n");
  fe::LoadRequest request{main, std::nullopt, {copy.string()}, std::nullopt, false};
  fe::Evaluation evaluation = fe::evaluate_file(request, sources_, sink_);
  program_ = std::move(evaluation.program);
  evaluator_ = std::move(evaluation.evaluator);
  root_ = evaluation.root;
  ASSERT_FALSE(sink_.has_errors()) << all_diags();
  EXPECT_EQ(real("tau"), 6.25);
}

}  // namespace
