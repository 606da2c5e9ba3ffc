// Appendix B of ../shared/spec/openplx-language.md, checked semantically: each case is loaded, instantiated
// and evaluated, and its expected values (or its expected diagnostic) are asserted. One test per case
// (CaseNN_...). Snippets given inline in the spec ("`Root:` / `a is Int: 1`") are rebuilt with 4-space
// indentation; attribute-only snippets are placed in a `Root:` model. Where the expected result depends on a
// proposal of the spec ((prop) / UNSPECIFIED), a comment names the decision the test pins.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "frontend/evaluation/value_format.h"
#include "frontend/syntax/ast.h"
#include "frontend/syntax/ast_dump.h"
#include "tests/support/eval_fixture.h"

namespace {

namespace fe = openplx::frontend;

class AppendixBEval : public openplx::testing::EvalTest {
 protected:
  // The type name of the instance at `path` ("" = the root), or "<none>".
  std::string type_name(const std::string& path) {
    const fe::ObjectId id = object(path);
    return id == fe::kNoObject ? "<none>" : evaluator_->graph().at(id).type->name;
  }
  // Number of instances in the graph whose type is named `name`.
  size_t instances_of(const std::string& name) const {
    size_t n = 0;
    const auto& objects = evaluator_->graph().objects;
    for (size_t i = 0; i < objects.size(); ++i) n += objects[i].type && objects[i].type->name == name;
    return n;
  }
  // An annotation constant as text: strings unquoted, Ints as digits, Bools as true/false.
  static std::string constant(const fe::Document& doc, fe::ExprId id) {
    const fe::Expr& e = doc.expr(id);
    switch (e.kind) {
      case fe::ExprKind::String:
        return e.string_value;
      case fe::ExprKind::Int:
        return e.int_value ? std::to_string(*e.int_value) : std::string(e.text);
      case fe::ExprKind::Bool:
        return e.bool_value ? "true" : "false";
      default:
        return fe::expr_to_string(doc, id);
    }
  }
  // The annotation `name` of the attribute at `path`, or "<none>".
  std::string slot_annotation(const std::string& path, const std::string& name) {
    const fe::Slot* s = slot(path);
    if (!s) return "<no slot>";
    if (!s->annotations()) return "<none>";
    auto it = s->annotations()->find(name);
    return it == s->annotations()->end() ? "<none>" : constant(*it->second.doc, it->second.expr);
  }
  // The model annotation `name` of the root's type, or "<none>".
  std::string root_annotation(const std::string& name) {
    const fe::ModelInfo* type = evaluator_->graph().at(root_).type;
    auto it = type->annotations.find(name);
    return it == type->annotations.end() ? "<none>" : constant(type->doc->doc, it->second);
  }
  // The Shop bundle of cases 95-101 under <D>/B: config (plus `config_body`) and Items/Tools.openplx.
  void write_shop(const std::string& config_body = "") {
    write("B/shop/config.openplx", "config is BundleConfig:\n    name: \"Shop\"\n" + config_body);
    write("B/shop/Items/Tools.openplx", "Hammer:\n    kg is Real: 1.2\n");
  }
  bool load_with_bundles(const std::string& path, const char* model = nullptr) {
    return load_file(path, model, {dir() + "/B"});
  }
};

// ---------------------------------------------------------------- Lexical and layout

TEST_F(AppendixBEval, Case01_CommentsEverywhere) {
  ASSERT_TRUE(
      load("# top comment\n"
           "Root:   # after head\n"
           "    a is Real: 2.5  # after value\n"))
      << all_diags();
  EXPECT_EQ(value("a"), "2.5");
}

TEST_F(AppendixBEval, Case02_TwoSpaceIndentation) {
  ASSERT_TRUE(load("Root:\n  a is Int: 1\n  b is Int: 2\n")) << all_diags();
  EXPECT_EQ(value("a"), "1");
  EXPECT_EQ(value("b"), "2");
}

TEST_F(AppendixBEval, Case03_RelativeChildDepth) {
  ASSERT_TRUE(
      load("Inner:\n"
           "    v is Real: 0.0\n"
           "Root:\n"
           "    inner is Inner:\n"
           "          v: 7.0\n"
           "    w is Real: 1.0\n"))
      << all_diags();
  EXPECT_EQ(value("inner.v"), "7.0");
  EXPECT_EQ(value("w"), "1.0");
}

TEST_F(AppendixBEval, Case04_DedentToUnknownColumn) {
  // (prop) dedenting to a column not on the indentation stack is `inconsistent-dedent`.
  EXPECT_FALSE(load("Root:\n    a is Int: 1\n  b is Int: 2\n"));
  expect_diag(fe::DiagCode::InconsistentDedent, 3, 3);
}

TEST_F(AppendixBEval, Case05_Exponents) {
  // (prop) lower-case `e` is accepted as the exponent letter.
  ASSERT_TRUE(load("Root:\n    g is Real: 2E3\n    h is Real: 1.5e-2\n")) << all_diags();
  EXPECT_EQ(value("g"), "2000.0");
  EXPECT_EQ(value("h"), "0.015");
  EXPECT_EQ(real("h"), 0.015);
}

TEST_F(AppendixBEval, Case06_IntLiteralIntoReal) {
  ASSERT_TRUE(load("Root:\n    r is Real: 4\n")) << all_diags();
  EXPECT_EQ(value("r"), "4.0");
  ASSERT_NE(slot("r"), nullptr);
  EXPECT_EQ(slot("r")->value.kind, fe::Value::Kind::Real);
  EXPECT_EQ(slot("r")->type()->kind, fe::TypeKind::Real);
}

TEST_F(AppendixBEval, Case07_IntegralRealIntoInt) {
  ASSERT_TRUE(load("Root:\n    i is Int: 6.0\n")) << all_diags();
  EXPECT_EQ(value("i"), "6");
  ASSERT_NE(slot("i"), nullptr);
  EXPECT_EQ(slot("i")->value.kind, fe::Value::Kind::Int);
}

TEST_F(AppendixBEval, Case08_NonIntegralRealIntoInt) {
  // (prop) Real→Int only for an integral value; otherwise a type-mismatch at the value.
  EXPECT_FALSE(load("Root:\n    i is Int: 6.5\n"));
  expect_diag(fe::DiagCode::TypeMismatch, 2, 15);
}

TEST_F(AppendixBEval, Case09_PlainStringWithHash) {
  ASSERT_TRUE(load("Root:\n    s is String: \"a b # not comment\"\n")) << all_diags();
  EXPECT_EQ(value("s"), "\"a b # not comment\"");
}

TEST_F(AppendixBEval, Case10_MultilineStringDoesNotDisturbIndentation) {
  ASSERT_TRUE(
      load("Root:\n"
           "    t is String: \"\"\"first\n"
           "second\"\"\"\n"
           "    n is Int: 3\n"))
      << all_diags();
  EXPECT_EQ(value("t"), "\"first\\nsecond\"");
  EXPECT_EQ(value("n"), "3");
}

TEST_F(AppendixBEval, Case11_PathString) {
  ASSERT_TRUE(load_file(write("scene.openplx", "Root:\n    p is String: @\"mesh/part.obj\"\n")))
      << all_diags();
  EXPECT_EQ(value("p"), "\"" + dir() + "/mesh/part.obj\"");
}

TEST_F(AppendixBEval, Case12_PathStringWithParentStep) {
  // (prop) `..` is normalised away.
  ASSERT_TRUE(load_file(write("scene.openplx", "Root:\n    q is String: @\"../x.txt\"\n"))) << all_diags();
  const std::string parent = std::filesystem::path(dir()).parent_path().generic_string();
  EXPECT_EQ(value("q"), "\"" + parent + "/x.txt\"");
}

TEST_F(AppendixBEval, Case13_BacktickName) {
  ASSERT_TRUE(
      load("Leaf:\n"
           "    k is Int: 4\n"
           "Root:\n"
           "    `a.b` is Leaf\n"))
      << all_diags();
  const fe::Object& root = evaluator_->graph().at(root_);
  ASSERT_EQ(root.slots.size(), 1u);
  EXPECT_EQ(root.slots[0].name(), "a.b");
  const fe::Value* ab = evaluator_->value(root_, "a.b");
  ASSERT_NE(ab, nullptr);
  ASSERT_EQ(ab->kind, fe::Value::Kind::Object);
  const fe::Value* k = evaluator_->value(ab->object, "k");
  ASSERT_NE(k, nullptr);
  EXPECT_EQ(fe::format_value(*evaluator_, *k, false), "4");
}

TEST_F(AppendixBEval, Case14_ImplicitLineJoining) {
  ASSERT_TRUE(load("Root:\n    zs is Int[]: [1,\n        2, 3]\n")) << all_diags();
  EXPECT_EQ(value("zs"), "[1, 2, 3]");
}

// ---------------------------------------------------------------- Document structure and completeness

TEST_F(AppendixBEval, Case15_LonelyModel) {
  ASSERT_TRUE(load("Lonely\n")) << all_diags();
  EXPECT_EQ(type_name(""), "Lonely");
  EXPECT_TRUE(evaluator_->graph().at(root_).slots.empty());
  EXPECT_EQ(values(), "");
}

TEST_F(AppendixBEval, Case16_EmptyDerivedModel) {
  ASSERT_TRUE(load("Base:\n    q is Int: 9\nAlias is Base\n", "Alias")) << all_diags();
  EXPECT_EQ(type_name(""), "Alias");
  EXPECT_EQ(value("q"), "9");
}

TEST_F(AppendixBEval, Case17_ColonWithoutBlock) {
  // The loader still looks for the root model after syntax errors, so both documented errors appear.
  EXPECT_FALSE(load("Broken:\n"));
  EXPECT_EQ(expect_diag(fe::DiagCode::ExpectedIndentedBlock, 1, 7), "Expected indented block");
  EXPECT_EQ(expect_diag(fe::DiagCode::NoModel, 1, 1), "No model could be found");
}

TEST_F(AppendixBEval, Case18_BareNameIsNotAMember) {
  EXPECT_FALSE(load("Thing:\n    speed\n"));
  EXPECT_EQ(expect_diag(fe::DiagCode::ExpectedIs, 2, 10), "Expected an is keyword");
}

TEST_F(AppendixBEval, Case19_MissingAssignment) {
  EXPECT_FALSE(load("Thing:\n    speed is Real\n"));
  EXPECT_EQ(expect_diag(fe::DiagCode::MissingAssignment, 2, 5),
            "Missing assignment Thing.speed, owning model is not complete");
}

TEST_F(AppendixBEval, Case20_IncompleteBaseCompleteDerived) {
  const char* text = "Base:\n    speed is Real\nCar is Base:\n    speed: 12.0\n";
  ASSERT_TRUE(load(text, "Car")) << all_diags();
  EXPECT_EQ(value("speed"), "12.0");
  EXPECT_FALSE(load(text, "Base"));
  EXPECT_EQ(expect_diag(fe::DiagCode::MissingAssignment, 2, 5),
            "Missing assignment Base.speed, owning model is not complete");
}

TEST_F(AppendixBEval, Case21_DefaultModelIsTheLast) {
  ASSERT_TRUE(load("A:\n    a is Int: 1\nB:\n    b is Int: 2\n")) << all_diags();
  EXPECT_EQ(type_name(""), "B");
  EXPECT_EQ(value("b"), "2");
  EXPECT_EQ(value("a"), "<missing>");
}

TEST_F(AppendixBEval, Case22_LoadNamedModel) {
  ASSERT_TRUE(load("A:\n    a is Int: 1\nB:\n    b is Int: 2\n", "A")) << all_diags();
  EXPECT_EQ(type_name(""), "A");
  EXPECT_EQ(value("a"), "1");
}

TEST_F(AppendixBEval, Case23_GlobalAttribute) {
  ASSERT_TRUE(load("scale is Real: 2.0\nRoot:\n    v is Real: scale * 3\n")) << all_diags();
  EXPECT_EQ(value("v"), "6.0");
}

TEST_F(AppendixBEval, Case24_ChainedGlobals) {
  ASSERT_TRUE(load("g1 is Int: 2\ng2 is Int: g1 * 5\nRoot:\n    c is Int: g2\n")) << all_diags();
  EXPECT_EQ(value("c"), "10");
}

TEST_F(AppendixBEval, Case25_Optional) {
  ASSERT_TRUE(load("Root:\n    optional label is String\n    n is Int: 1\n")) << all_diags();
  EXPECT_EQ(value("label"), "unset");
  ASSERT_NE(slot("label"), nullptr);
  EXPECT_TRUE(slot("label")->optional());
  EXPECT_EQ(value("n"), "1");
}

TEST_F(AppendixBEval, Case26_ReadingUnsetOptional) {
  // (prop) reading an unset optional is `unset-attribute`, reported where it is read.
  EXPECT_FALSE(load("Root:\n    optional label is String\n    n is Int: 1\n    m is String: label\n"));
  expect_diag(fe::DiagCode::UnsetAttribute, 4, 18);
}

TEST_F(AppendixBEval, Case27_TopLevelOrderDoesNotMatter) {
  // (prop) models may refer to models declared later in the same file.
  ASSERT_TRUE(
      load("Root:\n"
           "    p is Part\n"
           "Part:\n"
           "    m is Real: 1.5\n",
           "Root"))
      << all_diags();
  EXPECT_EQ(value("p.m"), "1.5");
}

// ---------------------------------------------------------------- Attributes, ownership, references

TEST_F(AppendixBEval, Case28_Bools) {
  ASSERT_TRUE(load("Root:\n    on is Bool: true\n    off is Bool: false\n")) << all_diags();
  EXPECT_EQ(value("on"), "true");
  EXPECT_EQ(value("off"), "false");
}

TEST_F(AppendixBEval, Case29_RealArrayWithInts) {
  ASSERT_TRUE(load("Root:\n    xs is Real[]: [1, 2.5, -3]\n")) << all_diags();
  EXPECT_EQ(value("xs"), "[1.0, 2.5, -3.0]");
}

TEST_F(AppendixBEval, Case30_EmptyArray) {
  ASSERT_TRUE(load("Root:\n    ys is Int[]: []\n")) << all_diags();
  EXPECT_EQ(value("ys"), "[]");
}

TEST_F(AppendixBEval, Case31_BadArrayElement) {
  // (prop) an array element that does not fit the element type is a type-mismatch, reported at that
  // element (2:19, `"x"`), not at the array literal.
  EXPECT_FALSE(load("Root:\n    zs is Int[]: [\"x\"]\n"));
  expect_diag(fe::DiagCode::TypeMismatch, 2, 19);
}

TEST_F(AppendixBEval, Case32_DistinctOwnedInstances) {
  ASSERT_TRUE(
      load("Wheel:\n"
           "    r is Real: 0.3\n"
           "Car:\n"
           "    front is Wheel\n"
           "    back is Wheel\n"))
      << all_diags();
  ASSERT_NE(object("front"), fe::kNoObject);
  ASSERT_NE(object("back"), fe::kNoObject);
  EXPECT_NE(object("front"), object("back"));
  EXPECT_EQ(value("front.r"), "0.3");
  EXPECT_EQ(value("back.r"), "0.3");
}

TEST_F(AppendixBEval, Case33_NestedAssignmentOnOneInstance) {
  ASSERT_TRUE(
      load("Wheel:\n"
           "    r is Real: 0.3\n"
           "Car:\n"
           "    front is Wheel:\n"
           "        r: 0.5\n"
           "    back is Wheel\n"))
      << all_diags();
  EXPECT_EQ(value("front.r"), "0.5");
  EXPECT_EQ(value("back.r"), "0.3");
}

TEST_F(AppendixBEval, Case34_NewAttributeInNestedBlock) {
  ASSERT_TRUE(
      load("Wheel:\n"
           "    r is Real: 0.3\n"
           "Car:\n"
           "    front is Wheel:\n"
           "        psi is Real: 2.2\n"
           "    back is Wheel\n"
           "    p is Real: front.psi\n"))
      << all_diags();
  EXPECT_EQ(value("p"), "2.2");
  EXPECT_EQ(value("front.psi"), "2.2");
  EXPECT_EQ(value("back.psi"), "<missing>");
}

TEST_F(AppendixBEval, Case35_Reference) {
  ASSERT_TRUE(
      load("Part:\n"
           "    m is Real: 1.0\n"
           "Holder:\n"
           "    a is Part:\n"
           "        m: 4.0\n"
           "    b is Part: a\n"))
      << all_diags();
  ASSERT_NE(object("a"), fe::kNoObject);
  EXPECT_EQ(object("b"), object("a"));
  EXPECT_EQ(value("b"), "-> a");
  EXPECT_EQ(value("b.m"), "4.0");
  EXPECT_TRUE(slot("a")->owns);
  EXPECT_FALSE(slot("b")->owns);
  EXPECT_EQ(instances_of("Part"), 1u);
}

TEST_F(AppendixBEval, Case36_ArrayOfReferences) {
  ASSERT_TRUE(
      load("Part:\n"
           "    m is Real: 1.0\n"
           "Holder:\n"
           "    a is Part\n"
           "    c is Part\n"
           "    all is Part[]: [a, c]\n"))
      << all_diags();
  const fe::Slot* all = slot("all");
  ASSERT_NE(all, nullptr);
  ASSERT_EQ(all->value.kind, fe::Value::Kind::Array);
  ASSERT_EQ(all->value.array().size(), 2u);
  EXPECT_EQ(all->value.array()[0].object, object("a"));
  EXPECT_EQ(all->value.array()[1].object, object("c"));
  EXPECT_EQ(value("all"), "[-> a, -> c]");
  EXPECT_EQ(instances_of("Part"), 2u);
}

TEST_F(AppendixBEval, Case37_ReferenceTypeCheck) {
  // (prop) a reference to an instance of an unrelated type is a type-mismatch at the value.
  EXPECT_FALSE(
      load("Part:\n"
           "    m is Real: 1.0\n"
           "Other:\n"
           "    z is Int: 0\n"
           "Holder:\n"
           "    o is Other\n"
           "    b is Part: o\n"));
  expect_diag(fe::DiagCode::TypeMismatch, 7, 16);
}

TEST_F(AppendixBEval, Case38_DuplicateAttribute) {
  // (prop) a second declaration of the same name is `duplicate-attribute` at the second one.
  EXPECT_FALSE(load("Root:\n    a is Int: 1\n    a is Int: 2\n"));
  expect_diag(fe::DiagCode::DuplicateAttribute, 3, 5);
}

// ---------------------------------------------------------------- Assignments and override order

TEST_F(AppendixBEval, Case39_DerivedOverride) {
  ASSERT_TRUE(load("Base:\n    x is Real: 0.0\nD is Base:\n    x: 2.0\n")) << all_diags();
  EXPECT_EQ(type_name(""), "D");
  EXPECT_EQ(value("x"), "2.0");
}

TEST_F(AppendixBEval, Case40_ChainWithLateBinding) {
  ASSERT_TRUE(
      load("A:\n"
           "    x is Real: 1.0\n"
           "B is A:\n"
           "    x: 2.0\n"
           "C is B:\n"
           "    y is Real: x + 1\n"))
      << all_diags();
  EXPECT_EQ(value("x"), "2.0");
  EXPECT_EQ(value("y"), "3.0");
}

TEST_F(AppendixBEval, Case41_DottedAssignment) {
  ASSERT_TRUE(
      load("In:\n"
           "    v is Real: 0.0\n"
           "Mid:\n"
           "    inner is In\n"
           "Top:\n"
           "    mid is Mid\n"
           "    mid.inner.v: 5.0\n"))
      << all_diags();
  EXPECT_EQ(value("mid.inner.v"), "5.0");
}

TEST_F(AppendixBEval, Case42_BlockAssignmentOnInheritedAttribute) {
  ASSERT_TRUE(
      load("In:\n"
           "    v is Real: 0.0\n"
           "    w is Real: 0.0\n"
           "Mid:\n"
           "    inner is In\n"
           "Top is Mid:\n"
           "    inner:\n"
           "        v: 1.0\n"
           "        w: 2.0\n"))
      << all_diags();
  EXPECT_EQ(value("inner.v"), "1.0");
  EXPECT_EQ(value("inner.w"), "2.0");
}

TEST_F(AppendixBEval, Case43_OwnerPriority) {
  const char* text =
      "Leaf:\n"
      "    k is Real: 1.0\n"
      "Box:\n"
      "    leaf is Leaf:\n"
      "        k: 2.0\n"
      "Outer:\n"
      "    box is Box:\n"
      "        leaf.k: 3.0\n"
      "Final is Outer:\n"
      "    box.leaf:\n"
      "        k: 4.0\n";
  ASSERT_TRUE(load(text, "Box")) << all_diags();
  EXPECT_EQ(value("leaf.k"), "2.0");
  ASSERT_TRUE(load(text, "Outer")) << all_diags();
  EXPECT_EQ(value("box.leaf.k"), "3.0");
  ASSERT_TRUE(load(text, "Final")) << all_diags();
  EXPECT_EQ(value("box.leaf.k"), "4.0");
}

TEST_F(AppendixBEval, Case44_ForwardUseInOneBody) {
  ASSERT_TRUE(load("Root:\n    b is Real: a * 2\n    a is Real: 5\n")) << all_diags();
  EXPECT_EQ(value("b"), "10.0");
  EXPECT_EQ(value("a"), "5.0");
}

TEST_F(AppendixBEval, Case45_UnknownTarget) {
  // (prop) an assignment to a name that is no attribute is `unknown-attribute` at the path.
  EXPECT_FALSE(load("Root:\n    nope: 3\n"));
  expect_diag(fe::DiagCode::UnknownAttribute, 2, 5);
}

TEST_F(AppendixBEval, Case46_SpaceBeforeColon) {
  ASSERT_TRUE(load("Base:\n    x is Int: 0\nD is Base:\n    x : 3\n")) << all_diags();
  EXPECT_EQ(value("x"), "3");
}

TEST_F(AppendixBEval, Case47_WrongType) {
  // (prop) Int into Bool is a type-mismatch at the value.
  EXPECT_FALSE(load("Root:\n    flag is Bool: 1\n"));
  expect_diag(fe::DiagCode::TypeMismatch, 2, 19);
}

TEST_F(AppendixBEval, Case48_DuplicateAssignment) {
  // (prop) one body assigning the same path twice is `duplicate-assignment` at the second assignment.
  EXPECT_FALSE(load("Base:\n    x is Int: 0\nD is Base:\n    x: 1\n    x: 2\n"));
  expect_diag(fe::DiagCode::DuplicateAssignment, 5, 5);
}

TEST_F(AppendixBEval, Case49_Cycle) {
  // (prop) a dependency cycle is `cyclic-dependency`, reported once, naming the attribute path.
  EXPECT_FALSE(load("Root:\n    a is Real: b\n    b is Real: a\n"));
  expect_diag_containing(fe::DiagCode::CyclicDependency, "Cyclic dependency detected at Root.");
  EXPECT_EQ(count(fe::DiagCode::CyclicDependency), 1u);
}

// ---------------------------------------------------------------- becomes and unions

const char* const kCase50 =
    "Shape:\n"
    "    area is Real: 0.0\n"
    "Square is Shape:\n"
    "    side is Real: 2.0\n"
    "    area: side * side\n"
    "Holder:\n"
    "    s is Shape\n"
    "Special is Holder:\n"
    "    s becomes Square\n";

TEST_F(AppendixBEval, Case50_Specialisation) {
  ASSERT_TRUE(load(kCase50, "Special")) << all_diags();
  EXPECT_EQ(type_name("s"), "Square");
  EXPECT_EQ(value("s"), "Square");
  EXPECT_EQ(value("s.area"), "4.0");
  ASSERT_TRUE(load(kCase50, "Holder")) << all_diags();
  EXPECT_EQ(type_name("s"), "Shape");
  EXPECT_EQ(value("s.area"), "0.0");
}

TEST_F(AppendixBEval, Case51_BecomesWithBlock) {
  ASSERT_TRUE(
      load("Shape:\n"
           "    area is Real: 0.0\n"
           "Square is Shape:\n"
           "    side is Real: 2.0\n"
           "    area: side * side\n"
           "Holder:\n"
           "    s is Shape\n"
           "Special is Holder:\n"
           "    s becomes Square:\n"
           "        side: 3.0\n"))
      << all_diags();
  EXPECT_EQ(type_name("s"), "Square");
  EXPECT_EQ(value("s.side"), "3.0");
  EXPECT_EQ(value("s.area"), "9.0");
}

TEST_F(AppendixBEval, Case52_IncompatibleBecomes) {
  // (prop) the message; the code is `incompatible-becomes`, reported at the new type.
  EXPECT_FALSE(load(std::string(kCase50) + "Other:\n    q is Int: 0\nBad is Holder:\n    s becomes Other\n"));
  expect_diag(fe::DiagCode::IncompatibleBecomes, 13, 15);
}

TEST_F(AppendixBEval, Case53_EarlierAssignmentSurvives) {
  // (prop) the owner's assignment (Holder's `area: 7.0`) beats Square's own default after `becomes`.
  ASSERT_TRUE(
      load("Shape:\n"
           "    area is Real: 0.0\n"
           "Square is Shape:\n"
           "    side is Real: 2.0\n"
           "    area: side * side\n"
           "Holder:\n"
           "    s is Shape:\n"
           "        area: 7.0\n"
           "Special is Holder:\n"
           "    s becomes Square\n"))
      << all_diags();
  EXPECT_EQ(type_name("s"), "Square");
  EXPECT_EQ(value("s.side"), "2.0");
  EXPECT_EQ(value("s.area"), "7.0");
}

const char* const kCase54 =
    "Cat:\n"
    "    lives is Int: 9\n"
    "Dog:\n"
    "    loud is Bool: true\n"
    "Home:\n"
    "    pet is Cat or Dog\n"
    "CatHome is Home:\n"
    "    pet becomes Cat\n";

TEST_F(AppendixBEval, Case54_UnionNarrowing) {
  ASSERT_TRUE(load(kCase54, "CatHome")) << all_diags();
  EXPECT_EQ(type_name("pet"), "Cat");
  EXPECT_EQ(value("pet.lives"), "9");
  // (prop) a union-typed attribute with no binding is incomplete.
  EXPECT_FALSE(load(kCase54, "Home"));
  EXPECT_EQ(expect_diag(fe::DiagCode::MissingAssignment, 6, 5),
            "Missing assignment Home.pet, owning model is not complete");
}

TEST_F(AppendixBEval, Case55_BecomesOutsideUnion) {
  EXPECT_FALSE(
      load("Wheel:\n"
           "    r is Real: 0.3\n"
           "Cat:\n"
           "    lives is Int: 9\n"
           "Dog:\n"
           "    loud is Bool: true\n"
           "Home:\n"
           "    pet is Cat or Dog\n"
           "CatHome is Home:\n"
           "    pet becomes Wheel\n"));
  expect_diag(fe::DiagCode::IncompatibleBecomes, 10, 17);
}

// ---------------------------------------------------------------- Traits

TEST_F(AppendixBEval, Case56_Inclusion) {
  ASSERT_TRUE(
      load("trait Named:\n"
           "    id is Int: 7\n"
           "Robot:\n"
           "    with Named\n"
           "    twice is Int: this.id * 2\n"))
      << all_diags();
  EXPECT_EQ(value("id"), "7");
  EXPECT_EQ(value("twice"), "14");
}

TEST_F(AppendixBEval, Case57_TwoTraits) {
  ASSERT_TRUE(
      load("trait TA:\n"
           "    a is Int: 1\n"
           "trait TB:\n"
           "    b is Int: 2\n"
           "M:\n"
           "    with TA\n"
           "    with TB\n"
           "    s is Int: a + b\n"))
      << all_diags();
  EXPECT_EQ(value("s"), "3");
}

TEST_F(AppendixBEval, Case58_TraitExtension) {
  ASSERT_TRUE(
      load("trait P:\n"
           "    a is Int: 1\n"
           "trait Q is P:\n"
           "    b is Int: 2\n"
           "M:\n"
           "    with Q\n"
           "    s is Int: a + b\n"))
      << all_diags();
  EXPECT_EQ(value("s"), "3");
}

TEST_F(AppendixBEval, Case59_TraitAsType) {
  ASSERT_TRUE(
      load("trait Tagged:\n"
           "    tag is Int: 5\n"
           "Item:\n"
           "    with Tagged\n"
           "Store:\n"
           "    item is Item\n"
           "    t is Tagged: item\n"
           "    v is Int: t.tag\n"))
      << all_diags();
  EXPECT_EQ(value("v"), "5");
  ASSERT_NE(object("item"), fe::kNoObject);
  EXPECT_EQ(object("t"), object("item"));
}

TEST_F(AppendixBEval, Case60_TraitsOnAttributeType) {
  ASSERT_TRUE(
      load("trait Red:\n"
           "    red is Real: 1.0\n"
           "trait Heavy:\n"
           "    kg is Real: 50.0\n"
           "Crate:\n"
           "    w is Real: 2.0\n"
           "Yard:\n"
           "    crate is Crate with Red, Heavy:\n"
           "        kg: 60.0\n"
           "    total is Real: crate.w + crate.red + crate.kg\n"))
      << all_diags();
  EXPECT_EQ(value("total"), "63.0");
  EXPECT_EQ(value("crate.kg"), "60.0");
}

TEST_F(AppendixBEval, Case61_TraitUsesWith) {
  // The snippet is loaded with Named from case 56 and a model that includes Bad, so Bad is resolved.
  EXPECT_FALSE(
      load("trait Named:\n"
           "    id is Int: 7\n"
           "trait Bad:\n"
           "    with Named\n"
           "M:\n"
           "    with Bad\n"));
  expect_diag(fe::DiagCode::TraitRestriction, 4, 5);
}

TEST_F(AppendixBEval, Case62_CommonAncestor) {
  EXPECT_FALSE(
      load("trait Z:\n"
           "    z is Int: 0\n"
           "trait L is Z:\n"
           "    l is Int: 1\n"
           "trait R is Z:\n"
           "    r is Int: 2\n"
           "M:\n"
           "    with L\n"
           "    with R\n"));
  expect_diag_containing(fe::DiagCode::TraitRestriction, "share common ancestor Z");
}

TEST_F(AppendixBEval, Case63_InjectedNameClash) {
  EXPECT_FALSE(load("trait T:\n    n is Int: 1\nM:\n    n is Int: 2\n    with T\n"));
  expect_diag_containing(fe::DiagCode::TraitRestriction, "injects attribute n");
}

TEST_F(AppendixBEval, Case64_TraitAsRoot) {
  // (prop) a trait is not a loadable model: a file holding only a trait has no model (`no-model`).
  EXPECT_FALSE(load("trait Solo:\n    a is Int: 1\n"));
  EXPECT_EQ(expect_diag(fe::DiagCode::NoModel, 1, 1), "No model could be found");
}

// ---------------------------------------------------------------- const models

TEST_F(AppendixBEval, Case65_ConstGlobalAccess) {
  ASSERT_TRUE(load("const Settings:\n    gain is Real: 3.0\nRoot:\n    g is Real: Settings.gain + 1.0\n"))
      << all_diags();
  EXPECT_EQ(value("g"), "4.0");
}

TEST_F(AppendixBEval, Case66_ConstAliases) {
  ASSERT_TRUE(load("const Settings:\n    gain is Real: 3.0\nRoot:\n    s is Settings\n    t is Settings\n"))
      << all_diags();
  ASSERT_NE(object("s"), fe::kNoObject);
  EXPECT_EQ(object("s"), object("t"));
  // The one instance is the global singleton `Settings`, not owned by Root.
  EXPECT_TRUE(evaluator_->graph().at(object("s")).is_const_singleton);
  EXPECT_FALSE(slot("s")->owns);
  EXPECT_FALSE(slot("t")->owns);
  EXPECT_EQ(value("s"), "-> Settings");
  EXPECT_EQ(instances_of("Settings"), 1u);
  EXPECT_EQ(value("s.gain"), "3.0");
}

TEST_F(AppendixBEval, Case67_EnumStyle) {
  ASSERT_TRUE(load("const Mode:\n    Off is Int: 0\n    On is Int: 1\nRoot:\n    m is Int: Mode.On\n"))
      << all_diags();
  EXPECT_EQ(value("m"), "1");
}

TEST_F(AppendixBEval, Case68_ConstModelAsValue) {
  ASSERT_TRUE(
      load("Material:\n"
           "    density is Real: 1000.0\n"
           "const Steel is Material:\n"
           "    density: 7800.0\n"
           "Part:\n"
           "    mat is Material\n"
           "Root:\n"
           "    p is Part:\n"
           "        mat: Steel\n"
           "    d is Real: p.mat.density\n"))
      << all_diags();
  EXPECT_EQ(value("d"), "7800.0");
  ASSERT_NE(object("p.mat"), fe::kNoObject);
  EXPECT_TRUE(evaluator_->graph().at(object("p.mat")).is_const_singleton);
  EXPECT_EQ(type_name("p.mat"), "Steel");
  EXPECT_EQ(value("p.mat"), "-> Steel");
  EXPECT_EQ(instances_of("Steel"), 1u);
}

TEST_F(AppendixBEval, Case69_WritingToConst) {
  // (prop) assigning to an attribute of a const instance is `const-assignment` at the assignment.
  EXPECT_FALSE(
      load("const Settings:\n"
           "    gain is Real: 3.0\n"
           "Root:\n"
           "    s is Settings\n"
           "    t is Settings\n"
           "    s.gain: 9.0\n"));
  expect_diag(fe::DiagCode::ConstAssignment, 6, 5);
}

// ---------------------------------------------------------------- Annotations

TEST_F(AppendixBEval, Case70_DocString) {
  ASSERT_TRUE(
      load("Root:\n"
           "    .doc: \"\"\"Root model\n"
           "more\"\"\"\n"
           "    a is Int: 1\n"))
      << all_diags();
  EXPECT_EQ(root_annotation("doc"), "Root model\nmore");
  EXPECT_EQ(value("a"), "1");
}

TEST_F(AppendixBEval, Case71_AnnotationsOnAnAttribute) {
  ASSERT_TRUE(
      load("Leaf:\n    k is Int: 0\nRoot:\n    leaf is Leaf:\n        .unit: \"m\"\n        .prio: 3\n"))
      << all_diags();
  EXPECT_EQ(slot_annotation("leaf", "unit"), "m");
  EXPECT_EQ(slot_annotation("leaf", "prio"), "3");
  EXPECT_EQ(value("leaf.k"), "0");
  EXPECT_EQ(root_annotation("unit"), "<none>");
}

TEST_F(AppendixBEval, Case72_AnnotationThroughInheritedAttribute) {
  ASSERT_TRUE(load(
      "Leaf:\n    k is Int: 0\nBase:\n    leaf is Leaf\nRoot is Base:\n    leaf:\n        .hidden: true\n"))
      << all_diags();
  EXPECT_EQ(type_name(""), "Root");
  EXPECT_EQ(slot_annotation("leaf", "hidden"), "true");
}

TEST_F(AppendixBEval, Case73_NonConstantAnnotation) {
  EXPECT_FALSE(load("Leaf:\n    k is Int: 0\nRoot:\n    leaf is Leaf\n    .metadata: leaf\n"));
  expect_diag(fe::DiagCode::AnnotationNotConstant, 5, 16);
}

// ---------------------------------------------------------------- Expressions, scope, methods

TEST_F(AppendixBEval, Case74_BindingStrength) {
  ASSERT_TRUE(
      load("Root:\n"
           "    a is Real: 2 + 3 * 4\n"
           "    b is Real: (2 + 3) * 4\n"
           "    c is Real: 10 - 4 - 3\n"
           "    d is Real: 8 / 2 / 2\n"))
      << all_diags();
  EXPECT_EQ(value("a"), "14.0");
  EXPECT_EQ(value("b"), "20.0");
  EXPECT_EQ(value("c"), "3.0");
  EXPECT_EQ(value("d"), "2.0");
}

TEST_F(AppendixBEval, Case75_UnaryMinus) {
  ASSERT_TRUE(load("Root:\n    a is Int: 4\n    b is Int: -a\n    c is Real: -2 * 3\n")) << all_diags();
  EXPECT_EQ(value("a"), "4");
  EXPECT_EQ(value("b"), "-4");
  EXPECT_EQ(value("c"), "-6.0");
}

TEST_F(AppendixBEval, Case76_IntDivision) {
  // (prop) Int / Int gives a Real.
  ASSERT_TRUE(load("Root:\n    q is Real: 7 / 2\n")) << all_diags();
  EXPECT_EQ(value("q"), "3.5");
}

TEST_F(AppendixBEval, Case77_ThisAgainstGlobal) {
  ASSERT_TRUE(load("x is Real: 100.0\nRoot:\n    x is Real: 1.0\n    y is Real: this.x + 1\n"))
      << all_diags();
  EXPECT_EQ(value("x"), "1.0");
  EXPECT_EQ(value("y"), "2.0");
}

TEST_F(AppendixBEval, Case78_OutermostScope) {
  ASSERT_TRUE(load(
      "Leaf:\n    k is Real: 0.0\nRoot:\n    base is Real: 5.0\n    leaf is Leaf:\n        k: base * 2\n"))
      << all_diags();
  EXPECT_EQ(value("leaf.k"), "10.0");
}

TEST_F(AppendixBEval, Case79_QualifiedNameFromOuterScope) {
  ASSERT_TRUE(load(
      "Leaf:\n    k is Real: 3.0\n    m is Real: 0.0\nRoot:\n    leaf is Leaf:\n        m: leaf.k + 1\n"))
      << all_diags();
  EXPECT_EQ(value("leaf.m"), "4.0");
  // (prop) RHS names resolve in the outermost model (Root), which has no `k`: `unknown-name`.
  EXPECT_FALSE(load_file(
      write("variant.openplx",
            "Leaf:\n    k is Real: 3.0\n    m is Real: 0.0\nRoot:\n    leaf is Leaf:\n        m: k + 1\n")));
  expect_diag(fe::DiagCode::UnknownName, 6, 12);
}

TEST_F(AppendixBEval, Case80_LateBindingInNestedType) {
  ASSERT_TRUE(load("A:\n    x is Real: 1.0\n    y is Real: x * 10\nS:\n    a is A:\n        x: 2.0\n"))
      << all_diags();
  EXPECT_EQ(value("a.x"), "2.0");
  EXPECT_EQ(value("a.y"), "20.0");
}

TEST_F(AppendixBEval, Case81_ThisAsValue) {
  ASSERT_TRUE(
      load("Probe:\n"
           "    optional target is Body\n"
           "Body:\n"
           "    mass is Real: 2.0\n"
           "    probe is Probe:\n"
           "        target: this\n"
           "Root:\n"
           "    b is Body\n"
           "    m is Real: b.probe.target.mass\n"))
      << all_diags();
  EXPECT_EQ(value("m"), "2.0");
  ASSERT_NE(object("b"), fe::kNoObject);
  EXPECT_EQ(object("b.probe.target"), object("b"));
  EXPECT_EQ(value("b.probe.target"), "-> b");
}

TEST_F(AppendixBEval, Case82_VectorOperators) {
  ASSERT_TRUE(
      load("Root:\n"
           "    a is Math.Vec3: Math.Vec3.from_xyz(1, 2, 3)\n"
           "    b is Math.Vec3: {2, 3, 4}\n"
           "    s is Math.Vec3: a + b\n"
           "    d is Real: a * b\n"
           "    k is Math.Vec3: 3 * a\n"
           "    h is Math.Vec3: b / 2\n"
           "    n is Math.Vec3: -a\n"))
      << all_diags();
  EXPECT_EQ(value("s"), "{3.0, 5.0, 7.0}");
  EXPECT_EQ(value("d"), "20.0");
  EXPECT_EQ(value("k"), "{3.0, 6.0, 9.0}");
  EXPECT_EQ(value("h"), "{1.0, 1.5, 2.0}");
  EXPECT_EQ(value("n"), "{-1.0, -2.0, -3.0}");
}

TEST_F(AppendixBEval, Case83_InstanceCalls) {
  ASSERT_TRUE(
      load("Root:\n"
           "    l is Real: Math.Vec3.from_xyz(3, 4, 0).length()\n"
           "    u is Math.Vec3: Math.Vec3.from_xyz(0, 0, 5).normal()\n"))
      << all_diags();
  EXPECT_EQ(value("l"), "5.0");
  EXPECT_EQ(value("u"), "{0.0, 0.0, 1.0}");
}

TEST_F(AppendixBEval, Case84_InitializerAsOperand) {
  // (prop) an initializer operand takes the expected type of the whole expression (Vec3 / Real exists).
  ASSERT_TRUE(load("Root:\n    m is Math.Vec3: {2, 4, 6} / 2\n")) << all_diags();
  EXPECT_EQ(value("m"), "{1.0, 2.0, 3.0}");
}

TEST_F(AppendixBEval, Case85_InitializerArity) {
  // (prop) more values than fields is `initializer-arity` at the initializer.
  EXPECT_FALSE(load("Root:\n    v is Math.Vec3: {1, 2, 3, 4}\n"));
  expect_diag(fe::DiagCode::InitializerArity, 2, 21);
}

TEST_F(AppendixBEval, Case86_ConstantsAndFunctions) {
  ASSERT_TRUE(load("Root:\n    h is Real: Math.PI / 2\n    r is Real: Math.Functions.sqrt(16)\n"))
      << all_diags();
  EXPECT_DOUBLE_EQ(real("h"), 1.5707963267948966);
  EXPECT_EQ(value("h"), "1.5707963267948966");
  EXPECT_EQ(value("r"), "4.0");
}

TEST_F(AppendixBEval, Case87_Quaternion) {
  ASSERT_TRUE(
      load("Root:\n"
           "    q is Math.Quat: Math.Quat.angle_axis(Math.PI, Math.Vec3.Z_AXIS())\n"
           "    v is Math.Vec3: q.rotate(Math.Vec3.X_AXIS())\n"))
      << all_diags();
  EXPECT_NEAR(real("v.x"), -1.0, 1e-9);
  EXPECT_NEAR(real("v.y"), 0.0, 1e-9);
  EXPECT_NEAR(real("v.z"), 0.0, 1e-9);
}

TEST_F(AppendixBEval, Case88_Vec3WithoutValue) {
  ASSERT_TRUE(load("Root:\n    p is Math.Vec3\n")) << all_diags();
  EXPECT_EQ(value("p"), "{0.0, 0.0, 0.0}");
}

TEST_F(AppendixBEval, Case89_CallingVoidMethod) {
  // (prop) calling a method with no return type is `void-method-call` at the call.
  EXPECT_FALSE(load("Gadget:\n    fn reset()\nRoot:\n    g is Gadget\n    x is Real: g.reset()\n"));
  expect_diag(fe::DiagCode::VoidMethodCall, 5, 16);
}

TEST_F(AppendixBEval, Case90_NoOperatorForTypes) {
  // (prop) no declared operator for (T, T) is `no-operator` at the expression.
  EXPECT_FALSE(load("T:\n    a is Int: 0\nRoot:\n    p is T\n    q is T\n    r is T: p + q\n"));
  expect_diag_containing(fe::DiagCode::NoOperator, "No operator + for T and T");
}

TEST_F(AppendixBEval, Case91_DeclaredOperator) {
  // (prop) the operator type-checks (t has static type Money); evaluating it without a native
  // implementation is `no-implementation`, and it is the only diagnostic.
  EXPECT_FALSE(
      load("Money:\n"
           "    c is Int: 0\n"
           "operator +(lhs: Money, rhs: Money) -> Money\n"
           "Root:\n"
           "    a is Money\n"
           "    b is Money\n"
           "    t is Money: a + b\n"));
  expect_diag(fe::DiagCode::NoImplementation, 7, 17);
  EXPECT_EQ(sink_.diagnostics().size(), 1u) << all_diags();
  ASSERT_NE(slot("t"), nullptr);
  ASSERT_EQ(slot("t")->type()->kind, fe::TypeKind::Model);
  EXPECT_EQ(slot("t")->type()->model->name, "Money");
}

TEST_F(AppendixBEval, Case92_StaticCallOnInstance) {
  // (prop) a static method called on an instance is `static-mismatch` at the call.
  EXPECT_FALSE(load("Vec:\n    static fn make() -> Vec\nRoot:\n    v is Vec\n    w is Vec: v.make()\n"));
  expect_diag(fe::DiagCode::StaticMismatch, 5, 15);
}

// ---------------------------------------------------------------- Imports and bundles

TEST_F(AppendixBEval, Case93_MissingImport) {
  // (prop) `import-not-found`, naming the absolute path.
  EXPECT_FALSE(load("import @\"nope.obj\"\nRoot\n"));
  expect_diag_containing(fe::DiagCode::ImportNotFound, dir() + "/nope.obj");
}

TEST_F(AppendixBEval, Case94_UnknownPlugin) {
  // (prop) `unsupported-import`, naming the extension.
  write("data.xyz", "some data\n");
  EXPECT_FALSE(load("import @\"data.xyz\" as Thing\nRoot\n"));
  expect_diag_containing(fe::DiagCode::UnsupportedImport, ".xyz");
}

TEST_F(AppendixBEval, Case95_BundleNamespace) {
  write_shop();
  ASSERT_TRUE(load_with_bundles(write("B/shop/scene.openplx", "Bench:\n    h is Items.Hammer\n")))
      << all_diags();
  EXPECT_EQ(type_name(""), "Bench");
  EXPECT_EQ(value("h.kg"), "1.2");
}

TEST_F(AppendixBEval, Case96_FromOutsideTheBundle) {
  write_shop();
  ASSERT_TRUE(load_with_bundles(write("main.openplx", "Yard:\n    h is Shop.Items.Hammer\n"))) << all_diags();
  EXPECT_EQ(value("h.kg"), "1.2");
}

TEST_F(AppendixBEval, Case97_SameNamespaceWithoutQualification) {
  write_shop();
  ASSERT_TRUE(load_with_bundles(write("B/shop/Items/Kit.openplx", "Kit:\n    tool is Hammer\n")))
      << all_diags();
  EXPECT_EQ(type_name(""), "Kit");
  EXPECT_EQ(value("tool.kg"), "1.2");
}

TEST_F(AppendixBEval, Case98_FileNameIsNotANamespace) {
  // (prop) file names create no namespace: `Tools` is an unknown name inside Shop.Items.
  write_shop();
  EXPECT_FALSE(load_with_bundles(write("main.openplx", "Yard:\n    x is Shop.Items.Tools.Hammer\n")));
  expect_diag_containing(fe::DiagCode::UnknownName, "Tools");
}

TEST_F(AppendixBEval, Case99_GlobalInAFolder) {
  write_shop();
  write("B/shop/Items/Limits.openplx", "MAXKG is Real: 9.0\n");
  ASSERT_TRUE(load_with_bundles(write("main.openplx", "Root:\n    m is Real: Shop.Items.MAXKG\n")))
      << all_diags();
  EXPECT_EQ(value("m"), "9.0");
}

TEST_F(AppendixBEval, Case100_DependencySyntax) {
  write_shop("    dependencies: [\"Math\", \"Other@1.2.3\"]\n");
  ASSERT_TRUE(load_with_bundles(write("main.openplx", "Root:\n    a is Int: 1\n"))) << all_diags();
  const fe::BundleConfig* shop = nullptr;
  for (const fe::BundleConfig& b : program_->bundles()) {
    if (b.name == "Shop") shop = &b;
  }
  ASSERT_NE(shop, nullptr);
  ASSERT_EQ(shop->dependencies.size(), 2u);
  EXPECT_EQ(shop->dependencies[0].name, "Math");
  EXPECT_EQ(shop->dependencies[0].version, "");
  EXPECT_EQ(shop->dependencies[1].name, "Other");
  EXPECT_EQ(shop->dependencies[1].version, "1.2.3");
}

TEST_F(AppendixBEval, Case101_UndeclaredBundle) {
  // (prop) dependencies are visible transitively, but a bundle not reachable from Shop's dependency list is
  // an unknown name, even when it is registered (here a Physics3D bundle beside Shop).
  write_shop();
  write("B/Physics3D/config.openplx", "config is BundleConfig:\n    name: \"Physics3D\"\n");
  write("B/Physics3D/System.openplx", "System:\n    g is Real: 9.81\n");
  EXPECT_FALSE(load_with_bundles(write("B/shop/scene.openplx", "Bench:\n    s is Physics3D.System\n")));
  expect_diag_containing(fe::DiagCode::UnknownName, "not declared as dependency");
}

}  // namespace
