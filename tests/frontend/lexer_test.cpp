// Unit tests of the lexer's token stream (../shared/spec/openplx-language.md §2): layout tokens from
// relative indentation, comments, identifiers and keywords, numbers, strings, implicit line joining, line
// ends.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "frontend/syntax/lexer.h"
#include "frontend/syntax/token.h"
#include "tests/support/parse_fixture.h"

namespace {

namespace fe = openplx::frontend;

class LexerTest : public openplx::testing::ParseTest {
 protected:
  std::string text(const fe::Token& t) const {
    return std::string(sources_.file(file_).text().substr(t.begin, t.end - t.begin));
  }

  // Renders tokens compactly: names and literals as `KIND(text)`, keywords and punctuation as themselves,
  // layout as NEWLINE / INDENT / DEDENT / EOF.
  std::string render(const std::vector<fe::Token>& tokens) const {
    std::string out;
    for (const fe::Token& t : tokens) {
      if (!out.empty()) out += ' ';
      out += fe::token_kind_name(t.kind);
      switch (t.kind) {
        case fe::TokenKind::Identifier:
        case fe::TokenKind::QuotedIdentifier:
        case fe::TokenKind::Int:
        case fe::TokenKind::Real:
        case fe::TokenKind::String:
        case fe::TokenKind::MultilineString:
        case fe::TokenKind::PathString:
        case fe::TokenKind::DollarPathString:
        case fe::TokenKind::Error:
          out += "(" + text(t) + ")";
          break;
        default:
          break;
      }
    }
    return out;
  }
  std::string lex_render(const std::string& source) { return render(lex(source)); }

  // Only the kinds, for comparing files whose token texts differ (CRLF vs LF).
  static std::string kinds(const std::vector<fe::Token>& tokens) {
    std::string out;
    for (const fe::Token& t : tokens) {
      if (!out.empty()) out += ' ';
      out += fe::token_kind_name(t.kind);
    }
    return out;
  }
  static size_t count_kind(const std::vector<fe::Token>& tokens, fe::TokenKind kind) {
    size_t n = 0;
    for (const fe::Token& t : tokens) n += t.kind == kind;
    return n;
  }
  std::string pos(uint32_t offset) const {
    fe::LineCol lc = sources_.file(file_).line_col(offset);
    return std::to_string(lc.line) + ":" + std::to_string(lc.col);
  }
};

// ---- indentation

TEST_F(LexerTest, TwoSpaceIndentation) {
  EXPECT_EQ(lex_render("Root:\n  a is Int: 1\n  b is Int: 2\n"),
            "IDENT(Root) : NEWLINE INDENT IDENT(a) is IDENT(Int) : INT(1) NEWLINE "
            "IDENT(b) is IDENT(Int) : INT(2) NEWLINE DEDENT EOF");
}

TEST_F(LexerTest, FourSpaceIndentation) {
  EXPECT_EQ(lex_render("Root:\n    a is Int: 1\n    b is Int: 2\n"),
            "IDENT(Root) : NEWLINE INDENT IDENT(a) is IDENT(Int) : INT(1) NEWLINE "
            "IDENT(b) is IDENT(Int) : INT(2) NEWLINE DEDENT EOF");
}

TEST_F(LexerTest, NestedTwoSpaceBlocks) {
  EXPECT_EQ(lex_render("A:\n  b:\n    c: 1\n  d: 2\n"),
            "IDENT(A) : NEWLINE INDENT IDENT(b) : NEWLINE INDENT IDENT(c) : INT(1) NEWLINE DEDENT "
            "IDENT(d) : INT(2) NEWLINE DEDENT EOF");
}

TEST_F(LexerTest, MixedDepthChildAtSixInsideFourSpaceParent) {
  // A child block 2 columns deeper than its 4-space parent opens exactly one block.
  EXPECT_EQ(lex_render("Root:\n    inner is Inner:\n      v: 7.0\n    w: 1\n"),
            "IDENT(Root) : NEWLINE INDENT IDENT(inner) is IDENT(Inner) : NEWLINE INDENT IDENT(v) : REAL(7.0) "
            "NEWLINE DEDENT IDENT(w) : INT(1) NEWLINE DEDENT EOF");
}

TEST_F(LexerTest, MixedDepthChildSixDeeperThanFourSpaceParent) {
  // As in differential_test.openplx and Appendix B case 3: the child sits at column 11 (10 spaces).
  EXPECT_EQ(lex_render("Root:\n    inner is Inner:\n          v: 7.0\n    w: 1\n"),
            "IDENT(Root) : NEWLINE INDENT IDENT(inner) is IDENT(Inner) : NEWLINE INDENT IDENT(v) : REAL(7.0) "
            "NEWLINE DEDENT IDENT(w) : INT(1) NEWLINE DEDENT EOF");
}

TEST_F(LexerTest, DifferentDepthsInSiblingBlocks) {
  // Each block chooses its own depth; only the stack of open columns matters.
  EXPECT_EQ(
      lex_render("A:\n  a: 1\nB:\n        b: 2\nC:\n   c:\n    d: 3\n"),
      "IDENT(A) : NEWLINE INDENT IDENT(a) : INT(1) NEWLINE DEDENT "
      "IDENT(B) : NEWLINE INDENT IDENT(b) : INT(2) NEWLINE DEDENT "
      "IDENT(C) : NEWLINE INDENT IDENT(c) : NEWLINE INDENT IDENT(d) : INT(3) NEWLINE DEDENT DEDENT EOF");
}

TEST_F(LexerTest, SeveralDedentsAtOnce) {
  auto tokens = lex("A:\n  b:\n    c:\n      d: 1\nE\n");
  EXPECT_EQ(render(tokens),
            "IDENT(A) : NEWLINE INDENT IDENT(b) : NEWLINE INDENT IDENT(c) : NEWLINE INDENT IDENT(d) : INT(1) "
            "NEWLINE DEDENT DEDENT DEDENT IDENT(E) NEWLINE EOF");
}

TEST_F(LexerTest, DedentToMiddleLevel) {
  EXPECT_EQ(lex_render("A:\n  b:\n    c:\n      d: 1\n    e: 2\n"),
            "IDENT(A) : NEWLINE INDENT IDENT(b) : NEWLINE INDENT IDENT(c) : NEWLINE INDENT IDENT(d) : INT(1) "
            "NEWLINE DEDENT IDENT(e) : INT(2) NEWLINE DEDENT DEDENT EOF");
}

TEST_F(LexerTest, DedentToUnknownColumnIsInconsistent) {
  auto tokens = lex("Root:\n    a is Int: 1\n  b is Int: 2\n");
  expect_diag(fe::DiagCode::InconsistentDedent, 3, 3);
  EXPECT_EQ(count_kind(tokens, fe::TokenKind::Indent), count_kind(tokens, fe::TokenKind::Dedent));
  EXPECT_EQ(tokens.back().kind, fe::TokenKind::EndOfFile);
}

TEST_F(LexerTest, TabInIndentationIsAnError) {
  lex("A:\n\tb: 1\n");
  expect_diag(fe::DiagCode::TabIndentation, 2, 1);
}

TEST_F(LexerTest, TabsOnBlankAndCommentOnlyLinesAreNotIndentation) {
  // §2.3: blank, whitespace-only and comment-only lines do not take part in indentation, so a tab there
  // is not a tab used for indentation.
  EXPECT_EQ(lex_render("A:\n  b: 1\n\t\n \t # c\n  c: 2\n"),
            "IDENT(A) : NEWLINE INDENT IDENT(b) : INT(1) NEWLINE IDENT(c) : INT(2) NEWLINE DEDENT EOF");
  EXPECT_EQ(count(fe::DiagCode::TabIndentation), 0u);
}

TEST_F(LexerTest, TabAfterCodeIsOrdinaryWhitespace) {
  EXPECT_EQ(lex_render("a:\t1\t# c\n"), "IDENT(a) : INT(1) NEWLINE EOF");
}

TEST_F(LexerTest, BlankWhitespaceOnlyAndCommentOnlyLinesEmitNothing) {
  EXPECT_EQ(lex_render("A:\n\n   \n  # comment in block\n# comment at column 1\n        \n"
                       "          # deep comment\n  b: 1\n\n  c: 2\n"),
            "IDENT(A) : NEWLINE INDENT IDENT(b) : INT(1) NEWLINE IDENT(c) : INT(2) NEWLINE DEDENT EOF");
}

TEST_F(LexerTest, FileOfOnlyCommentsAndBlanksIsJustEof) {
  EXPECT_EQ(lex_render("# one\n\n   # two\n    \n"), "EOF");
  EXPECT_EQ(lex_render(""), "EOF");
  EXPECT_EQ(lex_render("   "), "EOF");
}

TEST_F(LexerTest, TrailingCommentsAreSkipped) {
  EXPECT_EQ(lex_render("# top comment\nRoot:   # after head\n    a is Real: 2.5  # after value\n"),
            "IDENT(Root) : NEWLINE INDENT IDENT(a) is IDENT(Real) : REAL(2.5) NEWLINE DEDENT EOF");
}

TEST_F(LexerTest, CommentWithoutSpaceAfterCode) {
  EXPECT_EQ(lex_render("a: 1#x\n"), "IDENT(a) : INT(1) NEWLINE EOF");
}

TEST_F(LexerTest, HashInsideStringIsNotAComment) {
  auto tokens = lex("s: \"a b # not comment\" # real comment\n");
  EXPECT_EQ(render(tokens), "IDENT(s) : STRING(\"a b # not comment\") NEWLINE EOF");
  EXPECT_EQ(fe::decode_string(tokens[2].kind, text(tokens[2])), "a b # not comment");
}

TEST_F(LexerTest, HashInsideMultilineAndPathStrings) {
  EXPECT_EQ(lex_render("a: \"\"\"x # y\"\"\"\nb: @\"dir#1/f.obj\"\n"),
            "IDENT(a) : MLSTRING(\"\"\"x # y\"\"\") NEWLINE IDENT(b) : PATH(@\"dir#1/f.obj\") NEWLINE EOF");
}

// ---- identifiers and keywords

TEST_F(LexerTest, PlainIdentifiers) {
  EXPECT_EQ(lex_render("_x X1 abc_DEF Box box a_1_b\n"),
            "IDENT(_x) IDENT(X1) IDENT(abc_DEF) IDENT(Box) IDENT(box) IDENT(a_1_b) NEWLINE EOF");
}

TEST_F(LexerTest, BacktickIdentifierIsOneToken) {
  auto tokens = lex("`a.b` is Leaf\n");
  EXPECT_EQ(render(tokens), "QUOTED_IDENT(`a.b`) is IDENT(Leaf) NEWLINE EOF");
  EXPECT_EQ(tokens[0].begin, 0u);
  EXPECT_EQ(tokens[0].end, 5u);  // the range covers both backticks
}

TEST_F(LexerTest, BacktickIdentifierMayHoldSpacesAndKeywords) {
  EXPECT_EQ(lex_render("x.`odd name is`.y\n"),
            "IDENT(x) . QUOTED_IDENT(`odd name is`) . IDENT(y) NEWLINE EOF");
}

TEST_F(LexerTest, UnterminatedBacktickIsAnError) {
  lex("`abc\n");
  expect_diag(fe::DiagCode::UnterminatedBacktick, 1, 1);
}

TEST_F(LexerTest, AllKeywords) {
  EXPECT_EQ(lex_render("is becomes with trait const import fn static operator this true false or optional\n"),
            "is becomes with trait const import fn static operator this true false or optional NEWLINE EOF");
}

TEST_F(LexerTest, EveryKeywordHasItsOwnKind) {
  auto tokens = lex("is becomes with trait const import fn static operator this true false or optional\n");
  const std::vector<fe::TokenKind> expected = {
      fe::TokenKind::KwIs,       fe::TokenKind::KwBecomes, fe::TokenKind::KwWith, fe::TokenKind::KwTrait,
      fe::TokenKind::KwConst,    fe::TokenKind::KwImport,  fe::TokenKind::KwFn,   fe::TokenKind::KwStatic,
      fe::TokenKind::KwOperator, fe::TokenKind::KwThis,    fe::TokenKind::KwTrue, fe::TokenKind::KwFalse,
      fe::TokenKind::KwOr,       fe::TokenKind::KwOptional};
  ASSERT_EQ(tokens.size(), expected.size() + 2);
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(tokens[i].kind, expected[i]) << i;
}

TEST_F(LexerTest, ContextualWordsAreIdentifiers) {
  EXPECT_EQ(lex_render("from to as type range in size start end config name version dependencies\n"),
            "IDENT(from) IDENT(to) IDENT(as) IDENT(type) IDENT(range) IDENT(in) IDENT(size) IDENT(start) "
            "IDENT(end) IDENT(config) IDENT(name) IDENT(version) IDENT(dependencies) NEWLINE EOF");
}

TEST_F(LexerTest, KeywordsAreCaseSensitiveAndWholeWords) {
  EXPECT_EQ(
      lex_render("Is This TRUE isx this_ fnord optionally\n"),
      "IDENT(Is) IDENT(This) IDENT(TRUE) IDENT(isx) IDENT(this_) IDENT(fnord) IDENT(optionally) NEWLINE EOF");
}

// ---- numbers

TEST_F(LexerTest, IntAndRealLiterals) {
  EXPECT_EQ(lex_render("0 42 1.5 0.015 7.0\n"), "INT(0) INT(42) REAL(1.5) REAL(0.015) REAL(7.0) NEWLINE EOF");
}

TEST_F(LexerTest, ExponentsGiveReals) {
  EXPECT_EQ(lex_render("1E5 2.5e-3 2E+3 1.5e-2 2E3 3e0\n"),
            "REAL(1E5) REAL(2.5e-3) REAL(2E+3) REAL(1.5e-2) REAL(2E3) REAL(3e0) NEWLINE EOF");
}

TEST_F(LexerTest, FiftyDigitLiterals) {
  const std::string pi = "3.14159265358979323846264338327950288419716939937510";
  const std::string big = "12345678901234567890123456789012345678901234567890";
  ASSERT_EQ(big.size(), 50u);
  EXPECT_EQ(lex_render("PI is Real: " + pi + "\nN: " + big + "\n"),
            "IDENT(PI) is IDENT(Real) : REAL(" + pi + ") NEWLINE IDENT(N) : INT(" + big + ") NEWLINE EOF");
}

TEST_F(LexerTest, NumbersHaveNoSign) {
  EXPECT_EQ(lex_render("-3 -2.5 +1\n"), "- INT(3) - REAL(2.5) + INT(1) NEWLINE EOF");
}

TEST_F(LexerTest, TrailingDotIsMalformed) {
  // Proposed (§2.7): `5.` is invalid.
  lex("x: 5.\n");
  expect_diag(fe::DiagCode::MalformedNumber, 1, 4);
}

TEST_F(LexerTest, LeadingDotIsADotThenAnInt) {
  // Proposed (§2.7): `.5` is not a number; the lexer gives `.` and `5` and the parser rejects it.
  EXPECT_EQ(lex_render("x: .5\n"), "IDENT(x) : . INT(5) NEWLINE EOF");
}

TEST_F(LexerTest, ExponentWithoutDigitsIsMalformed) {
  lex("x: 1e+\n");
  expect_diag(fe::DiagCode::MalformedNumber, 1, 4);
}

TEST_F(LexerTest, DigitsRunningIntoLettersAreMalformed) {
  lex("x: 12ab\n");
  expect_diag(fe::DiagCode::MalformedNumber, 1, 4);
}

// ---- strings

TEST_F(LexerTest, StringEscapesDecode) {
  auto tokens = lex(R"(s: "q\"b\\s\nn\tt")"
                    "\n");
  ASSERT_EQ(tokens[2].kind, fe::TokenKind::String);
  EXPECT_EQ(text(tokens[2]), R"("q\"b\\s\nn\tt")");
  EXPECT_EQ(fe::decode_string(tokens[2].kind, text(tokens[2])), "q\"b\\s\nn\tt");
  EXPECT_EQ(kinds(tokens), "IDENT : STRING NEWLINE EOF");
}

TEST_F(LexerTest, PlainStringDecodesWithoutQuotes) {
  auto tokens = lex("s: \"\"\nt: \"abc\"\n");
  EXPECT_EQ(render(tokens), "IDENT(s) : STRING(\"\") NEWLINE IDENT(t) : STRING(\"abc\") NEWLINE EOF");
  EXPECT_EQ(fe::decode_string(tokens[2].kind, text(tokens[2])), "");
  EXPECT_EQ(fe::decode_string(tokens[6].kind, text(tokens[6])), "abc");
}

TEST_F(LexerTest, InvalidEscapeIsAnError) {
  lex("s: \"a\\qb\"\n");
  expect_diag(fe::DiagCode::InvalidEscape, 1, 6);
}

TEST_F(LexerTest, StringMustEndOnItsLine) {
  auto tokens = lex("s: \"abc\nt: 1\n");
  expect_diag(fe::DiagCode::UnterminatedString, 1, 4);
  EXPECT_EQ(tokens.back().kind, fe::TokenKind::EndOfFile);
}

TEST_F(LexerTest, MultilineStringSpansLinesWithoutLayoutTokens) {
  auto tokens = lex("Root:\n    t is String: \"\"\"first\nsecond\"\"\"\n    n is Int: 3\n");
  EXPECT_EQ(
      render(tokens),
      "IDENT(Root) : NEWLINE INDENT IDENT(t) is IDENT(String) : MLSTRING(\"\"\"first\nsecond\"\"\") NEWLINE "
      "IDENT(n) is IDENT(Int) : INT(3) NEWLINE DEDENT EOF");
  EXPECT_EQ(fe::decode_string(tokens[8].kind, text(tokens[8])), "first\nsecond");
}

TEST_F(LexerTest, MultilineStringWithIndentedAndDedentedLinesInside) {
  auto tokens = lex("A:\n  .doc: \"\"\"\n        deep\nshallow\n      \n    mid\"\"\"\n  b: 1\n");
  EXPECT_EQ(kinds(tokens),
            "IDENT : NEWLINE INDENT . IDENT : MLSTRING NEWLINE IDENT : INT NEWLINE DEDENT EOF");
  // Proposed (§2.8): the text is raw, with no indentation stripping.
  EXPECT_EQ(fe::decode_string(tokens[7].kind, text(tokens[7])), "\n        deep\nshallow\n      \n    mid");
}

TEST_F(LexerTest, EscapedQuoteInsideMultilineString) {
  // Decision: `\"` inside `"""` does not end the string and decodes to `"` (the published PackagePath doc
  // writes `name: \"my_package\"` and ends with `\""""`).
  auto tokens = lex("d: \"\"\"say \\\"hi\\\" and \\\"\"\"\"\nx: 1\n");
  EXPECT_EQ(kinds(tokens), "IDENT : MLSTRING NEWLINE IDENT : INT NEWLINE EOF");
  EXPECT_EQ(text(tokens[2]), "\"\"\"say \\\"hi\\\" and \\\"\"\"\"");
  EXPECT_EQ(fe::decode_string(tokens[2].kind, text(tokens[2])), "say \"hi\" and \"");
}

TEST_F(LexerTest, SingleAndDoubleQuotesInsideMultilineString) {
  auto tokens = lex("d: \"\"\"a \"b\" \"\"c\"\"\"\n");
  EXPECT_EQ(kinds(tokens), "IDENT : MLSTRING NEWLINE EOF");
  EXPECT_EQ(fe::decode_string(tokens[2].kind, text(tokens[2])), "a \"b\" \"\"c");
}

TEST_F(LexerTest, UnterminatedMultilineString) {
  auto tokens = lex("d: \"\"\"abc\nmore\n");
  expect_diag(fe::DiagCode::UnterminatedMultilineString, 1, 4);
  EXPECT_EQ(tokens.back().kind, fe::TokenKind::EndOfFile);
}

TEST_F(LexerTest, PathStrings) {
  auto tokens = lex("import @\"mesh/part.obj\"\nimport $\"r.urdf\" as a.b\n");
  EXPECT_EQ(
      render(tokens),
      "import PATH(@\"mesh/part.obj\") NEWLINE import DOLLAR_PATH($\"r.urdf\") IDENT(as) IDENT(a) . IDENT(b) "
      "NEWLINE EOF");
  EXPECT_EQ(fe::decode_string(tokens[1].kind, text(tokens[1])), "mesh/part.obj");
  EXPECT_EQ(fe::decode_string(tokens[4].kind, text(tokens[4])), "r.urdf");
}

TEST_F(LexerTest, PathStringProcessesNoEscapes) {
  // Proposed (§2.8): path strings process no escapes.
  auto tokens = lex("p: @\"a\\b\\n.obj\"\n");
  ASSERT_EQ(tokens[2].kind, fe::TokenKind::PathString);
  EXPECT_EQ(fe::decode_string(tokens[2].kind, text(tokens[2])), "a\\b\\n.obj");
}

TEST_F(LexerTest, AtWithoutQuoteIsMalformed) {
  lex("p: @mesh\n");
  expect_diag(fe::DiagCode::MalformedPathString, 1, 4);
}

// ---- implicit line joining

TEST_F(LexerTest, LineJoiningInsideSquareBrackets) {
  EXPECT_EQ(lex_render("xs: [1,\n    2,\n  3]\ny: 1\n"),
            "IDENT(xs) : [ INT(1) , INT(2) , INT(3) ] NEWLINE IDENT(y) : INT(1) NEWLINE EOF");
}

TEST_F(LexerTest, LineJoiningInsideParenthesesAndBracesInABlock) {
  EXPECT_EQ(
      lex_render("A:\n  a: f(1,\n        2)\n  b: {1,\n           2,\n     3}\n  c: (1 +\n      2)\n"),
      "IDENT(A) : NEWLINE INDENT IDENT(a) : IDENT(f) ( INT(1) , INT(2) ) NEWLINE "
      "IDENT(b) : { INT(1) , INT(2) , INT(3) } NEWLINE IDENT(c) : ( INT(1) + INT(2) ) NEWLINE DEDENT EOF");
}

TEST_F(LexerTest, LineJoiningIgnoresBlankAndCommentLinesInside) {
  EXPECT_EQ(lex_render("xs: [1, # one\n\n      # nothing\n      2]\n"),
            "IDENT(xs) : [ INT(1) , INT(2) ] NEWLINE EOF");
}

TEST_F(LexerTest, NestedBracketsAcrossLines) {
  EXPECT_EQ(lex_render("m: [[1, 2],\n    [3, f(4,\n          5)]]\nz: 0\n"),
            "IDENT(m) : [ [ INT(1) , INT(2) ] , [ INT(3) , IDENT(f) ( INT(4) , INT(5) ) ] ] NEWLINE "
            "IDENT(z) : INT(0) NEWLINE EOF");
}

TEST_F(LexerTest, ClosingBracketOnItsOwnLineAtOpenersColumn) {
  EXPECT_EQ(lex_render("A:\n  xs: [\n    1,\n    2\n  ]\n  y: 2\n"),
            "IDENT(A) : NEWLINE INDENT IDENT(xs) : [ INT(1) , INT(2) ] NEWLINE IDENT(y) : INT(2) NEWLINE "
            "DEDENT EOF");
}

TEST_F(LexerTest, ClosingBracketAtColumnOneAtTopLevel) {
  EXPECT_EQ(lex_render("xs: [\n  1\n]\nys: []\n"),
            "IDENT(xs) : [ INT(1) ] NEWLINE IDENT(ys) : [ ] NEWLINE EOF");
}

TEST_F(LexerTest, ContinuationLineAtOpenersIndentationIsStillJoined) {
  // §2.2: while a bracket is open, newlines and leading whitespace are not tokens, whatever the column.
  EXPECT_EQ(lex_render("A:\n  xs: [1,\n  2]\n  y: 3\n"),
            "IDENT(A) : NEWLINE INDENT IDENT(xs) : [ INT(1) , INT(2) ] NEWLINE IDENT(y) : INT(3) NEWLINE "
            "DEDENT EOF");
  EXPECT_EQ(lex_render("zs: [1,\n2, 3]\n"), "IDENT(zs) : [ INT(1) , INT(2) , INT(3) ] NEWLINE EOF");
}

TEST_F(LexerTest, UnclosedBracketIsReported) {
  auto tokens = lex("a: [1, 2\nb: 3\n");
  expect_diag(fe::DiagCode::UnclosedBracket, 1, 4);
  EXPECT_EQ(tokens.back().kind, fe::TokenKind::EndOfFile);
  // Lexing goes on at the next line, which is a line of its own.
  EXPECT_NE(render(tokens).find("NEWLINE IDENT(b) : INT(3) NEWLINE"), std::string::npos) << render(tokens);
}

TEST_F(LexerTest, UnmatchedClosingBracketIsReported) {
  lex("a: 1)\n");
  expect_diag(fe::DiagCode::UnmatchedBracket, 1, 5);
}

// ---- line ends, BOM, punctuation, EOF

TEST_F(LexerTest, CrlfGivesTheSameTokensAsLf) {
  const std::string lf =
      "# c\nRoot:\n    a is Real: 2.5  # x\n\n    xs is Int[]: [1,\n        2]\n    t is String: "
      "\"\"\"a\nb\"\"\"\n"
      "    inner is Inner:\n          v: 1\n";
  std::string crlf;
  for (char c : lf) {
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  auto lf_tokens = lex(lf);
  auto crlf_tokens = lex(crlf);
  EXPECT_EQ(kinds(crlf_tokens), kinds(lf_tokens));
  EXPECT_EQ(kinds(lf_tokens),
            "IDENT : NEWLINE INDENT IDENT is IDENT : REAL NEWLINE IDENT is IDENT [ ] : [ INT , INT ] NEWLINE "
            "IDENT is IDENT : MLSTRING NEWLINE IDENT is IDENT : NEWLINE INDENT IDENT : INT NEWLINE DEDENT "
            "DEDENT EOF");
  // Decision: a multi-line string's value is the same in a CRLF file as in its LF twin.
  for (const fe::Token& t : crlf_tokens) {
    if (t.kind == fe::TokenKind::MultilineString) {
      EXPECT_EQ(fe::decode_string(t.kind, text(t)), "a\nb");
    }
  }
}

TEST_F(LexerTest, CrlfPositionsCountLines) {
  auto tokens = lex("A:\r\n  b: 1\r\n");
  ASSERT_GE(tokens.size(), 6u);
  EXPECT_EQ(render(tokens), "IDENT(A) : NEWLINE INDENT IDENT(b) : INT(1) NEWLINE DEDENT EOF");
  EXPECT_EQ(pos(tokens[4].begin), "2:3");
}

TEST_F(LexerTest, LeadingBomIsSkipped) {
  auto tokens = lex("\xEF\xBB\xBFRoot:\n  a: 1\n");
  EXPECT_EQ(render(tokens), "IDENT(Root) : NEWLINE INDENT IDENT(a) : INT(1) NEWLINE DEDENT EOF");
  EXPECT_EQ(tokens[0].begin, 3u);
  EXPECT_EQ(pos(tokens[0].begin), "1:1");
}

TEST_F(LexerTest, ArrowVersusMinus) {
  EXPECT_EQ(lex_render("fn f() -> R\n"), "fn IDENT(f) ( ) -> IDENT(R) NEWLINE EOF");
  EXPECT_EQ(lex_render("a->b - c - > d -->e\n"),
            "IDENT(a) -> IDENT(b) - IDENT(c) - ERROR(>) IDENT(d) - -> IDENT(e) NEWLINE EOF");
  // `>` alone is not an OpenPLX character.
  expect_diag(fe::DiagCode::InvalidCharacter, 1, 12);
}

TEST_F(LexerTest, AllPunctuation) {
  EXPECT_EQ(lex_render(": . , ( ) [ ] { } -> + - * /\n"), ": . , ( ) [ ] { } -> + - * / NEWLINE EOF");
}

TEST_F(LexerTest, InvalidCharacterIsReported) {
  auto tokens = lex("a: 1 ; 2\n");
  expect_diag(fe::DiagCode::InvalidCharacter, 1, 6);
  EXPECT_EQ(render(tokens), "IDENT(a) : INT(1) ERROR(;) INT(2) NEWLINE EOF");
}

TEST_F(LexerTest, MissingFinalNewlineStillEndsTheLineAndClosesBlocks) {
  EXPECT_EQ(
      lex_render("A:\n  b:\n    c: 1"),
      "IDENT(A) : NEWLINE INDENT IDENT(b) : NEWLINE INDENT IDENT(c) : INT(1) NEWLINE DEDENT DEDENT EOF");
}

TEST_F(LexerTest, IndentsAndDedentsBalanceAtEof) {
  const std::vector<std::string> inputs = {
      "A:\n  b:\n    c:\n      d: 1\n",     "A:\n    x: 1\n        y: 2\n", "A:\n  b:\n    c: [1,\n",
      "A:\n    a: 1\n  b: 2\n      c: 3\n", "A:\n  t: \"\"\"open\n",
  };
  for (const std::string& input : inputs) {
    auto tokens = lex(input);
    EXPECT_EQ(count_kind(tokens, fe::TokenKind::Indent), count_kind(tokens, fe::TokenKind::Dedent)) << input;
    ASSERT_FALSE(tokens.empty());
    EXPECT_EQ(tokens.back().kind, fe::TokenKind::EndOfFile) << input;
    EXPECT_EQ(count_kind(tokens, fe::TokenKind::EndOfFile), 1u) << input;
  }
  accept_all_diags();  // some inputs are broken on purpose
}

TEST_F(LexerTest, EndOfFileIsAlwaysLastEvenAfterErrors) {
  for (const std::string& input : {std::string("\""), std::string("`"), std::string("@"), std::string("]]]"),
                                   std::string("\t\t"), std::string("\xFF\xFE"), std::string("1e")}) {
    auto tokens = lex(input);
    ASSERT_FALSE(tokens.empty());
    EXPECT_EQ(tokens.back().kind, fe::TokenKind::EndOfFile);
  }
  accept_all_diags();
}

TEST_F(LexerTest, TokenPositionsAreByteRanges) {
  auto tokens = lex("Root:\n    a is Real: 2.5\n");
  ASSERT_EQ(render(tokens),
            "IDENT(Root) : NEWLINE INDENT IDENT(a) is IDENT(Real) : REAL(2.5) NEWLINE DEDENT EOF");
  EXPECT_EQ(pos(tokens[4].begin), "2:5");
  EXPECT_EQ(pos(tokens[8].begin), "2:16");
  EXPECT_EQ(pos(tokens[8].end), "2:19");
}

}  // namespace
