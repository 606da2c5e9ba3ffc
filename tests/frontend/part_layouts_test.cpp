// A part's layout is worked out once per owner reach state, attribute and type, then copied
// (Evaluator::build_slots): the parts of instances that enclosing entries reach differently must still get
// their own bindings, and those of instances reached alike must share one layout.
#include <gtest/gtest.h>

#include "tests/support/eval_fixture.h"

namespace fe = openplx::frontend;

namespace {

class PartLayouts : public openplx::testing::EvalTest {};

TEST_F(PartLayouts, PartsReachedDifferentlyKeepTheirOwnValues) {
  ASSERT_TRUE(
      load("Part:\n"
           "    x is Real: 1\n"
           "    inner is Inner\n"
           "Inner:\n"
           "    y is Real: 10\n"
           "Holder:\n"
           "    part is Part\n"
           "Scene:\n"
           "    a is Holder\n"
           "    b is Holder:\n"
           "        part.x: 2\n"
           "    c is Holder\n"
           "    d is Holder\n"
           "    d.part.inner.y: 30\n"
           "    e is Holder:\n"
           "        part.inner.y: 40\n"
           "    f is Holder\n"))
      << all_diags();
  EXPECT_DOUBLE_EQ(real("a.part.x"), 1);
  EXPECT_DOUBLE_EQ(real("b.part.x"), 2);
  EXPECT_DOUBLE_EQ(real("c.part.x"), 1);
  EXPECT_DOUBLE_EQ(real("d.part.x"), 1);
  EXPECT_DOUBLE_EQ(real("a.part.inner.y"), 10);
  EXPECT_DOUBLE_EQ(real("b.part.inner.y"), 10);
  EXPECT_DOUBLE_EQ(real("d.part.inner.y"), 30);
  EXPECT_DOUBLE_EQ(real("e.part.inner.y"), 40);
  EXPECT_DOUBLE_EQ(real("f.part.inner.y"), 10);
  // Reached alike: a, c and f share their parts' layouts; b, d and e do not share a's.
  const auto layout = [&](const std::string& path) { return evaluator_->graph().at(object(path)).layout; };
  EXPECT_EQ(layout("a.part"), layout("c.part"));
  EXPECT_EQ(layout("a.part.inner"), layout("f.part.inner"));
  EXPECT_NE(layout("a.part"), layout("b.part"));
  EXPECT_NE(layout("a.part.inner"), layout("d.part.inner"));
  EXPECT_NE(layout("a.part.inner"), layout("e.part.inner"));
}

}  // namespace
