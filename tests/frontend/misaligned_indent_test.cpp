// A line shallower than its nested block but deeper than the line that opened it (the 0.20.2 release's
// TIM150.openplx, column 12 in a block at 13 opened at 9): AGX takes it into the block, and so do we, with a
// `misaligned-indent` warning. The spec's errors stay errors: the same layout in a top-level declaration's
// block (its case 4), tabs, and a dedent that lands on no column at all.
#include <gtest/gtest.h>

#include "frontend/syntax/parser.h"
#include "tests/support/parse_fixture.h"

namespace {

namespace fe = openplx::frontend;
using Names = std::vector<std::string>;

class MisalignedIndent : public openplx::testing::ParseTest {
 protected:
  static Names names(const std::vector<fe::Member>& members) {
    Names out;
    for (const fe::Member& m : members) out.push_back(fe::to_string(m.path));
    return out;
  }
};

TEST_F(MisalignedIndent, LineOneColumnShortStaysInItsNestedBlock) {
  // TIM150's shape: the two lines at column 12 belong to `noise`, and `after` to the outer block again.
  parse(
      "Lidar:\n"
      "    logic is Logic:\n"
      "        noise is Noise:\n"
      "            mean: 0.0\n"
      "           deviation: 0\n"
      "           slope: 3e-3\n"
      "        after: [noise]\n");
  const std::string message = expect_diag(fe::DiagCode::MisalignedIndent, 5, 12);
  EXPECT_NE(message.find("column 13"), std::string::npos) << message;
  EXPECT_NE(message.find("column 9"), std::string::npos) << message;
  EXPECT_EQ(count(fe::DiagCode::MisalignedIndent), 1u);  // the block goes on at column 12: one warning
  ASSERT_EQ(doc_.decls.size(), 1u);
  const fe::Member& logic = doc_.decls[0].body.at(0);
  EXPECT_EQ(names(logic.block), (Names{"noise", "after"}));
  EXPECT_EQ(names(logic.block.at(0).block), (Names{"mean", "deviation", "slope"}));
}

TEST_F(MisalignedIndent, TheBlockContinuesAtTheLinesColumn) {
  // After the short line (column 8), a line that opens a block gets its own deeper block; a line at column 9
  // is then deeper than `d` (opened at 8) and short of its block (12): it is d's, as the rule reads it.
  parse(
      "A:\n"
      "    b is B:\n"
      "        c: 1\n"
      "       d is D:\n"
      "           e: 2\n"
      "        f: 3\n"
      "       g: 4\n"
      "    h: 5\n");
  expect_diag(fe::DiagCode::MisalignedIndent, 4, 8);
  expect_diag(fe::DiagCode::MisalignedIndent, 6, 9);
  const fe::Member& b = doc_.decls.at(0).body.at(0);
  EXPECT_EQ(names(b.block), (Names{"c", "d", "g"}));
  EXPECT_EQ(names(b.block.at(1).block), (Names{"e", "f"}));
  EXPECT_EQ(names(doc_.decls[0].body), (Names{"b", "h"}));
}

TEST_F(MisalignedIndent, ClosesDeeperBlocksFirst) {
  // Column 8 closes the block at 13, then lands inside the block at 9 opened at 5.
  parse(
      "A:\n"
      "    b is B:\n"
      "        c is C:\n"
      "            d: 1\n"
      "       e: 2\n");
  expect_diag(fe::DiagCode::MisalignedIndent, 5, 8);
  const fe::Member& b = doc_.decls.at(0).body.at(0);
  EXPECT_EQ(names(b.block), (Names{"c", "e"}));
}

TEST_F(MisalignedIndent, TopLevelBlocksKeepTheSpecsError) {
  // ../shared/spec/openplx-language.md appendix case 4: `Root:` / 4 spaces / 2 spaces.
  parse("Root:\n    a is Int: 1\n  b is Int: 2\n");
  expect_diag(fe::DiagCode::InconsistentDedent, 3, 3);
  EXPECT_EQ(count(fe::DiagCode::MisalignedIndent), 0u);
}

TEST_F(MisalignedIndent, TabsAreStillErrors) {
  parse("A:\n    b is B:\n        c: 1\n\t   d: 2\n");
  expect_diag(fe::DiagCode::TabIndentation, 4, 1);
  accept_all_diags();
}

TEST_F(MisalignedIndent, IsAnErrorUnderStrict) {
  fe::DiagnosticSink strict(true);
  const fe::FileId id = sources_.add("strict.openplx", "A:\n    b is B:\n        c: 1\n       d: 2\n");
  fe::parse_file(sources_, id, strict);
  EXPECT_EQ(strict.error_count(), 1u);
}

}  // namespace
