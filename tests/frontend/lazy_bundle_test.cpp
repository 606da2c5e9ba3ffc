// Bundle files are parsed only when a name they declare is looked up (program.h, bundle_index.h), while
// whatever sees a whole namespace (duplicates, "did you mean", operators) behaves as if all were parsed.
#include <algorithm>
#include <filesystem>

#include "frontend/bundles/bundle_index.h"
#include "frontend/syntax/parser.h"
#include "tests/support/eval_fixture.h"

namespace {

namespace fe = openplx::frontend;

using Names = std::vector<std::string>;

fe::FileDeclarations scan(const std::string& text) {
  return fe::scan_declarations(text);
}

TEST(BundleIndex, ListsTopLevelNamesOfPlainDeclarations) {
  const fe::FileDeclarations d = scan(
      "# A comment at column 1\n"
      "Base:\n"
      "    x is Real: 1  # `not: a name`\n"
      "    list is Real[]: [\n"
      "        1, 2]\n"
      "\n"
      "Derived is Base with Trait:\n"
      "    s is String: \"a: \\\" b\"\n"
      "trait Trait:\n"
      "    y is Int: 2\n"
      "const `Odd name` is Base:\n"
      "    x: 3\n"
      "gravity is Real: 9.81\n"
      "Empty\n");
  EXPECT_TRUE(d.complete);
  EXPECT_TRUE(d.lazy);
  EXPECT_EQ(d.names, (Names{"Base", "Derived", "Trait", "Odd name", "gravity", "Empty"}));
}

TEST(BundleIndex, ReadsCrlfAndSkipsAByteOrderMark) {
  const std::string text =
      "\xEF\xBB\xBF"
      "A:\r\n    v is Int: 1\r\nB is A\r\n";
  const fe::FileDeclarations d = fe::scan_declarations(text, 3);
  EXPECT_TRUE(d.lazy);
  EXPECT_EQ(d.names, (Names{"A", "B"}));
}

TEST(BundleIndex, ImportsAndOperatorsAreParsedWithTheNamespace) {
  for (const char* text : {"import @\"other.openplx\" as O\nA:\n    v is O.B\n",
                           "A:\n    v is Int: 1\noperator +(a: A, b: A) -> A\n", "# only a comment\n"}) {
    const fe::FileDeclarations d = scan(text);
    EXPECT_TRUE(d.complete) << text;
    EXPECT_FALSE(d.lazy) << text;
    EXPECT_EQ(d.names, text[0] == '#' ? Names{} : Names{"A"}) << text;
  }
}

// Lines of a multi-line string are text, even at column 1 (the 0.20.2 release's `.doc` texts), and `\"`
// does not end it, as the lexer reads it.
TEST(BundleIndex, StepsOverMultilineStrings) {
  const fe::FileDeclarations d = scan(
      "A:\n    .doc: \"\"\"\nB: not a declaration\n  \\\"\"\" still text\n\"\"\"\n        v is Int: 1\nC is "
      "A\n");
  EXPECT_TRUE(d.complete);
  EXPECT_TRUE(d.lazy);
  EXPECT_EQ(d.names, (Names{"A", "C"}));
}

TEST(BundleIndex, IsUnsureOfAnythingElse) {
  const char* unsure[] = {
      "A:\n    doc is String: \"\"\"\nB:\n",              // an unterminated multi-line string
      "A:\n\tv is Int: 1\n",                              // tab indentation
      "A:\n    v is Real[]: [1,\nB:\n    w is Int: 2\n",  // an unclosed bracket
      "A:\n    v is Int: 1)\n",                           // an unmatched bracket
      "A:\n    s is String: \"open\n",                    // an unterminated string
      "A:\n    v is Int: 1 ; 2\n",                        // an invalid character
      "A:\nB:\n    v is Int: 1\n",                        // a header without a block
      "A\n    v is Int: 1\n",                             // a block without a colon
      "    v is Int: 1\n",                                // indented, outside any block
      "A.b:\n    v is Int: 1\n",                          // not a declaration
      "with A:\n    v is Int: 1\n",                       // a keyword
  };
  for (const char* text : unsure) {
    EXPECT_FALSE(scan(text).complete) << text;
    EXPECT_FALSE(scan(text).lazy) << text;
  }
}

// The scan against the parser on every file we have: a file it calls lazy declares exactly the names it
// lists (a name it missed would stay invisible), and in the project's bundles it parses without findings.
TEST(BundleIndex, AgreesWithTheParserOnEveryFile) {
  namespace fs = std::filesystem;
  size_t lazy_files = 0;
  for (const std::string& root :
       {std::string(OPENPLX_SAMPLES_DIR) + "/../bundles", std::string(OPENPLX_TEST_DATA_DIR),
        std::string(OPENPLX_SAMPLES_DIR), std::string(OPENPLX_SHARED_CORPUS_DIR),
        std::string(OPENPLX_SHARED_CORPUS_DIR) + "/../bundles-0.20.2"}) {
    if (!fs::is_directory(root)) continue;
    const bool bundles = root.ends_with("/bundles");
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
      if (entry.path().extension() != ".openplx") continue;
      fe::SourceManager sources;
      fe::DiagnosticSink sink;
      std::string error;
      const std::optional<fe::FileId> id = sources.load(entry.path().string(), error);
      ASSERT_TRUE(id) << error;
      const fe::SourceFile& file = sources.file(*id);
      const fe::FileDeclarations scanned = fe::scan_declarations(file.text(), file.content_begin());
      if (!scanned.lazy) continue;
      ++lazy_files;
      const fe::Document doc = fe::parse_file(sources, *id, sink);
      Names parsed;
      for (const fe::Decl& decl : doc.decls) {
        EXPECT_TRUE(decl.kind == fe::DeclKind::Model || decl.kind == fe::DeclKind::Trait ||
                    decl.kind == fe::DeclKind::GlobalAttribute)
            << entry.path();
        parsed.emplace_back(decl.name.text);
      }
      if (sink.diagnostics().empty()) {
        EXPECT_EQ(parsed, scanned.names) << entry.path();
      } else {
        // A broken declaration may be dropped by the parser, but none can appear that the scan missed.
        for (const std::string& name : parsed) {
          EXPECT_NE(std::find(scanned.names.begin(), scanned.names.end(), name), scanned.names.end())
              << entry.path() << ": " << name;
        }
        EXPECT_FALSE(bundles) << entry.path() << " has findings";
      }
    }
  }
  EXPECT_GT(lazy_files, 100u);
}

class LazyBundle : public openplx::testing::EvalTest {
 protected:
  void SetUp() override {
    write("bundles/Lazy/config.openplx", "config is BundleConfig:\n    name: \"Lazy\"\n");
    write("bundles/Lazy/Used.openplx", "Used:\n    v is Int: 1\n");
    write("bundles/Lazy/Unused.openplx", "Unused:\n    w is Int: 2\n");
  }
  // The file a diagnostic with `code` is in ("" when there is none).
  std::string file_of(fe::DiagCode code) const {
    for (const fe::Diagnostic& d : sink_.diagnostics()) {
      if (d.code == code && d.range.file != fe::kNoFile) return sources_.file(d.range.file).path();
    }
    return {};
  }
  bool load_main(const std::string& text) {
    return load_file(write("main.openplx", text), nullptr, {dir() + "/bundles"});
  }
};

TEST_F(LazyBundle, ParsesOnlyTheFilesWhoseNamesAreLookedUp) {
  ASSERT_TRUE(load_main("M:\n    u is Lazy.Used\n")) << all_diags();
  EXPECT_EQ(value("u.v"), "1");
  EXPECT_NE(program_->loaded_model("Lazy.Used"), nullptr);
  EXPECT_EQ(program_->loaded_model("Lazy.Unused"), nullptr);  // its file was scanned, not parsed
  const size_t documents = program_->document_count();
  fe::ModelInfo* unused = program_->builtin_model("Lazy.Unused");
  ASSERT_NE(unused, nullptr);
  EXPECT_EQ(unused->qualified, "Lazy.Unused");
  EXPECT_EQ(program_->document_count(), documents + 1);
  EXPECT_EQ(program_->loaded_model("Lazy.Unused"), unused);
}

TEST_F(LazyBundle, FilesWithOperatorsAreParsedWithTheirNamespace) {
  write("bundles/Lazy/Pair.openplx", "Pair:\n    a is Int: 0\noperator +(lhs: Pair, rhs: Pair) -> Pair\n");
  ASSERT_TRUE(load_main("M:\n    u is Lazy.Used\n")) << all_diags();
  EXPECT_NE(program_->loaded_model("Lazy.Pair"), nullptr);
  EXPECT_EQ(program_->operators().size(), 1u);
  EXPECT_EQ(program_->loaded_model("Lazy.Unused"), nullptr);
}

TEST_F(LazyBundle, ADuplicateAcrossFilesIsStillReported) {
  write("bundles/Lazy/Zzz.openplx", "Used:\n    v is Int: 3\n");
  load_main("M:\n    u is Lazy.Used\n");
  EXPECT_EQ(expect_diag(fe::DiagCode::DuplicateDeclaration, 1, 1), "Duplicate declaration Lazy.Used");
  EXPECT_TRUE(file_of(fe::DiagCode::DuplicateDeclaration).ends_with("/Lazy/Zzz.openplx"));
  EXPECT_EQ(value("u.v"), "1");  // the first file in path order declares it
}

TEST_F(LazyBundle, ADuplicateOfANameInAFileWithOperatorsIsStillReported) {
  // Ops.openplx, first in path order and parsed with the namespace, declares the Used that counts.
  write("bundles/Lazy/Ops.openplx", "Used:\n    v is Int: 5\noperator +(lhs: Used, rhs: Used) -> Used\n");
  load_main("M:\n    u is Lazy.Used\n");
  EXPECT_EQ(expect_diag(fe::DiagCode::DuplicateDeclaration, 1, 1), "Duplicate declaration Lazy.Used");
  EXPECT_TRUE(file_of(fe::DiagCode::DuplicateDeclaration).ends_with("/Lazy/Used.openplx"));
  EXPECT_EQ(value("u.v"), "5");
}

TEST_F(LazyBundle, DidYouMeanSeesNamesOfFilesNotParsed) {
  EXPECT_FALSE(load_main("M:\n    u is Lazy.Unusd\n"));
  EXPECT_EQ(expect_diag(fe::DiagCode::UnknownName, 2, 15),
            "Unknown name Lazy.Unusd: no `Unusd` in Lazy; did you mean `Unused`?");
}

TEST_F(LazyBundle, AnImportOfAWaitingFileSharesItsDocument) {
  // Used.openplx is indexed before Zimporter.openplx (path order), whose import then parses it in Lazy.
  write("bundles/Lazy/Zimporter.openplx", "import @\"Used.openplx\"\nUser:\n    u is Used\n");
  ASSERT_TRUE(load_main("M:\n    u is Lazy.User\n")) << all_diags();
  EXPECT_EQ(value("u.u.v"), "1");
  EXPECT_NE(program_->loaded_model("Lazy.Used"), nullptr);
}

TEST_F(LazyBundle, AUsersFileInsideABundleHasItsFoldersParsedWhole) {
  // A bundle being edited: every file of the folders down to the user's is parsed, and its findings reported.
  write("bundles/Lazy/Broken.openplx", "Broken:\n    v is Int: 1 +\n");
  const std::string main = write("bundles/Lazy/Main.openplx", "Main:\n    u is Used\n");
  EXPECT_FALSE(load_file(main, nullptr, {dir() + "/bundles"}));
  expect_diag(fe::DiagCode::UnexpectedToken, 2, 18);
  EXPECT_NE(program_->loaded_model("Lazy.Unused"), nullptr);
}

}  // namespace
