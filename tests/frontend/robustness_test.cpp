// Robustness: the lexer and parser finish on any input, never crash, keep their recursion bounded and report
// a bounded number of diagnostics. These inputs are also sized to show up as slow if something goes
// quadratic, but no timing is asserted.
#include <gtest/gtest.h>

#include <cstdint>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "frontend/diagnostics/diagnostics.h"
#include "frontend/syntax/ast_dump.h"
#include "frontend/syntax/lexer.h"
#include "frontend/syntax/parser.h"
#include "tests/support/lcg_bytes.h"
#include "tests/support/parse_fixture.h"

namespace fe = openplx::frontend;

namespace {

class Robustness : public openplx::testing::ParseTest {
 protected:
  std::vector<std::string> decl_names() const {
    std::vector<std::string> out;
    for (const fe::Decl& d : doc_.decls) out.emplace_back(d.name.text);
    return out;
  }
  // Every member path in the document, depth first, indented two spaces per level.
  static void append_members(const std::vector<fe::Member>& members, int level,
                             std::vector<std::string>& out) {
    for (const fe::Member& m : members) {
      out.push_back(std::string(2 * level, ' ') + fe::to_string(m.path));
      append_members(m.block, level + 1, out);
    }
  }
  std::vector<std::string> outline() const {
    std::vector<std::string> out;
    for (const fe::Decl& d : doc_.decls) {
      out.emplace_back(d.name.text);
      append_members(d.body, 1, out);
    }
    return out;
  }
  // Depth of the expression tree under `id`, walked without recursion.
  size_t expr_depth(fe::ExprId id) const {
    size_t deepest = 0;
    std::vector<std::pair<fe::ExprId, size_t>> stack{{id, 1}};
    while (!stack.empty()) {
      auto [e, depth] = stack.back();
      stack.pop_back();
      deepest = std::max(deepest, depth);
      for (fe::ExprId operand : doc_.expr(e).operands) stack.emplace_back(operand, depth + 1);
    }
    return deepest;
  }
  // Renders every diagnostic the way the CLI does, so the printer sees the same garbage.
  std::string printed() const {
    std::ostringstream out;
    fe::print_diagnostics(out, sources_, sink_.diagnostics());
    return out.str();
  }
  const fe::Member& only_member() const {
    EXPECT_EQ(doc_.decls.size(), 1u);
    EXPECT_EQ(doc_.decls.at(0).body.size(), 1u);
    return doc_.decls.at(0).body.at(0);
  }
};

using Names = std::vector<std::string>;

using openplx::testing::lcg_bytes;

// ---------------------------------------------------------------------------------------------------------
// Empty and nearly empty files

TEST_F(Robustness, EmptyFile) {
  parse("");
  EXPECT_TRUE(doc_.decls.empty());
  EXPECT_TRUE(sink_.diagnostics().empty());
  EXPECT_EQ(doc_.last_model(), nullptr);
}

TEST_F(Robustness, OnlyCommentsAndBlankLines) {
  parse("# header\n\n   \n    # indented comment\n#\n\n  \n# last line without newline");
  EXPECT_TRUE(doc_.decls.empty());
  EXPECT_TRUE(sink_.diagnostics().empty());
}

TEST_F(Robustness, TabsOnBlankAndCommentLinesAreNotIndentation) {
  // §2.3: blank, whitespace-only and comment-only lines do not take part in indentation.
  parse("M:\n  a is Int\n\t\n\t# note\n  b is Int\n");
  EXPECT_EQ(count(fe::DiagCode::TabIndentation), 0u) << all_diags();
  accept_all_diags();
  ASSERT_EQ(decl_names(), Names{"M"});
  EXPECT_EQ(doc_.decls[0].body.size(), 2u);
}

TEST_F(Robustness, LoneByteOrderMark) {
  parse("\xEF\xBB\xBF");
  EXPECT_TRUE(doc_.decls.empty());
  EXPECT_TRUE(sink_.diagnostics().empty());
}

TEST_F(Robustness, ByteOrderMarkBeforeAModel) {
  parse("\xEF\xBB\xBFM:\n  a is Int\n");
  EXPECT_TRUE(sink_.diagnostics().empty());
  EXPECT_EQ(decl_names(), Names{"M"});
}

// ---------------------------------------------------------------------------------------------------------
// Line ends

constexpr const char* kLineEndSample =
    "import @\"lib.openplx\" as lib\n"
    "\n"
    "# a comment\n"
    "trait Named:\n"
    "  name is String: \"n\"\n"
    "Base:\n"
    "  .doc: \"\"\"two\n"
    "lines\"\"\"\n"
    "  a is Real: 1.5\n"
    "  v is Real[]: [1,\n"
    "      2, 3]\n"
    "Root is Base with Named:\n"
    "  b is Base:\n"
    "    a: 2\n"
    "    c is Int: 3\n"
    "  a: -4 * (1 + 2)\n"
    "PI is Real: 3.14\n";

std::string replace_newlines(std::string text, const std::string& with) {
  std::string out;
  for (char c : text) {
    if (c == '\n') {
      out += with;
    } else {
      out += c;
    }
  }
  return out;
}

TEST_F(Robustness, LfSampleParsesCleanly) {
  parse(kLineEndSample);
  EXPECT_TRUE(sink_.diagnostics().empty()) << all_diags();
  EXPECT_EQ(outline(), (Names{"", "Named", "  name", "Base", "  doc", "  a", "  v", "Root", "  b", "    a",
                              "    c", "  a", "PI"}));
}

TEST_F(Robustness, CrlfFileParsesLikeItsLfTwin) {
  parse(kLineEndSample, "lf.openplx");
  const Names lf = outline();
  const size_t lf_exprs = doc_.exprs.size();
  const std::string lf_doc = doc_.expr(*doc_.decls[2].body[0].value).string_value;

  parse(replace_newlines(kLineEndSample, "\r\n"), "crlf.openplx");
  EXPECT_TRUE(sink_.diagnostics().empty()) << all_diags();
  EXPECT_EQ(outline(), lf);
  EXPECT_EQ(doc_.exprs.size(), lf_exprs);
  ASSERT_EQ(doc_.decls.size(), 5u);
  EXPECT_EQ(doc_.expr(*doc_.decls[2].body[0].value).string_value, lf_doc);
  EXPECT_EQ(lf_doc, "two\nlines");
  // Positions count lines the same way.
  EXPECT_EQ(sources_.file(file_).line_col(doc_.decls[3].range.begin).line, 12u);
}

TEST_F(Robustness, LoneCrFileParsesLikeItsLfTwin) {
  parse(kLineEndSample, "lf.openplx");
  const Names lf = outline();
  parse(replace_newlines(kLineEndSample, "\r"), "cr.openplx");
  EXPECT_TRUE(sink_.diagnostics().empty()) << all_diags();
  EXPECT_EQ(outline(), lf);
}

// ---------------------------------------------------------------------------------------------------------
// Binary input

TEST_F(Robustness, EveryByteValueRepeated) {
  std::string text;
  for (int round = 0; round < 8; ++round) {
    for (int b = 0; b < 256; ++b) text += static_cast<char>(b);
  }
  parse(text);
  EXPECT_TRUE(sink_.has_errors());
  EXPECT_LE(sink_.diagnostics().size(), text.size() / 4);
  EXPECT_FALSE(printed().empty());
  accept_all_diags();
}

TEST_F(Robustness, PseudoRandomBytesFromFixedSeeds) {
  for (uint64_t seed = 1; seed <= 100; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const std::string text = lcg_bytes(seed, 2048);
    const size_t before = sink_.diagnostics().size();
    const fe::Document& doc = parse(text, "garbage" + std::to_string(seed) + ".openplx");
    const size_t reported = sink_.diagnostics().size() - before;
    EXPECT_GT(reported, 0u);
    EXPECT_LE(reported, text.size() / 4);
    for (const fe::Decl& d : doc.decls) EXPECT_LE(d.range.end, text.size());
    for (const fe::Expr& e : doc.exprs) EXPECT_LE(e.range.begin, e.range.end);
    std::ostringstream dump;
    fe::dump_ast(dump, sources_.file(file_), doc);
  }
  EXPECT_FALSE(printed().empty());
  accept_all_diags();
}

TEST_F(Robustness, PseudoRandomTokensFromFixedSeeds) {
  // Garbage made of real OpenPLX pieces reaches deeper into the parser than random bytes do.
  static const char* const kPieces[] = {
      "M",      "a",      "is",   "Real",    ":",      "\n",   "  ", "    ", "(",  ")",
      "[",      "]",      "{",    "}",       ",",      ".",    "+",  "-",    "*",  "/",
      "1",      "2.5",    "with", "trait",   "import", "fn",   "->", "or",   "\"", "\"\"\"",
      "@\"p\"", "$\"p\"", "`q`",  "becomes", "const",  "this", "#",  " "};
  constexpr size_t kCount = sizeof(kPieces) / sizeof(kPieces[0]);
  for (uint64_t seed = 1; seed <= 100; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    uint64_t state = seed;
    std::string text;
    while (text.size() < 2048) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      text += kPieces[(state >> 33) % kCount];
      text += ' ';
    }
    const size_t before = sink_.diagnostics().size();
    const fe::Document& doc = parse(text, "tokens" + std::to_string(seed) + ".openplx");
    EXPECT_LE(sink_.diagnostics().size() - before, text.size() / 4);
    std::ostringstream dump;
    fe::dump_ast(dump, sources_.file(file_), doc);
  }
  printed();
  accept_all_diags();
}

TEST_F(Robustness, NulByteIsAnInvalidCharacter) {
  parse(std::string("M:\n  a is Int: 1") + '\0' + "\n  b is Int\n");
  expect_diag(fe::DiagCode::InvalidCharacter, 2, 14);
  ASSERT_EQ(decl_names(), Names{"M"});
  ASSERT_EQ(doc_.decls[0].body.size(), 1u);
  EXPECT_EQ(doc_.decls[0].body[0].path.parts[0].text, "b");
}

TEST_F(Robustness, NulBytesInACommentAreIgnored) {
  parse(std::string("# a") + '\0' + "b\nM:\n  a is Int\n");
  EXPECT_TRUE(sink_.diagnostics().empty()) << all_diags();
  EXPECT_EQ(decl_names(), Names{"M"});
}

TEST_F(Robustness, FileOfNulBytes) {
  parse(std::string(4096, '\0'));
  expect_diag(fe::DiagCode::InvalidCharacter, 1, 1);
  EXPECT_EQ(sink_.diagnostics().size(), 1u);  // one run of invalid bytes, one error
  EXPECT_TRUE(doc_.decls.empty());
}

// ---------------------------------------------------------------------------------------------------------
// Deep nesting: reported once, recursion bounded

TEST_F(Robustness, FiveThousandNestedParentheses) {
  parse("M:\n  a is Real: " + std::string(5000, '(') + "1" + std::string(5000, ')') + "\nN:\n  b is Int\n");
  EXPECT_EQ(count(fe::DiagCode::NestingTooDeep), 1u) << all_diags();
  expect_diag(fe::DiagCode::NestingTooDeep, 2, 14 + 199);
  EXPECT_EQ(decl_names(), (Names{"M", "N"}));
}

TEST_F(Robustness, FiveThousandUnaryMinuses) {
  parse("M:\n  a is Real: " + std::string(5000, '-') + "1\n  b is Int\n");
  EXPECT_EQ(count(fe::DiagCode::NestingTooDeep), 1u) << all_diags();
  expect_diag(fe::DiagCode::NestingTooDeep, 2, 14 + 198);
  ASSERT_EQ(decl_names(), Names{"M"});
  ASSERT_EQ(doc_.decls[0].body.size(), 1u);
  EXPECT_EQ(doc_.decls[0].body[0].path.parts[0].text, "b");
}

TEST_F(Robustness, FiveThousandNestedArrays) {
  parse("M:\n  a is Real[]: " + std::string(5000, '[') + "1" + std::string(5000, ']') + "\n  b is Int\n");
  EXPECT_EQ(count(fe::DiagCode::NestingTooDeep), 1u) << all_diags();
  accept_all_diags();
  ASSERT_EQ(decl_names(), Names{"M"});
  ASSERT_EQ(doc_.decls[0].body.size(), 1u);
  EXPECT_EQ(doc_.decls[0].body[0].path.parts[0].text, "b");
}

TEST_F(Robustness, ThreeThousandNestedBlocks) {
  std::string text = "M:\n";
  for (int i = 1; i <= 3000; ++i) text += std::string(i, ' ') + "a" + std::to_string(i) + " is T:\n";
  text += std::string(3001, ' ') + "z is Int\n";
  text += "N:\n  b is Int\n";
  parse(text);
  EXPECT_EQ(count(fe::DiagCode::NestingTooDeep), 1u) << all_diags();
  accept_all_diags();
  ASSERT_EQ(decl_names(), (Names{"M", "N"}));
  ASSERT_EQ(doc_.decls[0].body.size(), 1u);
  EXPECT_EQ(doc_.decls[0].body[0].path.parts[0].text, "a1");
  // The kept part of the tree is no deeper than the limit.
  size_t depth = 0;
  for (const std::vector<fe::Member>* block = &doc_.decls[0].body; !block->empty();
       block = &block->front().block) {
    ++depth;
  }
  EXPECT_LE(depth, static_cast<size_t>(fe::kMaxNesting));
  EXPECT_GE(depth, static_cast<size_t>(fe::kMaxNesting) - 1);
}

TEST_F(Robustness, ThreeThousandUnclosedParentheses) {
  parse("M:\n  a is Real: " + std::string(3000, '(') + "1\nN:\n  b is Int\n");
  expect_diag(fe::DiagCode::UnclosedBracket, 2, 14);
  EXPECT_EQ(count(fe::DiagCode::UnclosedBracket), 1u) << all_diags();
  EXPECT_EQ(count(fe::DiagCode::NestingTooDeep), 1u) << all_diags();
  accept_all_diags();
  EXPECT_EQ(decl_names(), (Names{"M", "N"}));
}

TEST_F(Robustness, UnclosedParenthesesToEndOfFile) {
  parse("M:\n  a is Real: " + std::string(3000, '('));
  EXPECT_EQ(count(fe::DiagCode::UnclosedBracket), 1u) << all_diags();
  accept_all_diags();
  EXPECT_EQ(decl_names(), Names{"M"});
}

// ---------------------------------------------------------------------------------------------------------
// Size

TEST_F(Robustness, OneMegabyteArrayOnOneLine) {
  std::string text = "M:\n  a is Int[]: [1";
  const size_t elements = 1 << 18;  // "1, " per element: about 768 KB, plus the rest below
  text.reserve(4 * elements);
  for (size_t i = 1; i < elements; ++i) text += ", 1";
  while (text.size() < (1u << 20)) text += " ";
  text += "]\n";
  parse(text);
  EXPECT_TRUE(sink_.diagnostics().empty()) << all_diags();
  const fe::Member& a = only_member();
  ASSERT_TRUE(a.value.has_value());
  EXPECT_EQ(doc_.expr(*a.value).kind, fe::ExprKind::Array);
  EXPECT_EQ(doc_.expr(*a.value).operands.size(), elements);
}

TEST_F(Robustness, OneMegabyteStringOnOneLine) {
  const std::string body(1 << 20, 'x');
  parse("M:\n  s is String: \"" + body + "\"\n");
  EXPECT_TRUE(sink_.diagnostics().empty()) << all_diags();
  const fe::Member& s = only_member();
  ASSERT_TRUE(s.value.has_value());
  EXPECT_EQ(doc_.expr(*s.value).string_value, body);
}

TEST_F(Robustness, OneMegabyteSumOnOneLineKeepsTheTreeShallow) {
  // `1 + 1 + ...` over 1 MB is 262,144 additions. The parser promises (parser.h) that nesting is bounded so
  // no later pass that walks the tree recursively can overflow the stack: either the tree stays within the
  // limit or the line is rejected as nesting-too-deep.
  std::string text = "M:\n  a is Int: 1";
  while (text.size() < (1u << 20)) text += " + 1";
  text += "\n";
  parse(text);
  accept_all_diags();
  ASSERT_EQ(decl_names(), Names{"M"});
  if (doc_.decls[0].body.empty()) {
    EXPECT_EQ(count(fe::DiagCode::NestingTooDeep), 1u) << all_diags();
    return;
  }
  const fe::Member& a = doc_.decls[0].body[0];
  ASSERT_TRUE(a.value.has_value());
  const size_t depth = expr_depth(*a.value);
  EXPECT_LE(depth, static_cast<size_t>(fe::kMaxNesting) + 1);
  if (depth <= static_cast<size_t>(fe::kMaxNesting) + 1) {
    // Only walk it recursively when that is safe, so a failure here does not take the whole binary down.
    EXPECT_FALSE(fe::expr_to_string(doc_, *a.value).empty());
  }
}

TEST_F(Robustness, HundredThousandMembers) {
  std::string text = "M:\n";
  text.reserve(16 * 100000);
  for (int i = 0; i < 100000; ++i) text += "  a is Int: 1\n";
  parse(text);
  EXPECT_TRUE(sink_.diagnostics().empty()) << all_diags();
  ASSERT_EQ(decl_names(), Names{"M"});
  EXPECT_EQ(doc_.decls[0].body.size(), 100000u);
  EXPECT_EQ(sources_.file(file_).line_col(doc_.decls[0].body.back().range.begin).line, 100001u);
}

TEST_F(Robustness, HundredThousandErrorLinesStopAtTheErrorLimit) {
  // Each line once, up to the limit; then one note, and the rest of the file is not read (a huge broken
  // file costs what its first hundred errors cost).
  std::string text = "M:\n";
  for (int i = 0; i < 100000; ++i) text += "  a is Int: 1 +\n";
  parse(text);
  EXPECT_EQ(count(fe::DiagCode::UnexpectedToken), fe::kMaxErrorsPerFile);
  EXPECT_EQ(count(fe::DiagCode::TooManyErrors), 1u);
  EXPECT_EQ(sink_.diagnostics().size(), fe::kMaxErrorsPerFile + 1);
  EXPECT_EQ(sink_.diagnostics().back().code, fe::DiagCode::TooManyErrors);
  const fe::SourceRange& stop = sink_.diagnostics().back().range;
  EXPECT_EQ(sources_.file(stop.file).line_col(stop.begin).line, fe::kMaxErrorsPerFile + 1);  // its last line
  accept_all_diags();
  std::ostringstream out;
  fe::print_diagnostics(out, sources_, sink_.diagnostics(), 100);
  EXPECT_NE(out.str().find("too-many-errors"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------------------
// Long literals

TEST_F(Robustness, FiftyDigitIntLiteral) {
  parse("M:\n  a is Real: 1" + std::string(49, '0') + "\n");
  EXPECT_TRUE(sink_.diagnostics().empty()) << all_diags();
  const fe::Member& a = only_member();
  ASSERT_TRUE(a.value.has_value());
  const fe::Expr& e = doc_.expr(*a.value);
  EXPECT_EQ(e.kind, fe::ExprKind::Int);
  EXPECT_EQ(e.text.size(), 50u);
  EXPECT_FALSE(e.int_value.has_value());
  EXPECT_DOUBLE_EQ(e.real_value, 1e49);
}

TEST_F(Robustness, LargestAndJustTooLargeInt64) {
  parse("M:\n  a is Int: 9223372036854775807\n  b is Int: 9223372036854775808\n");
  EXPECT_TRUE(sink_.diagnostics().empty()) << all_diags();
  ASSERT_EQ(doc_.decls.size(), 1u);
  ASSERT_EQ(doc_.decls[0].body.size(), 2u);
  const fe::Expr& a = doc_.expr(*doc_.decls[0].body[0].value);
  const fe::Expr& b = doc_.expr(*doc_.decls[0].body[1].value);
  ASSERT_TRUE(a.int_value.has_value());
  EXPECT_EQ(*a.int_value, INT64_MAX);
  EXPECT_FALSE(b.int_value.has_value());
  EXPECT_DOUBLE_EQ(b.real_value, 9223372036854775808.0);
}

TEST_F(Robustness, FiftyDecimalRealLiteral) {
  parse("PI is Real: 3.14159265358979323846264338327950288419716939937510\n");
  EXPECT_TRUE(sink_.diagnostics().empty()) << all_diags();
  ASSERT_EQ(doc_.decls.size(), 1u);
  EXPECT_EQ(doc_.decls[0].kind, fe::DeclKind::GlobalAttribute);
  ASSERT_TRUE(doc_.decls[0].value.has_value());
  const fe::Expr& e = doc_.expr(*doc_.decls[0].value);
  EXPECT_EQ(e.kind, fe::ExprKind::Real);
  EXPECT_EQ(e.real_value, 3.141592653589793);  // the double nearest to pi, exactly
}

TEST_F(Robustness, HugeExponentsDoNotCrash) {
  parse("M:\n  a is Real: 1e999999\n  b is Real: 1e-999999\n");
  accept_all_diags();
  ASSERT_EQ(doc_.decls.size(), 1u);
  EXPECT_EQ(doc_.decls[0].body.size(), 2u);
}

TEST_F(Robustness, VeryLongNameAndQualifiedName) {
  const std::string name(100000, 'n');
  std::string path = "x";
  for (int i = 0; i < 20000; ++i) path += ".y";
  parse("M:\n  " + name + " is Int: 1\n  " + path + ": 2\n");
  EXPECT_TRUE(sink_.diagnostics().empty()) << all_diags();
  ASSERT_EQ(doc_.decls.size(), 1u);
  ASSERT_EQ(doc_.decls[0].body.size(), 2u);
  EXPECT_EQ(doc_.decls[0].body[0].path.parts[0].text.size(), name.size());
  EXPECT_EQ(doc_.decls[0].body[1].path.parts.size(), 20001u);
}

}  // namespace
