#include "tests/support/eval_fixture.h"

namespace {

class EvalSmoke : public openplx::testing::EvalTest {};

TEST_F(EvalSmoke, OwnedChildrenReferencesAndMath) {
  ASSERT_TRUE(
      load("Inner:\n"
           "    v is Real: 0.0\n"
           "Root:\n"
           "    inner is Inner:\n"
           "          v: 7.0\n"
           "    ref is Inner: inner\n"
           "    p is Math.Vec3: Math.Vec3.from_xyz(1, 2, 3)\n"
           "    q is Math.Vec3: {2, 4, 6} / 2\n"
           "    d is Real: p * q\n"))
      << all_diags();
  EXPECT_EQ(value("inner.v"), "7.0");
  EXPECT_EQ(value("ref"), "-> inner");
  EXPECT_EQ(object("ref"), object("inner"));
  EXPECT_EQ(value("q"), "{1.0, 2.0, 3.0}");
  EXPECT_EQ(real("d"), 14.0);
}

}  // namespace
