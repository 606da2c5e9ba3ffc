// Huge and hostile inputs cost what their first errors cost, not what their size is: a binary file is one
// error at its first NUL byte and nothing read; text that is garbage stops at kMaxErrorsPerFile errors with
// a note where reading stopped. Inputs are a megabyte here; bench/scaling.sh runs 100 MB through the
// converter.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "frontend/syntax/lexer.h"
#include "tests/support/lcg_bytes.h"
#include "tests/support/parse_fixture.h"

namespace {

namespace fe = openplx::frontend;

using openplx::testing::lcg_bytes;

class HugeInput : public openplx::testing::ParseTest {};

TEST_F(HugeInput, RandomBytesAreRefusedAsNotTextAtTheirFirstNul) {
  std::string bytes = lcg_bytes(7, 1 << 20);
  const size_t nul = bytes.find('\0');
  ASSERT_NE(nul, std::string::npos);
  const std::vector<fe::Token> tokens = lex(bytes);
  ASSERT_EQ(sink_.diagnostics().size(), 1u) << all_diags();
  const fe::Diagnostic& d = sink_.diagnostics()[0];
  EXPECT_EQ(d.code, fe::DiagCode::InvalidCharacter);
  EXPECT_EQ(d.range.begin, nul);
  EXPECT_NE(d.message.find("this file is not text"), std::string::npos) << d.message;
  ASSERT_EQ(tokens.size(), 1u);
  EXPECT_EQ(tokens[0].kind, fe::TokenKind::EndOfFile);
  accept_all_diags();
}

TEST_F(HugeInput, UnicodeTextWithOneNulIsReadWithAnInvalidCharacter) {
  // Valid UTF-8 is text however little of it is ASCII: a stray NUL in it is one invalid character.
  std::string text = "# ";
  for (int i = 0; i < 2000; ++i) text += "\xE6\xA8\xA1\xE5\x9E\x8B ";  // 模型
  text += "\nM:\n    a is Int: 1";
  text += '\0';
  text += "\n    b is Int: 2\n";
  parse(text);
  expect_diag(fe::DiagCode::InvalidCharacter, 3, 16);
  ASSERT_EQ(doc_.decls.size(), 1u);
  ASSERT_EQ(doc_.decls[0].body.size(), 1u);  // the broken line is dropped, the next one read
  EXPECT_EQ(doc_.decls[0].body[0].path.parts[0].text, "b");
}

TEST_F(HugeInput, GarbageTextStopsAtTheErrorLimitWithANoteWhereReadingStopped) {
  std::string text = lcg_bytes(11, 1 << 20);
  for (char& c : text) {
    if (c == '\0') c = '!';  // no NUL: read as (broken) text
  }
  const std::vector<fe::Token> tokens = lex(text);
  size_t errors = 0;
  for (const fe::Diagnostic& d : sink_.diagnostics()) errors += d.severity == fe::Severity::Error;
  EXPECT_EQ(errors, fe::kMaxErrorsPerFile);
  ASSERT_EQ(count(fe::DiagCode::TooManyErrors), 1u);
  const fe::Diagnostic& note = sink_.diagnostics().back();
  EXPECT_EQ(note.code, fe::DiagCode::TooManyErrors);
  EXPECT_NE(note.message.find("the rest of it was not read"), std::string::npos);
  EXPECT_LT(note.range.begin, text.size() / 10);  // stopped near the start, not at the end
  EXPECT_EQ(tokens.back().kind, fe::TokenKind::EndOfFile);
  EXPECT_EQ(tokens.back().begin, note.range.begin);
  accept_all_diags();
}

TEST_F(HugeInput, ParserStopsAtTheErrorLimitToo) {
  // Lexically clean lines the parser rejects, one error each.
  std::string text = "M:\n";
  for (int i = 0; i < 50000; ++i) text += "    a" + std::to_string(i) + " is Int: (1 +]\n";
  parse(text);
  size_t errors = 0;
  for (const fe::Diagnostic& d : sink_.diagnostics()) errors += d.severity == fe::Severity::Error;
  EXPECT_EQ(errors, fe::kMaxErrorsPerFile) << all_diags();
  EXPECT_EQ(count(fe::DiagCode::TooManyErrors), 1u);
  accept_all_diags();
}

TEST_F(HugeInput, ErrorsBelowTheLimitAreAllReported) {
  std::string text = "M:\n";
  for (int i = 0; i < 99; ++i) text += "    a" + std::to_string(i) + " is Int: 1 +\n";
  text += "    last is Int: 1\n";
  parse(text);
  EXPECT_EQ(count(fe::DiagCode::UnexpectedToken), 99u);
  EXPECT_EQ(count(fe::DiagCode::TooManyErrors), 0u);
  ASSERT_EQ(doc_.decls.size(), 1u);
  EXPECT_EQ(doc_.decls[0].body.back().path.parts[0].text, "last");
  accept_all_diags();
}

}  // namespace
