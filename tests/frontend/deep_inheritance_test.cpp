// Long inheritance chains and trait diamonds: a model's linearization is built when first asked for (one
// list for the model used, not one per model of the chain), and an attribute declared again below an
// ancestor is still found, with the message it always had. Sizes are small; the time a 10,000-model chain
// takes is bench/scaling.sh's to show, not a test's.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/support/eval_fixture.h"

namespace {

namespace fe = openplx::frontend;

// `M0` declares a0; each `Mk is M(k-1)` declares ak = k; the root model `Scene is M(n-1)`.
std::string chain(int n, const std::string& last_extra = "") {
  std::string text = "M0:\n    a0 is Real: 0\n";
  for (int k = 1; k < n; ++k) {
    text += "M" + std::to_string(k) + " is M" + std::to_string(k - 1) + ":\n    a" + std::to_string(k) +
            " is Real: " + std::to_string(k) + "\n";
  }
  return text + "Scene is M" + std::to_string(n - 1) + (last_extra.empty() ? "\n" : ":\n" + last_extra);
}

class DeepInheritance : public openplx::testing::EvalTest {
 protected:
  std::vector<std::string> linearization_names(const fe::ModelInfo* model) {
    std::vector<std::string> names;
    for (const fe::ModelInfo* m : model->linearization()) names.push_back(m->name);
    return names;
  }
  const fe::ModelInfo* root_type() { return evaluator_->graph().at(root_).type; }
};

TEST_F(DeepInheritance, ChainOf2000ModelsHasEveryInheritedAttribute) {
  ASSERT_TRUE(load(chain(2000, "    a1999: -1\n"))) << all_diags();
  EXPECT_EQ(value("a0"), "0.0");
  EXPECT_EQ(value("a1234"), "1234.0");
  EXPECT_EQ(value("a1999"), "-1.0");  // the root's own assignment wins over the declaration's default
  const fe::ModelInfo* scene = root_type();
  ASSERT_EQ(scene->linearization().size(), 2001u);
  EXPECT_EQ(scene->linearization().front()->name, "Scene");
  EXPECT_EQ(scene->linearization()[1]->name, "M1999");
  EXPECT_EQ(scene->linearization().back()->name, "M0");
  EXPECT_TRUE(scene->is_subtype_of(scene->linearization().back()));
  EXPECT_FALSE(scene->linearization().back()->is_subtype_of(scene));
}

TEST_F(DeepInheritance, AttributeDeclaredAgainFarBelowItsAncestorIsReported) {
  EXPECT_FALSE(load(chain(500, "    a3 is Real: 9\n")));
  expect_diag_containing(fe::DiagCode::DuplicateAttribute,
                         "Duplicate attribute name a3 (already declared in M3)");
}

TEST_F(DeepInheritance, SameNameInUnrelatedModelsIsNoClash) {
  ASSERT_TRUE(
      load("A:\n    x is Real: 1\n"
           "B:\n    x is Real: 2\n"
           "C is B:\n    y is Real: 3\n"
           "Scene:\n    a is A\n    c is C\n"))
      << all_diags();
  EXPECT_EQ(value("a.x"), "1.0");
  EXPECT_EQ(value("c.x"), "2.0");
}

TEST_F(DeepInheritance, TraitInjectingAnAttributeOfADeepBaseIsReported) {
  EXPECT_FALSE(load("trait T:\n    a2 is Real: 5\n" + chain(300, "    with T\n")));
  expect_diag_containing(fe::DiagCode::DuplicateAttribute, "Duplicate attribute name a2 in Scene");
}

TEST_F(DeepInheritance, OwnAttributeClashingWithATraitBelowALongChainIsReported) {
  EXPECT_FALSE(load("trait T:\n    x is Real: 5\n" + chain(300, "    with T\n    x is Real: 1\n")));
  expect_diag_containing(fe::DiagCode::TraitRestriction, "Trait T injects attribute x which already exists");
}

TEST_F(DeepInheritance, LinearizationOfTraitDiamondsListsEachModelOnceInOrder) {
  // Self, each trait with its parents (each model the first time it is met), then the base's.
  ASSERT_TRUE(
      load("trait Z:\n    z is Int: 0\n"
           "trait L is Z:\n    l is Int: 1\n"
           "trait W:\n    w is Int: 2\n"
           "Base:\n    with L\n    b is Int: 3\n"
           "Mid is Base:\n    with W\n    with Z\n    m is Int: 4\n"
           "Scene is Mid:\n    with L\n    s is Int: 5\n"))
      << all_diags();
  EXPECT_EQ(linearization_names(root_type()),
            (std::vector<std::string>{"Scene", "L", "Z", "Mid", "W", "Base"}));
  EXPECT_EQ(value("z"), "0");
  EXPECT_EQ(value("s"), "5");
}

TEST_F(DeepInheritance, ChainWrittenLastModelFirstIsResolvedWithoutDeepRecursion) {
  // Each model names a base declared after it: resolving the first one would recurse 20,000 levels.
  const int n = 20000;
  std::string text = "Scene is M" + std::to_string(n - 1) + "\n";
  for (int k = n - 1; k > 0; --k) {
    text += "M" + std::to_string(k) + " is M" + std::to_string(k - 1) + ":\n    a" + std::to_string(k) +
            " is Real: " + std::to_string(k) + "\n";
  }
  text += "M0:\n    a0 is Real: 0\n";
  ASSERT_TRUE(load(text, "Scene")) << all_diags();
  EXPECT_EQ(value("a0"), "0.0");
  EXPECT_EQ(value("a19999"), "19999.0");
  EXPECT_EQ(root_type()->linearization().size(), static_cast<size_t>(n + 1));
}

TEST_F(DeepInheritance, CycleInALongChainIsReported) {
  std::string text = chain(200);
  text.replace(0, 2, "M0 is M199");  // `M0:` becomes `M0 is M199:`
  EXPECT_FALSE(load(text));
  accept_all_diags();
  bool cyclic = false;
  for (const fe::Diagnostic& d : sink_.diagnostics())
    cyclic = cyclic || d.code == fe::DiagCode::CyclicInheritance;
  EXPECT_TRUE(cyclic);
}

}  // namespace
