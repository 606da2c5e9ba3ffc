// Malformed OpenPLX inputs: every lexical and syntax diagnostic code, at its exact line:col, with the
// documented message texts (spec §17) checked verbatim, and error recovery (every error of a file reported,
// the good declarations kept, one bad line giving exactly one error).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "frontend/syntax/parser.h"
#include "tests/support/parse_fixture.h"

namespace fe = openplx::frontend;

namespace {

class MalformedInput : public openplx::testing::ParseTest {
 protected:
  std::vector<std::string> decl_names() const {
    std::vector<std::string> out;
    for (const fe::Decl& d : doc_.decls) out.emplace_back(d.name.text);
    return out;
  }
  static std::vector<std::string> member_names(const std::vector<fe::Member>& members) {
    std::vector<std::string> out;
    for (const fe::Member& m : members) out.push_back(fe::to_string(m.path));
    return out;
  }
  fe::LineCol pos(uint32_t offset) const { return sources_.file(file_).line_col(offset); }
};

using Names = std::vector<std::string>;

// ---------------------------------------------------------------------------------------------------------
// Lexical errors

TEST_F(MalformedInput, TabAsIndentation) {
  parse("M:\n\ta is Real\n");
  expect_diag(fe::DiagCode::TabIndentation, 2, 1);
  ASSERT_EQ(decl_names(), Names{"M"});
  EXPECT_EQ(member_names(doc_.decls[0].body), Names{"a"});
}

TEST_F(MalformedInput, TabAfterSpacesInIndentation) {
  parse("M:\n  \ta is Int\n");
  expect_diag(fe::DiagCode::TabIndentation, 2, 3);
  ASSERT_EQ(decl_names(), Names{"M"});
  EXPECT_EQ(member_names(doc_.decls[0].body), Names{"a"});
}

TEST_F(MalformedInput, OneTabIndentedLineIsOneErrorNotAlsoABadDedent) {
  // The tab is the only mistake; the next line, indented with two spaces, is fine.
  parse("M:\n\ta is Int\n  b is Int\n");
  expect_diag(fe::DiagCode::TabIndentation, 2, 1);
  EXPECT_EQ(count(fe::DiagCode::InconsistentDedent), 0u) << all_diags();
}

TEST_F(MalformedInput, DedentToAColumnNoBlockOpened) {
  parse("M:\n    a is Real\n  b is Int\nN:\n  c is Int\n");
  const std::string message = expect_diag(fe::DiagCode::InconsistentDedent, 3, 3);
  EXPECT_NE(message.find("Inconsistent indentation"), std::string::npos) << message;
  ASSERT_EQ(decl_names(), (Names{"M", "N"}));
  EXPECT_EQ(member_names(doc_.decls[0].body), (Names{"a", "b"}));
  EXPECT_EQ(member_names(doc_.decls[1].body), Names{"c"});
}

TEST_F(MalformedInput, UnterminatedString) {
  parse("M:\n  s is String: \"abc\n  b is Int\n");
  expect_diag(fe::DiagCode::UnterminatedString, 2, 16);
  ASSERT_EQ(decl_names(), Names{"M"});
  EXPECT_EQ(member_names(doc_.decls[0].body), (Names{"s", "b"}));
}

TEST_F(MalformedInput, UnterminatedMultilineString) {
  parse("M:\n  .doc: \"\"\"abc\n  b is Int\n");
  expect_diag(fe::DiagCode::UnterminatedMultilineString, 2, 9);
}

TEST_F(MalformedInput, UnterminatedBacktickName) {
  parse("M:\n  `abc is Int\n  b is Int\n");
  expect_diag(fe::DiagCode::UnterminatedBacktick, 2, 3);
  EXPECT_EQ(count(fe::DiagCode::UnexpectedToken), 0u);
  ASSERT_EQ(decl_names(), Names{"M"});
  EXPECT_EQ(member_names(doc_.decls[0].body), Names{"b"});
}

TEST_F(MalformedInput, EmptyBacktickName) {
  parse("M:\n  `` is Int\n");
  expect_diag(fe::DiagCode::UnterminatedBacktick, 2, 3);
}

TEST_F(MalformedInput, InvalidEscapeInString) {
  parse(R"(M:
  s is String: "a\qb"
)");
  expect_diag(fe::DiagCode::InvalidEscape, 2, 18);
  ASSERT_EQ(decl_names(), Names{"M"});
  EXPECT_EQ(member_names(doc_.decls[0].body), Names{"s"});
}

TEST_F(MalformedInput, InvalidPunctuationCharacter) {
  parse("M:\n  a is Int: 1 ! 2\n");
  expect_diag(fe::DiagCode::InvalidCharacter, 2, 15);
  EXPECT_EQ(count(fe::DiagCode::UnexpectedToken), 0u);
}

TEST_F(MalformedInput, NonAsciiNameIsOneInvalidCharacterError) {
  parse("M:\n  a is Int: 1\n  \xC3\xA9t\xC3\xA9 is Int\n");
  const std::string message = expect_diag(fe::DiagCode::InvalidCharacter, 3, 3);
  EXPECT_NE(message.find("backticks"), std::string::npos) << message;
  EXPECT_EQ(count(fe::DiagCode::InvalidCharacter), 1u) << all_diags();
  ASSERT_EQ(decl_names(), Names{"M"});
  EXPECT_EQ(member_names(doc_.decls[0].body), Names{"a"});
}

TEST_F(MalformedInput, ControlCharacter) {
  parse("M:\n  a is Int: \x01\n");
  const std::string message = expect_diag(fe::DiagCode::InvalidCharacter, 2, 13);
  EXPECT_EQ(message, "invalid control character");
}

TEST_F(MalformedInput, NumberWithoutDigitsAfterThePoint) {
  parse("M:\n  a is Real: 5.\n");
  expect_diag(fe::DiagCode::MalformedNumber, 2, 14);
  EXPECT_EQ(count(fe::DiagCode::UnexpectedToken), 0u);
}

TEST_F(MalformedInput, NumberWithEmptyExponent) {
  parse("M:\n  a is Real: 1e\n");
  expect_diag(fe::DiagCode::MalformedNumber, 2, 14);
}

TEST_F(MalformedInput, NumberWithLettersAttached) {
  parse("M:\n  a is Real: 12ab\n");
  const std::string message = expect_diag(fe::DiagCode::MalformedNumber, 2, 14);
  EXPECT_NE(message.find("12ab"), std::string::npos) << message;
}

TEST_F(MalformedInput, AtWithoutQuotedPath) {
  parse("M:\n  p is String: @x\n");
  expect_diag(fe::DiagCode::MalformedPathString, 2, 16);
  EXPECT_EQ(count(fe::DiagCode::UnexpectedToken), 0u);
}

TEST_F(MalformedInput, DollarWithoutQuotedPathInImport) {
  parse("import $x\n");
  expect_diag(fe::DiagCode::MalformedPathString, 1, 8);
  EXPECT_TRUE(doc_.decls.empty());
}

TEST_F(MalformedInput, BracketUnclosedAtEndOfFile) {
  parse("M:\n  a is Real[]: [1, 2");
  expect_diag(fe::DiagCode::UnclosedBracket, 2, 16);
  EXPECT_EQ(count(fe::DiagCode::UnexpectedToken), 0u);
}

TEST_F(MalformedInput, BracketUnclosedWhenTheNextLineDedents) {
  parse("M:\n  a is Real[]: [1, 2\nN:\n  b is Int\n");
  expect_diag(fe::DiagCode::UnclosedBracket, 2, 16);
  ASSERT_EQ(decl_names(), (Names{"M", "N"}));
  EXPECT_EQ(member_names(doc_.decls[1].body), Names{"b"});
}

TEST_F(MalformedInput, ParenUnclosedWhenTheNextLineIsASibling) {
  parse("M:\n  a is Int: (1\n  b is Int: 2\n");
  expect_diag(fe::DiagCode::UnclosedBracket, 2, 13);
  ASSERT_EQ(decl_names(), Names{"M"});
  EXPECT_EQ(member_names(doc_.decls[0].body), Names{"b"});
}

TEST_F(MalformedInput, ClosingParenWithoutOpening) {
  parse("M:\n  a is Int: 1)\n");
  expect_diag(fe::DiagCode::UnmatchedBracket, 2, 14);
  EXPECT_EQ(count(fe::DiagCode::UnexpectedToken), 0u);
}

TEST_F(MalformedInput, ExtraClosingSquareBracket) {
  parse("M:\n  a is Int: [1]]\n");
  expect_diag(fe::DiagCode::UnmatchedBracket, 2, 16);
}

// ---------------------------------------------------------------------------------------------------------
// `Expected indented block` (documented text). The position is the `:` that promised the block.

TEST_F(MalformedInput, MemberColonWithoutBlock) {
  parse("M:\n  a is Real:\n  b is Int\n");
  EXPECT_EQ(expect_diag(fe::DiagCode::ExpectedIndentedBlock, 2, 12), "Expected indented block");
  ASSERT_EQ(decl_names(), Names{"M"});
  EXPECT_EQ(member_names(doc_.decls[0].body), (Names{"a", "b"}));
  EXPECT_FALSE(doc_.decls[0].body[0].has_block);
}

TEST_F(MalformedInput, AssignmentColonWithoutValueOrBlock) {
  parse("M:\n  a:\n");
  EXPECT_EQ(expect_diag(fe::DiagCode::ExpectedIndentedBlock, 2, 4), "Expected indented block");
}

TEST_F(MalformedInput, TopLevelColonWithoutBlock) {
  parse("M is Base:\nN:\n  a is Int\n");
  EXPECT_EQ(expect_diag(fe::DiagCode::ExpectedIndentedBlock, 1, 10), "Expected indented block");
  ASSERT_EQ(decl_names(), Names{"N"});
  EXPECT_EQ(member_names(doc_.decls[0].body), Names{"a"});
}

TEST_F(MalformedInput, LoneModelHeadAtEndOfFile) {
  parse("M:");
  EXPECT_EQ(expect_diag(fe::DiagCode::ExpectedIndentedBlock, 1, 2), "Expected indented block");
}

// ---------------------------------------------------------------------------------------------------------
// `Expected an is keyword` (documented text), at the token where `is` was expected.

TEST_F(MalformedInput, MemberNameFollowedByAType) {
  parse("M:\n  a Real\n  b is Int\n");
  EXPECT_EQ(expect_diag(fe::DiagCode::ExpectedIs, 2, 5), "Expected an is keyword");
  ASSERT_EQ(decl_names(), Names{"M"});
  EXPECT_EQ(member_names(doc_.decls[0].body), Names{"b"});
}

TEST_F(MalformedInput, MemberThatIsOnlyAName) {
  parse("M:\n  a\n");
  EXPECT_EQ(expect_diag(fe::DiagCode::ExpectedIs, 2, 4), "Expected an is keyword");
}

TEST_F(MalformedInput, TopLevelNameFollowedByAType) {
  parse("Foo Bar:\n  a is Int\nN:\n  c is Int\n");
  EXPECT_EQ(expect_diag(fe::DiagCode::ExpectedIs, 1, 5), "Expected an is keyword");
  EXPECT_EQ(count(fe::DiagCode::ExpectedIs), 1u);
  ASSERT_EQ(decl_names(), Names{"N"});
  EXPECT_EQ(member_names(doc_.decls[0].body), Names{"c"});
}

// ---------------------------------------------------------------------------------------------------------
// Unexpected tokens

TEST_F(MalformedInput, ExpressionMissingAfterOperator) {
  parse("M:\n  a is Real: 1 +\n");
  const std::string message = expect_diag(fe::DiagCode::UnexpectedToken, 2, 17);
  EXPECT_NE(message.find("expression"), std::string::npos) << message;
}

TEST_F(MalformedInput, TwoOperatorsInARow) {
  parse("M:\n  a is Real: 2 +* 3\n");
  const std::string message = expect_diag(fe::DiagCode::UnexpectedToken, 2, 17);
  EXPECT_NE(message.find("`*`"), std::string::npos) << message;
}

TEST_F(MalformedInput, MissingCommaOrParenInCallArguments) {
  parse("M:\n  a is Real: f(1 2)\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 2, 18);
}

TEST_F(MalformedInput, TrailingCommaInCallArguments) {
  parse("M:\n  a is Real: f(1,)\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 2, 18);
}

TEST_F(MalformedInput, WrongClosingBracketInParenthesis) {
  parse("M:\n  a is Real: (1 + 2]\n");
  const std::string message = expect_diag(fe::DiagCode::UnexpectedToken, 2, 20);
  EXPECT_NE(message.find("`)`"), std::string::npos) << message;
}

TEST_F(MalformedInput, TypeMissingAfterIs) {
  parse("M:\n  a is\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 2, 7);
}

TEST_F(MalformedInput, ColonInsteadOfTypeAfterIs) {
  parse("M:\n  a is : 1\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 2, 8);
}

TEST_F(MalformedInput, TopLevelTypeMissingAfterIs) {
  parse("M is\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 1, 5);
  EXPECT_TRUE(doc_.decls.empty());
}

TEST_F(MalformedInput, OperatorDeclarationWithoutOperator) {
  parse("operator (a: Real)\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 1, 10);
  EXPECT_TRUE(doc_.decls.empty());
}

TEST_F(MalformedInput, OperatorDeclarationWithoutParentheses) {
  parse("operator + a\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 1, 12);
}

TEST_F(MalformedInput, OperatorParameterWithoutColon) {
  parse("operator +(a Real)\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 1, 14);
}

TEST_F(MalformedInput, MethodParameterWithoutColon) {
  parse("M:\n  fn f(a Real)\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 2, 10);
}

TEST_F(MalformedInput, ImportWithoutPath) {
  parse("import\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 1, 7);
  EXPECT_TRUE(doc_.decls.empty());
}

TEST_F(MalformedInput, ImportOfABareName) {
  parse("import foo\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 1, 8);
}

TEST_F(MalformedInput, WithWithoutTraitName) {
  parse("M:\n  with\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 2, 7);
}

TEST_F(MalformedInput, AnnotationWithoutName) {
  parse("M:\n  .: 1\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 2, 4);
}

TEST_F(MalformedInput, MemberStartingWithANumber) {
  parse("M:\n  3: 1\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 2, 3);
}

TEST_F(MalformedInput, TwoValuesOnOneLine) {
  parse("M:\n  a is Int: 1 2\n");
  const std::string message = expect_diag(fe::DiagCode::UnexpectedToken, 2, 15);
  EXPECT_NE(message.find("end of line"), std::string::npos) << message;
}

TEST_F(MalformedInput, IndentedTopLevelDeclaration) {
  parse("  M:\n    a is Int\nN:\n  b is Int\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 1, 3);
  EXPECT_EQ(count(fe::DiagCode::UnexpectedToken), 1u);
  EXPECT_EQ(decl_names(), Names{"N"});
}

// ---------------------------------------------------------------------------------------------------------
// Lenient forms: warnings, and the declaration is kept

TEST_F(MalformedInput, DeeperLineAfterAMemberWithoutBlockIsAWarning) {
  parse("M:\n  .doc: \"x\"\n    a: 1\n");
  expect_diag(fe::DiagCode::UnexpectedIndent, 3, 5);
  ASSERT_EQ(decl_names(), Names{"M"});
  EXPECT_EQ(member_names(doc_.decls[0].body), (Names{"doc", "a"}));
  EXPECT_EQ(doc_.decls[0].body[1].kind, fe::MemberKind::Assignment);
  EXPECT_FALSE(sink_.has_errors());
}

TEST_F(MalformedInput, TopLevelTraitWithoutColon) {
  parse("trait X\n  a is Int\n");
  expect_diag(fe::DiagCode::MissingColon, 1, 8);
  ASSERT_EQ(decl_names(), Names{"X"});
  EXPECT_EQ(doc_.decls[0].kind, fe::DeclKind::Trait);
  EXPECT_TRUE(doc_.decls[0].has_body);
  EXPECT_EQ(member_names(doc_.decls[0].body), Names{"a"});
  EXPECT_FALSE(sink_.has_errors());
}

TEST_F(MalformedInput, ModelWithBaseWithoutColon) {
  parse("M is B\n  a is Int\n");
  expect_diag(fe::DiagCode::MissingColon, 1, 7);
  ASSERT_EQ(decl_names(), Names{"M"});
  EXPECT_EQ(member_names(doc_.decls[0].body), Names{"a"});
}

TEST_F(MalformedInput, MissingColonPointsAfterTheNameNotPastATrailingComment) {
  // The `:` belongs right after `X`, as for `trait X` without a comment (1:8).
  parse("trait X  # note\n  a is Int\n");
  expect_diag(fe::DiagCode::MissingColon, 1, 8);
  ASSERT_EQ(decl_names(), Names{"X"});
}

TEST_F(MalformedInput, MemberMissingColonPointsAfterTheTypeNotPastATrailingComment) {
  parse("M:\n  a is T  # note\n    b: 1\n");
  expect_diag(fe::DiagCode::MissingColon, 2, 9);
}

TEST_F(MalformedInput, MemberAttributeWithoutColon) {
  parse("M:\n  a is T\n    b: 1\n");
  expect_diag(fe::DiagCode::MissingColon, 2, 9);
  ASSERT_EQ(decl_names(), Names{"M"});
  ASSERT_EQ(member_names(doc_.decls[0].body), Names{"a"});
  EXPECT_TRUE(doc_.decls[0].body[0].has_block);
  EXPECT_EQ(member_names(doc_.decls[0].body[0].block), Names{"b"});
}

// ---------------------------------------------------------------------------------------------------------
// Structural errors

TEST_F(MalformedInput, ParenthesesNestedTooDeep) {
  // The model body is level 1 and the value level 2, so the 199th `(` opens level 201.
  parse("M:\n  a is Real: " + std::string(199, '(') + "1" + std::string(199, ')') + "\n  b is Int\n");
  expect_diag(fe::DiagCode::NestingTooDeep, 2, 14 + 199);
  EXPECT_EQ(count(fe::DiagCode::NestingTooDeep), 1u);
  ASSERT_EQ(decl_names(), Names{"M"});
  EXPECT_EQ(member_names(doc_.decls[0].body), Names{"b"});
}

TEST_F(MalformedInput, ParenthesesJustWithinTheLimit) {
  parse("M:\n  a is Real: " + std::string(198, '(') + "1" + std::string(198, ')') + "\n");
  ASSERT_EQ(decl_names(), Names{"M"});
  ASSERT_EQ(member_names(doc_.decls[0].body), Names{"a"});
  EXPECT_EQ(doc_.expr(*doc_.decls[0].body[0].value).kind, fe::ExprKind::Int);
}

TEST_F(MalformedInput, AnnotationValueIsAName) {
  parse("M:\n  .meta: leaf\n");
  expect_diag(fe::DiagCode::AnnotationNotConstant, 2, 10);
}

TEST_F(MalformedInput, AnnotationValueIsAnExpression) {
  parse("M:\n  .x: 1 + 2\n  .y: -1\n");
  expect_diag(fe::DiagCode::AnnotationNotConstant, 2, 7);
  ASSERT_EQ(decl_names(), Names{"M"});
  EXPECT_EQ(member_names(doc_.decls[0].body), Names{"y"});  // a negative number is a constant
}

TEST_F(MalformedInput, MethodInANestedBlock) {
  parse("M:\n  a is T:\n    fn f()\n    c: 1\n");
  expect_diag(fe::DiagCode::MisplacedDeclaration, 3, 5);
  ASSERT_EQ(decl_names(), Names{"M"});
  ASSERT_EQ(member_names(doc_.decls[0].body), Names{"a"});
  EXPECT_EQ(member_names(doc_.decls[0].body[0].block), Names{"c"});
}

TEST_F(MalformedInput, OperatorInsideAModel) {
  parse("M:\n  operator +(a: Real)\n");
  expect_diag(fe::DiagCode::MisplacedDeclaration, 2, 3);
}

TEST_F(MalformedInput, WithAtTopLevel) {
  parse("with T\nM:\n  a is Int\n");
  expect_diag(fe::DiagCode::MisplacedDeclaration, 1, 1);
  EXPECT_EQ(decl_names(), Names{"M"});
}

TEST_F(MalformedInput, MethodAtTopLevel) {
  parse("fn f()\n");
  expect_diag(fe::DiagCode::MisplacedDeclaration, 1, 1);
}

TEST_F(MalformedInput, ImportInsideAModel) {
  parse("M:\n  import @\"x.openplx\"\n");
  expect_diag(fe::DiagCode::MisplacedDeclaration, 2, 3);
}

TEST_F(MalformedInput, TraitUsingWith) {
  parse("trait X with Y:\n  a is Int\n");
  expect_diag(fe::DiagCode::MisplacedDeclaration, 1, 9);
  EXPECT_TRUE(doc_.decls.empty());
}

TEST_F(MalformedInput, ConstGlobalAttribute) {
  parse("const P is Real: 3.0\n");
  expect_diag(fe::DiagCode::MisplacedDeclaration, 1, 1);
  EXPECT_TRUE(doc_.decls.empty());
}

TEST_F(MalformedInput, ModelWithAUnionBase) {
  parse("M is A or B:\n  a is Int\nN:\n  b is Int\n");
  expect_diag(fe::DiagCode::InvalidModelBase, 1, 6);
  EXPECT_EQ(count(fe::DiagCode::InvalidModelBase), 1u);
  EXPECT_EQ(decl_names(), Names{"N"});
}

TEST_F(MalformedInput, ModelWithAnArrayBase) {
  parse("M is A[]\n");
  expect_diag(fe::DiagCode::InvalidModelBase, 1, 6);
}

TEST_F(MalformedInput, DollarPathInAnAttributeValue) {
  parse("M:\n  p is String: $\"x\"\n");
  expect_diag(fe::DiagCode::DollarPathOutsideImport, 2, 16);
}

TEST_F(MalformedInput, DollarPathInAGlobalAttribute) {
  parse("P is String: $\"x\"\n");
  expect_diag(fe::DiagCode::DollarPathOutsideImport, 1, 14);
}

// ---------------------------------------------------------------------------------------------------------
// Recovery: every error is reported, the good declarations survive, no cascades

TEST_F(MalformedInput, EveryErrorOfAFileIsReportedAndGoodDeclarationsSurvive) {
  parse(
      "import foo\n"               // 1: unexpected-token at `foo`
      "Good1:\n"                   // 2
      "  a is Real: 1.0\n"         // 3
      "  b is Real: 2 +* 3\n"      // 4: unexpected-token at `*`
      "  c Real\n"                 // 5: expected-is at `Real`
      "  d is Int: 4\n"            // 6
      "Bad is A or B:\n"           // 7: invalid-model-base
      "  x is Int\n"               // 8
      "Good2 is Good1:\n"          // 9
      "  .x: leaf\n"               // 10: annotation-not-constant
      "  e is String: \"ok\"\n");  // 11
  expect_diag(fe::DiagCode::UnexpectedToken, 1, 8);
  expect_diag(fe::DiagCode::UnexpectedToken, 4, 17);
  EXPECT_EQ(expect_diag(fe::DiagCode::ExpectedIs, 5, 5), "Expected an is keyword");
  expect_diag(fe::DiagCode::InvalidModelBase, 7, 8);
  expect_diag(fe::DiagCode::AnnotationNotConstant, 10, 7);
  EXPECT_EQ(sink_.diagnostics().size(), 5u) << all_diags();
  ASSERT_EQ(decl_names(), (Names{"Good1", "Good2"}));
  EXPECT_EQ(member_names(doc_.decls[0].body), (Names{"a", "d"}));
  EXPECT_EQ(member_names(doc_.decls[1].body), Names{"e"});
  ASSERT_TRUE(doc_.decls[1].base.has_value());
  EXPECT_EQ(fe::to_string(*doc_.decls[1].base), "Good1");
}

TEST_F(MalformedInput, LexicalAndSyntaxErrorsInOneFile) {
  parse(
      "M:\n"                     // 1
      "  b is String: \"open\n"  // 2: unterminated-string
      "  c is Int: 1)\n"         // 3: unmatched-bracket
      "  d is Int: 2\n"          // 4
      "trait T with U\n"         // 5: misplaced-declaration
      "N:\n"                     // 6
      "\ta is Int\n"             // 7: tab-indentation
      "O:\n"                     // 8
      "  e is Real[]: [1, 2\n"   // 9: unclosed-bracket
      "  f is Int: 3\n");        // 10
  expect_diag(fe::DiagCode::UnterminatedString, 2, 16);
  expect_diag(fe::DiagCode::UnmatchedBracket, 3, 14);
  expect_diag(fe::DiagCode::MisplacedDeclaration, 5, 9);
  expect_diag(fe::DiagCode::TabIndentation, 7, 1);
  expect_diag(fe::DiagCode::UnclosedBracket, 9, 16);
  EXPECT_EQ(sink_.diagnostics().size(), 5u) << all_diags();
  ASSERT_EQ(decl_names(), (Names{"M", "N", "O"}));
  EXPECT_EQ(member_names(doc_.decls[0].body), (Names{"b", "d"}));
  EXPECT_EQ(member_names(doc_.decls[1].body), Names{"a"});
  EXPECT_EQ(member_names(doc_.decls[2].body), Names{"f"});
}

TEST_F(MalformedInput, EachBadLineGivesExactlyOneError) {
  parse("M:\n  a is Real: 2 +* 3\n  b is Real: 2 +* 3\n  c is Real: 1\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 2, 17);
  expect_diag(fe::DiagCode::UnexpectedToken, 3, 17);
  EXPECT_EQ(count(fe::DiagCode::UnexpectedToken), 2u);
  ASSERT_EQ(decl_names(), Names{"M"});
  EXPECT_EQ(member_names(doc_.decls[0].body), Names{"c"});
}

TEST_F(MalformedInput, BadLineInANestedBlockDropsOnlyThatLine) {
  parse("M:\n  a is T:\n    b: 2 +* 3\n    c: 1\n  d is Int\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 3, 11);
  EXPECT_EQ(sink_.diagnostics().size(), 1u);
  ASSERT_EQ(decl_names(), Names{"M"});
  ASSERT_EQ(member_names(doc_.decls[0].body), (Names{"a", "d"}));
  EXPECT_EQ(member_names(doc_.decls[0].body[0].block), Names{"c"});
}

TEST_F(MalformedInput, BrokenHeadSkipsItsBlockWithoutFurtherErrors) {
  parse("M:\n  a Real:\n    b: 1\n    c d e\n  f is Int\n");
  EXPECT_EQ(expect_diag(fe::DiagCode::ExpectedIs, 2, 5), "Expected an is keyword");
  EXPECT_EQ(sink_.diagnostics().size(), 1u);
  ASSERT_EQ(decl_names(), Names{"M"});
  EXPECT_EQ(member_names(doc_.decls[0].body), Names{"f"});
}

TEST_F(MalformedInput, InvalidCharacterIsNotReportedAgainByTheParser) {
  parse("M!:\n  a is Int\nN:\n  b is Int\n");
  expect_diag(fe::DiagCode::InvalidCharacter, 1, 2);
  EXPECT_EQ(sink_.diagnostics().size(), 1u) << all_diags();
  EXPECT_EQ(decl_names(), Names{"N"});
}

// ---------------------------------------------------------------------------------------------------------
// Source ranges

TEST_F(MalformedInput, MemberRangeCoversTheLineWithoutTheComment) {
  parse("M:\n  a is Real: 1.5  # comment\n  b: 2\n");
  ASSERT_EQ(decl_names(), Names{"M"});
  ASSERT_EQ(doc_.decls[0].body.size(), 2u);
  const fe::Member& a = doc_.decls[0].body[0];
  EXPECT_EQ(pos(a.range.begin).line, 2u);
  EXPECT_EQ(pos(a.range.begin).col, 3u);
  EXPECT_EQ(pos(a.range.end).line, 2u);
  EXPECT_EQ(pos(a.range.end).col, 17u);  // just after `1.5`
  const fe::Member& b = doc_.decls[0].body[1];
  EXPECT_EQ(pos(b.range.begin).line, 3u);
  EXPECT_EQ(pos(b.range.end).col, 7u);
}

TEST_F(MalformedInput, DeclRangeEndsAtItsLastMemberAfterAnError) {
  parse("M:\n  a is T:\n    b: 1\n  c is Int: 2 +* 3\nN:\n  d is Int\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 4, 16);
  ASSERT_EQ(decl_names(), (Names{"M", "N"}));
  const fe::Decl& m = doc_.decls[0];
  EXPECT_EQ(pos(m.range.begin).line, 1u);
  EXPECT_EQ(pos(m.range.begin).col, 1u);
  EXPECT_LE(pos(m.range.end).line, 4u);  // never into N
  const fe::Member& a = m.body[0];
  EXPECT_EQ(pos(a.range.begin).line, 2u);
  EXPECT_EQ(pos(a.range.end).line, 3u);
  EXPECT_EQ(pos(a.range.end).col, 9u);  // after `b: 1`
  const fe::Decl& n = doc_.decls[1];
  EXPECT_EQ(pos(n.range.begin).line, 5u);
  EXPECT_EQ(pos(n.range.end).line, 6u);
  EXPECT_EQ(pos(n.range.end).col, 11u);
}

TEST_F(MalformedInput, DiagnosticRangeOfAMalformedNumberCoversTheWholeToken) {
  parse("M:\n  a is Real: 12ab\n");
  expect_diag(fe::DiagCode::MalformedNumber, 2, 14);
  ASSERT_EQ(sink_.diagnostics().size(), 1u);
  const fe::SourceRange r = sink_.diagnostics()[0].range;
  EXPECT_EQ(r.end - r.begin, 4u);
}

}  // namespace
