// Appendix B of ../shared/spec/openplx-language.md, at the level the parser can check: one test per case
// (CaseNN_...).
// A case whose expected result depends on the syntax tree asserts that shape; a case whose result is decided
// by semantic analysis or evaluation checks that its snippet parses cleanly, and says so in a comment.
// Snippets given inline in the spec ("`Root:` / `a is Int: 1`") are rebuilt with 4-space indentation.
#include <gtest/gtest.h>

#include <string>

#include "frontend/syntax/ast.h"
#include "frontend/syntax/ast_dump.h"
#include "tests/support/parse_fixture.h"

namespace {

namespace fe = openplx::frontend;

class AppendixB : public openplx::testing::ParseTest {
 protected:
  // The document as indented text without source ranges: one line per declaration and member, values
  // printed by expr_to_string, a trailing `:` when a block follows.
  std::string shape() const {
    std::string out;
    for (const fe::Decl& d : doc_.decls) {
      switch (d.kind) {
        case fe::DeclKind::Import:
          out += "import " + expr(d.value);
          if (d.alias) out += " as " + fe::to_string(*d.alias);
          break;
        case fe::DeclKind::Model:
        case fe::DeclKind::Trait:
          out += d.kind == fe::DeclKind::Trait ? "trait " : (d.is_const ? "const model " : "model ");
          out += name(d.name);
          if (d.base) out += " is " + fe::to_string(*d.base);
          for (size_t i = 0; i < d.traits.size(); ++i)
            out += (i ? ", " : " with ") + fe::to_string(d.traits[i]);
          if (d.has_body) out += ":";
          break;
        case fe::DeclKind::GlobalAttribute:
          out += "global " + name(d.name) + " is " + type(d.type) + " = " + expr(d.value);
          break;
        case fe::DeclKind::Operator:
          out += std::string("operator ") + d.op + "(" + params(d.params) + ")";
          if (d.return_type) out += " -> " + type_ref(*d.return_type);
          break;
      }
      out += "\n";
      for (const fe::Member& m : d.body) member(out, m, 1);
    }
    return out;
  }

  // The members of `model` (which must exist), rendered as by shape().
  std::string body_of(std::string_view model) const {
    const fe::Decl* d = doc_.find_model(model);
    if (d == nullptr) return "<no model " + std::string(model) + ">";
    std::string out;
    for (const fe::Member& m : d->body) member(out, m, 0);
    return out;
  }

  bool clean() const { return sink_.diagnostics().empty(); }

  std::string expr(const std::optional<fe::ExprId>& id) const {
    return id ? fe::expr_to_string(doc_, *id) : "<none>";
  }
  static std::string name(const fe::Ident& id) {
    return id.quoted ? "`" + std::string(id.text) + "`" : std::string(id.text);
  }
  static std::string type_ref(const fe::TypeRef& t) {
    return fe::to_string(t.name) + (t.is_array ? "[]" : "");
  }
  static std::string type(const fe::TypeExpr& t) {
    std::string out;
    for (size_t i = 0; i < t.alternatives.size(); ++i) out += (i ? " or " : "") + type_ref(t.alternatives[i]);
    for (size_t i = 0; i < t.traits.size(); ++i) out += (i ? ", " : " with ") + fe::to_string(t.traits[i]);
    return out;
  }
  static std::string params(const std::vector<fe::Param>& ps) {
    std::string out;
    for (size_t i = 0; i < ps.size(); ++i)
      out += (i ? ", " : "") + name(ps[i].name) + ": " + type_ref(ps[i].type);
    return out;
  }
  void member(std::string& out, const fe::Member& m, int depth) const {
    out += std::string(static_cast<size_t>(depth) * 2, ' ');
    switch (m.kind) {
      case fe::MemberKind::Annotation:
        out += "." + fe::to_string(m.path);
        break;
      case fe::MemberKind::TraitUse:
        out += "with " + fe::to_string(m.path);
        break;
      case fe::MemberKind::Method:
        out += std::string(m.is_static ? "static fn " : "fn ") + fe::to_string(m.path) + "(" +
               params(m.params) + ")";
        if (m.return_type) out += " -> " + type_ref(*m.return_type);
        break;
      case fe::MemberKind::Attribute:
        out += std::string(m.is_optional ? "optional " : "") + fe::to_string(m.path) + " is " + type(m.type);
        break;
      case fe::MemberKind::Becomes:
        out += fe::to_string(m.path) + " becomes " + type(m.type);
        break;
      case fe::MemberKind::Assignment:
        out += fe::to_string(m.path);
        break;
    }
    if (m.value) out += " = " + expr(m.value);
    if (m.has_block) out += ":";
    out += "\n";
    for (const fe::Member& child : m.block) member(out, child, depth + 1);
  }
};

// ---------------------------------------------------------------- Lexical and layout

TEST_F(AppendixB, Case01_CommentsEverywhere) {
  parse(
      "# top comment\n"
      "Root:   # after head\n"
      "    a is Real: 2.5  # after value\n");
  EXPECT_EQ(shape(), "model Root:\n  a is Real = 2.5\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  ASSERT_EQ(doc_.decls[0].body.size(), 1u);
  const fe::Expr& v = doc_.expr(*doc_.decls[0].body[0].value);
  EXPECT_EQ(v.kind, fe::ExprKind::Real);
  EXPECT_DOUBLE_EQ(v.real_value, 2.5);
}

TEST_F(AppendixB, Case02_TwoSpaceIndentation) {
  parse("Root:\n  a is Int: 1\n  b is Int: 2\n");
  EXPECT_EQ(shape(), "model Root:\n  a is Int = 1\n  b is Int = 2\n");
}

TEST_F(AppendixB, Case03_RelativeChildDepth) {
  parse(
      "Inner:\n"
      "    v is Real: 0.0\n"
      "Root:\n"
      "    inner is Inner:\n"
      "          v: 7.0\n"
      "    w is Real: 1.0\n");
  // inner's nested block assigns v = 7.0; w belongs to Root, not to inner's block.
  EXPECT_EQ(shape(),
            "model Inner:\n  v is Real = 0.0\n"
            "model Root:\n  inner is Inner:\n    v = 7.0\n  w is Real = 1.0\n");
}

TEST_F(AppendixB, Case04_DedentToUnknownColumn) {
  // (prop) dedenting to a column not on the indentation stack is `inconsistent-dedent`.
  parse("Root:\n    a is Int: 1\n  b is Int: 2\n");
  expect_diag(fe::DiagCode::InconsistentDedent, 3, 3);
  EXPECT_EQ(count(fe::DiagCode::InconsistentDedent), 1u);
  EXPECT_NE(doc_.find_model("Root"), nullptr);
}

TEST_F(AppendixB, Case05_Exponents) {
  // (prop) lower-case `e` is accepted as the exponent letter.
  parse("Root:\n    g is Real: 2E3\n    h is Real: 1.5e-2\n");
  EXPECT_EQ(body_of("Root"), "g is Real = 2E3\nh is Real = 1.5e-2\n");
  const auto& body = doc_.decls.at(0).body;
  ASSERT_EQ(body.size(), 2u);
  EXPECT_EQ(doc_.expr(*body[0].value).kind, fe::ExprKind::Real);
  EXPECT_DOUBLE_EQ(doc_.expr(*body[0].value).real_value, 2000.0);
  EXPECT_EQ(doc_.expr(*body[1].value).kind, fe::ExprKind::Real);
  EXPECT_DOUBLE_EQ(doc_.expr(*body[1].value).real_value, 0.015);
}

TEST_F(AppendixB, Case06_IntLiteralIntoReal) {
  // The Int→Real conversion is semantic; the parser keeps an Int literal under a Real type.
  parse("Root:\n    r is Real: 4\n");
  EXPECT_EQ(body_of("Root"), "r is Real = 4\n");
  const fe::Expr& v = doc_.expr(*doc_.decls.at(0).body.at(0).value);
  EXPECT_EQ(v.kind, fe::ExprKind::Int);
  EXPECT_EQ(v.int_value, 4);
}

TEST_F(AppendixB, Case07_IntegralRealIntoInt) {
  parse("Root:\n    i is Int: 6.0\n");
  EXPECT_EQ(body_of("Root"), "i is Int = 6.0\n");
  const fe::Expr& v = doc_.expr(*doc_.decls.at(0).body.at(0).value);
  EXPECT_EQ(v.kind, fe::ExprKind::Real);
  EXPECT_DOUBLE_EQ(v.real_value, 6.0);
}

TEST_F(AppendixB, Case08_NonIntegralRealIntoInt) {
  // semantic error expected: checked by the semantics issue ((prop) Real→Int only for integral values).
  parse("Root:\n    i is Int: 6.5\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(body_of("Root"), "i is Int = 6.5\n");
}

TEST_F(AppendixB, Case09_PlainStringWithHash) {
  parse("Root:\n    s is String: \"a b # not comment\"\n");
  const fe::Expr& v = doc_.expr(*doc_.decls.at(0).body.at(0).value);
  EXPECT_EQ(v.kind, fe::ExprKind::String);
  EXPECT_EQ(v.string_value, "a b # not comment");
  EXPECT_EQ(body_of("Root"), "s is String = \"a b # not comment\"\n");
}

TEST_F(AppendixB, Case10_MultilineStringKeepsIndentation) {
  parse(
      "Root:\n"
      "    t is String: \"\"\"first\n"
      "second\"\"\"\n"
      "    n is Int: 3\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const auto& body = doc_.decls[0].body;
  ASSERT_EQ(body.size(), 2u);  // n is still in Root
  const fe::Expr& t = doc_.expr(*body[0].value);
  EXPECT_EQ(t.kind, fe::ExprKind::String);
  EXPECT_TRUE(t.multiline);
  EXPECT_EQ(t.string_value, "first\nsecond");
  EXPECT_EQ(fe::to_string(body[1].path), "n");
  EXPECT_EQ(expr(body[1].value), "3");
}

TEST_F(AppendixB, Case11_PathString) {
  // The parser keeps the path as written; resolving it against <D> is semantic.
  parse("Root:\n    p is String: @\"mesh/part.obj\"\n", "D/scene.openplx");
  const fe::Expr& v = doc_.expr(*doc_.decls.at(0).body.at(0).value);
  EXPECT_EQ(v.kind, fe::ExprKind::PathString);
  EXPECT_FALSE(v.quoted);
  EXPECT_EQ(v.string_value, "mesh/part.obj");
}

TEST_F(AppendixB, Case12_PathStringWithParentStep) {
  // (prop) `..` is normalised when sema resolves the path; the AST keeps it as written.
  parse("Root:\n    q is String: @\"../x.txt\"\n", "D/scene.openplx");
  const fe::Expr& v = doc_.expr(*doc_.decls.at(0).body.at(0).value);
  EXPECT_EQ(v.kind, fe::ExprKind::PathString);
  EXPECT_EQ(v.string_value, "../x.txt");
}

TEST_F(AppendixB, Case13_BacktickName) {
  parse(
      "Leaf:\n"
      "    k is Int: 4\n"
      "Root:\n"
      "    `a.b` is Leaf\n");
  const fe::Decl* root = doc_.find_model("Root");
  ASSERT_NE(root, nullptr);
  ASSERT_EQ(root->body.size(), 1u);  // exactly one attribute
  const fe::Member& m = root->body[0];
  EXPECT_EQ(m.kind, fe::MemberKind::Attribute);
  ASSERT_EQ(m.path.parts.size(), 1u);
  EXPECT_EQ(m.path.parts[0].text, "a.b");
  EXPECT_TRUE(m.path.parts[0].quoted);
  EXPECT_EQ(body_of("Root"), "`a.b` is Leaf\n");
}

TEST_F(AppendixB, Case14_ImplicitLineJoining) {
  parse("Root:\n    zs is Int[]: [1,\n        2, 3]\n");
  EXPECT_EQ(body_of("Root"), "zs is Int[] = [1, 2, 3]\n");
  const fe::Expr& v = doc_.expr(*doc_.decls.at(0).body.at(0).value);
  EXPECT_EQ(v.kind, fe::ExprKind::Array);
  EXPECT_EQ(v.operands.size(), 3u);
}

// ---------------------------------------------------------------- Document structure and completeness

TEST_F(AppendixB, Case15_LonelyModel) {
  parse("Lonely\n");
  EXPECT_EQ(shape(), "model Lonely\n");
  ASSERT_NE(doc_.last_model(), nullptr);
  EXPECT_EQ(doc_.last_model()->name.text, "Lonely");
  EXPECT_TRUE(doc_.last_model()->body.empty());
}

TEST_F(AppendixB, Case16_EmptyDerivedModel) {
  parse("Base:\n    q is Int: 9\nAlias is Base\n");
  EXPECT_EQ(shape(), "model Base:\n  q is Int = 9\nmodel Alias is Base\n");
  ASSERT_NE(doc_.last_model(), nullptr);
  EXPECT_EQ(doc_.last_model()->name.text, "Alias");
}

TEST_F(AppendixB, Case17_ColonWithoutBlock) {
  parse("Broken:\n");
  EXPECT_EQ(expect_diag(fe::DiagCode::ExpectedIndentedBlock, 1, 7), "Expected indented block");
  // No model declaration survives, so the loader reports `No model could be found`.
  EXPECT_TRUE(doc_.decls.empty());
  EXPECT_EQ(doc_.last_model(), nullptr);
}

TEST_F(AppendixB, Case18_BareNameIsNotAMember) {
  parse("Thing:\n    speed\n");
  EXPECT_EQ(expect_diag(fe::DiagCode::ExpectedIs, 2, 10), "Expected an is keyword");
  EXPECT_EQ(count(fe::DiagCode::ExpectedIs), 1u);
  EXPECT_EQ(body_of("Thing"), "");
}

TEST_F(AppendixB, Case19_MissingAssignment) {
  // semantic error expected: checked by the semantics issue (`Missing assignment Thing.speed, ...`).
  parse("Thing:\n    speed is Real\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(shape(), "model Thing:\n  speed is Real\n");
}

TEST_F(AppendixB, Case20_IncompleteBaseCompleteDerived) {
  parse("Base:\n    speed is Real\nCar is Base:\n    speed: 12.0\n");
  EXPECT_EQ(shape(), "model Base:\n  speed is Real\nmodel Car is Base:\n  speed = 12.0\n");
}

TEST_F(AppendixB, Case21_DefaultModelIsTheLast) {
  parse("A:\n    a is Int: 1\nB:\n    b is Int: 2\n");
  ASSERT_NE(doc_.last_model(), nullptr);
  EXPECT_EQ(doc_.last_model()->name.text, "B");
  EXPECT_EQ(body_of("B"), "b is Int = 2\n");
}

TEST_F(AppendixB, Case22_LoadNamedModel) {
  parse("A:\n    a is Int: 1\nB:\n    b is Int: 2\n");
  ASSERT_NE(doc_.find_model("A"), nullptr);
  EXPECT_EQ(body_of("A"), "a is Int = 1\n");
}

TEST_F(AppendixB, Case23_GlobalAttribute) {
  parse("scale is Real: 2.0\nRoot:\n    v is Real: scale * 3\n");
  EXPECT_EQ(shape(), "global scale is Real = 2.0\nmodel Root:\n  v is Real = (scale * 3)\n");
}

TEST_F(AppendixB, Case24_ChainedGlobals) {
  parse("g1 is Int: 2\ng2 is Int: g1 * 5\nRoot:\n    c is Int: g2\n");
  EXPECT_EQ(shape(), "global g1 is Int = 2\nglobal g2 is Int = (g1 * 5)\nmodel Root:\n  c is Int = g2\n");
  ASSERT_NE(doc_.last_model(), nullptr);
  EXPECT_EQ(doc_.last_model()->name.text, "Root");
}

TEST_F(AppendixB, Case25_Optional) {
  parse("Root:\n    optional label is String\n    n is Int: 1\n");
  EXPECT_EQ(body_of("Root"), "optional label is String\nn is Int = 1\n");
  EXPECT_TRUE(doc_.decls.at(0).body.at(0).is_optional);
  EXPECT_FALSE(doc_.decls.at(0).body.at(1).is_optional);
}

TEST_F(AppendixB, Case26_ReadingUnsetOptional) {
  // semantic error expected: checked by the semantics issue ((prop) unset-attribute error).
  parse("Root:\n    optional label is String\n    n is Int: 1\n    m is String: label\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(body_of("Root"), "optional label is String\nn is Int = 1\nm is String = label\n");
}

TEST_F(AppendixB, Case27_TopLevelOrderDoesNotMatter) {
  // (prop) models may refer to models declared later; the parser keeps both, in file order.
  parse(
      "Root:\n"
      "    p is Part\n"
      "Part:\n"
      "    m is Real: 1.5\n");
  EXPECT_EQ(shape(), "model Root:\n  p is Part\nmodel Part:\n  m is Real = 1.5\n");
  ASSERT_NE(doc_.find_model("Root"), nullptr);
}

// ---------------------------------------------------------------- Attributes, ownership, references

TEST_F(AppendixB, Case28_Bools) {
  parse("Root:\n    on is Bool: true\n    off is Bool: false\n");
  const auto& body = doc_.decls.at(0).body;
  ASSERT_EQ(body.size(), 2u);
  EXPECT_EQ(doc_.expr(*body[0].value).kind, fe::ExprKind::Bool);
  EXPECT_TRUE(doc_.expr(*body[0].value).bool_value);
  EXPECT_EQ(doc_.expr(*body[1].value).kind, fe::ExprKind::Bool);
  EXPECT_FALSE(doc_.expr(*body[1].value).bool_value);
}

TEST_F(AppendixB, Case29_RealArrayWithInts) {
  parse("Root:\n    xs is Real[]: [1, 2.5, -3]\n");
  EXPECT_EQ(body_of("Root"), "xs is Real[] = [1, 2.5, (-3)]\n");
  const fe::Expr& v = doc_.expr(*doc_.decls.at(0).body.at(0).value);
  ASSERT_EQ(v.operands.size(), 3u);
  EXPECT_EQ(doc_.expr(v.operands[0]).kind, fe::ExprKind::Int);
  EXPECT_EQ(doc_.expr(v.operands[1]).kind, fe::ExprKind::Real);
  EXPECT_EQ(doc_.expr(v.operands[2]).kind, fe::ExprKind::Unary);
}

TEST_F(AppendixB, Case30_EmptyArray) {
  parse("Root:\n    ys is Int[]: []\n");
  EXPECT_EQ(body_of("Root"), "ys is Int[] = []\n");
  const fe::Expr& v = doc_.expr(*doc_.decls.at(0).body.at(0).value);
  EXPECT_EQ(v.kind, fe::ExprKind::Array);
  EXPECT_TRUE(v.operands.empty());
}

TEST_F(AppendixB, Case31_BadArrayElement) {
  // semantic error expected: checked by the semantics issue ((prop) type mismatch).
  parse("Root:\n    zs is Int[]: [\"x\"]\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(body_of("Root"), "zs is Int[] = [\"x\"]\n");
}

TEST_F(AppendixB, Case32_DistinctOwnedInstances) {
  parse(
      "Wheel:\n"
      "    r is Real: 0.3\n"
      "Car:\n"
      "    front is Wheel\n"
      "    back is Wheel\n");
  EXPECT_EQ(shape(), "model Wheel:\n  r is Real = 0.3\nmodel Car:\n  front is Wheel\n  back is Wheel\n");
}

TEST_F(AppendixB, Case33_NestedAssignmentOnOneInstance) {
  parse(
      "Wheel:\n"
      "    r is Real: 0.3\n"
      "Car:\n"
      "    front is Wheel:\n"
      "        r: 0.5\n"
      "    back is Wheel\n");
  EXPECT_EQ(body_of("Car"), "front is Wheel:\n  r = 0.5\nback is Wheel\n");
}

TEST_F(AppendixB, Case34_NewAttributeInNestedBlock) {
  parse(
      "Wheel:\n"
      "    r is Real: 0.3\n"
      "Car:\n"
      "    front is Wheel:\n"
      "        psi is Real: 2.2\n"
      "    back is Wheel\n"
      "    p is Real: front.psi\n");
  EXPECT_EQ(body_of("Car"), "front is Wheel:\n  psi is Real = 2.2\nback is Wheel\np is Real = front.psi\n");
  EXPECT_EQ(doc_.find_model("Car")->body[0].block.at(0).kind, fe::MemberKind::Attribute);
}

TEST_F(AppendixB, Case35_Reference) {
  parse(
      "Part:\n"
      "    m is Real: 1.0\n"
      "Holder:\n"
      "    a is Part:\n"
      "        m: 4.0\n"
      "    b is Part: a\n");
  EXPECT_EQ(body_of("Holder"), "a is Part:\n  m = 4.0\nb is Part = a\n");
  EXPECT_EQ(doc_.expr(*doc_.find_model("Holder")->body.at(1).value).kind, fe::ExprKind::Name);
}

TEST_F(AppendixB, Case36_ArrayOfReferences) {
  parse("Part:\n    m is Real: 1.0\nHolder:\n    a is Part\n    c is Part\n    all is Part[]: [a, c]\n");
  EXPECT_EQ(body_of("Holder"), "a is Part\nc is Part\nall is Part[] = [a, c]\n");
}

TEST_F(AppendixB, Case37_ReferenceTypeCheck) {
  // semantic error expected: checked by the semantics issue ((prop) type mismatch).
  parse("Part:\n    m is Real: 1.0\nOther:\n    z is Int: 0\nHolder:\n    o is Other\n    b is Part: o\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(body_of("Holder"), "o is Other\nb is Part = o\n");
}

TEST_F(AppendixB, Case38_DuplicateAttribute) {
  // semantic error expected: checked by the semantics issue ((prop) duplicate attribute).
  parse("Root:\n    a is Int: 1\n    a is Int: 2\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(body_of("Root"), "a is Int = 1\na is Int = 2\n");
}

// ---------------------------------------------------------------- Assignments and override order

TEST_F(AppendixB, Case39_DerivedOverride) {
  parse("Base:\n    x is Real: 0.0\nD is Base:\n    x: 2.0\n");
  EXPECT_EQ(shape(), "model Base:\n  x is Real = 0.0\nmodel D is Base:\n  x = 2.0\n");
}

TEST_F(AppendixB, Case40_ChainWithLateBinding) {
  parse(
      "A:\n"
      "    x is Real: 1.0\n"
      "B is A:\n"
      "    x: 2.0\n"
      "C is B:\n"
      "    y is Real: x + 1\n");
  EXPECT_EQ(shape(),
            "model A:\n  x is Real = 1.0\nmodel B is A:\n  x = 2.0\nmodel C is B:\n  y is Real = (x + 1)\n");
}

TEST_F(AppendixB, Case41_DottedAssignment) {
  parse(
      "In:\n"
      "    v is Real: 0.0\n"
      "Mid:\n"
      "    inner is In\n"
      "Top:\n"
      "    mid is Mid\n"
      "    mid.inner.v: 5.0\n");
  EXPECT_EQ(body_of("Top"), "mid is Mid\nmid.inner.v = 5.0\n");
  const fe::Member& m = doc_.find_model("Top")->body.at(1);
  EXPECT_EQ(m.kind, fe::MemberKind::Assignment);
  EXPECT_EQ(m.path.parts.size(), 3u);
}

TEST_F(AppendixB, Case42_BlockAssignmentOnInheritedAttribute) {
  parse(
      "In:\n"
      "    v is Real: 0.0\n"
      "    w is Real: 0.0\n"
      "Mid:\n"
      "    inner is In\n"
      "Top is Mid:\n"
      "    inner:\n"
      "        v: 1.0\n"
      "        w: 2.0\n");
  EXPECT_EQ(body_of("Top"), "inner:\n  v = 1.0\n  w = 2.0\n");
  EXPECT_EQ(doc_.find_model("Top")->body.at(0).kind, fe::MemberKind::Assignment);
}

TEST_F(AppendixB, Case43_OwnerPriority) {
  parse(
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
      "        k: 4.0\n");
  EXPECT_EQ(shape(),
            "model Leaf:\n  k is Real = 1.0\n"
            "model Box:\n  leaf is Leaf:\n    k = 2.0\n"
            "model Outer:\n  box is Box:\n    leaf.k = 3.0\n"
            "model Final is Outer:\n  box.leaf:\n    k = 4.0\n");
}

TEST_F(AppendixB, Case44_ForwardUseInOneBody) {
  parse("Root:\n    b is Real: a * 2\n    a is Real: 5\n");
  EXPECT_EQ(body_of("Root"), "b is Real = (a * 2)\na is Real = 5\n");
}

TEST_F(AppendixB, Case45_UnknownTarget) {
  // semantic error expected: checked by the semantics issue ((prop) unknown attribute).
  parse("Root:\n    nope: 3\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(body_of("Root"), "nope = 3\n");
}

TEST_F(AppendixB, Case46_SpaceBeforeColon) {
  parse("Base:\n    x is Int: 0\nD is Base:\n    x : 3\n");
  EXPECT_EQ(body_of("D"), "x = 3\n");
  EXPECT_EQ(doc_.find_model("D")->body.at(0).kind, fe::MemberKind::Assignment);
}

TEST_F(AppendixB, Case47_WrongType) {
  // semantic error expected: checked by the semantics issue ((prop) type mismatch).
  parse("Root:\n    flag is Bool: 1\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(body_of("Root"), "flag is Bool = 1\n");
}

TEST_F(AppendixB, Case48_DuplicateAssignment) {
  // semantic error expected: checked by the semantics issue ((prop) duplicate assignment).
  parse("Base:\n    x is Int: 0\nD is Base:\n    x: 1\n    x: 2\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(body_of("D"), "x = 1\nx = 2\n");
}

TEST_F(AppendixB, Case49_Cycle) {
  // semantic error expected: checked by the semantics issue ((prop) cyclic dependency).
  parse("Root:\n    a is Real: b\n    b is Real: a\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(body_of("Root"), "a is Real = b\nb is Real = a\n");
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

TEST_F(AppendixB, Case50_Specialisation) {
  parse(kCase50);
  EXPECT_EQ(shape(),
            "model Shape:\n  area is Real = 0.0\n"
            "model Square is Shape:\n  side is Real = 2.0\n  area = (side * side)\n"
            "model Holder:\n  s is Shape\n"
            "model Special is Holder:\n  s becomes Square\n");
  EXPECT_EQ(doc_.find_model("Special")->body.at(0).kind, fe::MemberKind::Becomes);
}

TEST_F(AppendixB, Case51_BecomesWithBlock) {
  parse(
      "Shape:\n"
      "    area is Real: 0.0\n"
      "Square is Shape:\n"
      "    side is Real: 2.0\n"
      "    area: side * side\n"
      "Holder:\n"
      "    s is Shape\n"
      "Special is Holder:\n"
      "    s becomes Square:\n"
      "        side: 3.0\n");
  EXPECT_EQ(body_of("Special"), "s becomes Square:\n  side = 3.0\n");
}

TEST_F(AppendixB, Case52_IncompatibleBecomes) {
  // semantic error expected: checked by the semantics issue ((prop) message for the incompatible type).
  parse(std::string(kCase50) + "Other:\n    q is Int: 0\nBad is Holder:\n    s becomes Other\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(body_of("Bad"), "s becomes Other\n");
}

TEST_F(AppendixB, Case53_EarlierAssignmentSurvives) {
  // (prop) the owner's assignment beats Square's default; the parser records it in Holder's nested block.
  parse(
      "Shape:\n"
      "    area is Real: 0.0\n"
      "Square is Shape:\n"
      "    side is Real: 2.0\n"
      "    area: side * side\n"
      "Holder:\n"
      "    s is Shape:\n"
      "        area: 7.0\n"
      "Special is Holder:\n"
      "    s becomes Square\n");
  EXPECT_EQ(body_of("Holder"), "s is Shape:\n  area = 7.0\n");
  EXPECT_EQ(body_of("Special"), "s becomes Square\n");
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

TEST_F(AppendixB, Case54_UnionNarrowing) {
  // (prop) loading Home is a missing-assignment error (semantic); the parser records the union.
  parse(kCase54);
  EXPECT_EQ(body_of("Home"), "pet is Cat or Dog\n");
  EXPECT_EQ(doc_.find_model("Home")->body.at(0).type.alternatives.size(), 2u);
  EXPECT_EQ(body_of("CatHome"), "pet becomes Cat\n");
}

TEST_F(AppendixB, Case55_BecomesOutsideUnion) {
  // semantic error expected: checked by the semantics issue (incompatible type).
  parse(
      "Wheel:\n"
      "    r is Real: 0.3\n"
      "Cat:\n"
      "    lives is Int: 9\n"
      "Dog:\n"
      "    loud is Bool: true\n"
      "Home:\n"
      "    pet is Cat or Dog\n"
      "CatHome is Home:\n"
      "    pet becomes Wheel\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(body_of("CatHome"), "pet becomes Wheel\n");
}

// ---------------------------------------------------------------- Traits

TEST_F(AppendixB, Case56_Inclusion) {
  parse(
      "trait Named:\n"
      "    id is Int: 7\n"
      "Robot:\n"
      "    with Named\n"
      "    twice is Int: this.id * 2\n");
  EXPECT_EQ(shape(),
            "trait Named:\n  id is Int = 7\nmodel Robot:\n  with Named\n  twice is Int = (this.id * 2)\n");
}

TEST_F(AppendixB, Case57_TwoTraits) {
  parse(
      "trait TA:\n    a is Int: 1\ntrait TB:\n    b is Int: 2\nM:\n    with TA\n    with TB\n    s is Int: a "
      "+ b\n");
  EXPECT_EQ(shape(),
            "trait TA:\n  a is Int = 1\ntrait TB:\n  b is Int = 2\n"
            "model M:\n  with TA\n  with TB\n  s is Int = (a + b)\n");
}

TEST_F(AppendixB, Case58_TraitExtension) {
  parse("trait P:\n    a is Int: 1\ntrait Q is P:\n    b is Int: 2\nM:\n    with Q\n    s is Int: a + b\n");
  EXPECT_EQ(
      shape(),
      "trait P:\n  a is Int = 1\ntrait Q is P:\n  b is Int = 2\nmodel M:\n  with Q\n  s is Int = (a + b)\n");
}

TEST_F(AppendixB, Case59_TraitAsType) {
  parse(
      "trait Tagged:\n"
      "    tag is Int: 5\n"
      "Item:\n"
      "    with Tagged\n"
      "Store:\n"
      "    item is Item\n"
      "    t is Tagged: item\n"
      "    v is Int: t.tag\n");
  EXPECT_EQ(body_of("Store"), "item is Item\nt is Tagged = item\nv is Int = t.tag\n");
  EXPECT_EQ(body_of("Item"), "with Tagged\n");
}

TEST_F(AppendixB, Case60_TraitsOnAttributeType) {
  parse(
      "trait Red:\n"
      "    red is Real: 1.0\n"
      "trait Heavy:\n"
      "    kg is Real: 50.0\n"
      "Crate:\n"
      "    w is Real: 2.0\n"
      "Yard:\n"
      "    crate is Crate with Red, Heavy:\n"
      "        kg: 60.0\n"
      "    total is Real: crate.w + crate.red + crate.kg\n");
  EXPECT_EQ(
      body_of("Yard"),
      "crate is Crate with Red, Heavy:\n  kg = 60.0\ntotal is Real = ((crate.w + crate.red) + crate.kg)\n");
  EXPECT_EQ(doc_.find_model("Yard")->body.at(0).type.traits.size(), 2u);
}

TEST_F(AppendixB, Case61_TraitUsesWith) {
  // semantic error expected: checked by the semantics issue (traits cannot use `with`).
  parse("trait Named:\n    id is Int: 7\ntrait Bad:\n    with Named\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(shape(), "trait Named:\n  id is Int = 7\ntrait Bad:\n  with Named\n");
}

TEST_F(AppendixB, Case62_CommonAncestor) {
  // semantic error expected: checked by the semantics issue (shared-ancestor error).
  parse(
      "trait Z:\n    z is Int: 0\ntrait L is Z:\n    l is Int: 1\ntrait R is Z:\n    r is Int: 2\n"
      "M:\n    with L\n    with R\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(body_of("M"), "with L\nwith R\n");
}

TEST_F(AppendixB, Case63_InjectedNameClash) {
  // semantic error expected: checked by the semantics issue (injected-name error).
  parse("trait T:\n    n is Int: 1\nM:\n    n is Int: 2\n    with T\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(body_of("M"), "n is Int = 2\nwith T\n");
}

TEST_F(AppendixB, Case64_TraitAsRoot) {
  // semantic error expected: checked by the semantics issue ((prop) no loadable model / cannot instantiate).
  parse("trait Solo:\n    a is Int: 1\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(shape(), "trait Solo:\n  a is Int = 1\n");
  EXPECT_EQ(doc_.last_model(), nullptr);
}

// ---------------------------------------------------------------- const models

TEST_F(AppendixB, Case65_ConstGlobalAccess) {
  parse("const Settings:\n    gain is Real: 3.0\nRoot:\n    g is Real: Settings.gain + 1.0\n");
  EXPECT_EQ(
      shape(),
      "const model Settings:\n  gain is Real = 3.0\nmodel Root:\n  g is Real = (Settings.gain + 1.0)\n");
}

TEST_F(AppendixB, Case66_ConstAliases) {
  parse("const Settings:\n    gain is Real: 3.0\nRoot:\n    s is Settings\n    t is Settings\n");
  EXPECT_EQ(shape(),
            "const model Settings:\n  gain is Real = 3.0\nmodel Root:\n  s is Settings\n  t is Settings\n");
}

TEST_F(AppendixB, Case67_EnumStyle) {
  parse("const Mode:\n    Off is Int: 0\n    On is Int: 1\nRoot:\n    m is Int: Mode.On\n");
  EXPECT_EQ(shape(),
            "const model Mode:\n  Off is Int = 0\n  On is Int = 1\nmodel Root:\n  m is Int = Mode.On\n");
  const fe::Expr& v = doc_.expr(*doc_.find_model("Root")->body.at(0).value);
  EXPECT_EQ(v.kind, fe::ExprKind::Member);
  EXPECT_EQ(v.text, "On");
}

TEST_F(AppendixB, Case68_ConstModelAsValue) {
  parse(
      "Material:\n"
      "    density is Real: 1000.0\n"
      "const Steel is Material:\n"
      "    density: 7800.0\n"
      "Part:\n"
      "    mat is Material\n"
      "Root:\n"
      "    p is Part:\n"
      "        mat: Steel\n"
      "    d is Real: p.mat.density\n");
  EXPECT_EQ(shape(),
            "model Material:\n  density is Real = 1000.0\n"
            "const model Steel is Material:\n  density = 7800.0\n"
            "model Part:\n  mat is Material\n"
            "model Root:\n  p is Part:\n    mat = Steel\n  d is Real = p.mat.density\n");
}

TEST_F(AppendixB, Case69_WritingToConst) {
  // semantic error expected: checked by the semantics issue ((prop) read-only const).
  parse(
      "const Settings:\n    gain is Real: 3.0\nRoot:\n    s is Settings\n    t is Settings\n    s.gain: "
      "9.0\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(body_of("Root"), "s is Settings\nt is Settings\ns.gain = 9.0\n");
}

// ---------------------------------------------------------------- Annotations

TEST_F(AppendixB, Case70_DocString) {
  parse(
      "Root:\n"
      "    .doc: \"\"\"Root model\n"
      "more\"\"\"\n"
      "    a is Int: 1\n");
  EXPECT_EQ(shape(), "model Root:\n  .doc = \"Root model\\nmore\"\n  a is Int = 1\n");
  const fe::Member& doc = doc_.decls.at(0).body.at(0);
  EXPECT_EQ(doc.kind, fe::MemberKind::Annotation);
  EXPECT_EQ(doc_.expr(*doc.value).string_value, "Root model\nmore");
  EXPECT_TRUE(doc_.expr(*doc.value).multiline);
}

TEST_F(AppendixB, Case71_AnnotationsOnAnAttribute) {
  parse("Leaf:\n    k is Int: 0\nRoot:\n    leaf is Leaf:\n        .unit: \"m\"\n        .prio: 3\n");
  // The annotations sit in leaf's nested block, not in Root's body.
  EXPECT_EQ(body_of("Root"), "leaf is Leaf:\n  .unit = \"m\"\n  .prio = 3\n");
  EXPECT_EQ(doc_.find_model("Root")->body.at(0).block.at(0).kind, fe::MemberKind::Annotation);
}

TEST_F(AppendixB, Case72_AnnotationThroughInheritedAttribute) {
  parse("Leaf:\n    k is Int: 0\nBase:\n    leaf is Leaf\nRoot is Base:\n    leaf:\n        .hidden: true\n");
  EXPECT_EQ(body_of("Root"), "leaf:\n  .hidden = true\n");
  const fe::Member& assign = doc_.find_model("Root")->body.at(0);
  EXPECT_EQ(assign.kind, fe::MemberKind::Assignment);
  EXPECT_EQ(assign.block.at(0).kind, fe::MemberKind::Annotation);
}

TEST_F(AppendixB, Case73_NonConstantAnnotation) {
  parse("Leaf:\n    k is Int: 0\nRoot:\n    leaf is Leaf\n    .metadata: leaf\n");
  expect_diag(fe::DiagCode::AnnotationNotConstant, 5, 16);
  EXPECT_EQ(body_of("Root"), "leaf is Leaf\n");
}

// ---------------------------------------------------------------- Expressions, scope, methods

TEST_F(AppendixB, Case74_BindingStrength) {
  parse(
      "Root:\n    a is Real: 2 + 3 * 4\n    b is Real: (2 + 3) * 4\n    c is Real: 10 - 4 - 3\n"
      "    d is Real: 8 / 2 / 2\n");
  EXPECT_EQ(body_of("Root"),
            "a is Real = (2 + (3 * 4))\nb is Real = ((2 + 3) * 4)\nc is Real = ((10 - 4) - 3)\n"
            "d is Real = ((8 / 2) / 2)\n");
}

TEST_F(AppendixB, Case75_UnaryMinus) {
  parse("Root:\n    a is Int: 4\n    b is Int: -a\n    c is Real: -2 * 3\n");
  EXPECT_EQ(body_of("Root"), "a is Int = 4\nb is Int = (-a)\nc is Real = ((-2) * 3)\n");
}

TEST_F(AppendixB, Case76_IntDivision) {
  // (prop) Int / Int gives Real (evaluation); the parser sees a division of two Int literals.
  parse("Root:\n    q is Real: 7 / 2\n");
  EXPECT_EQ(body_of("Root"), "q is Real = (7 / 2)\n");
  const fe::Expr& v = doc_.expr(*doc_.decls.at(0).body.at(0).value);
  EXPECT_EQ(doc_.expr(v.operands[0]).kind, fe::ExprKind::Int);
  EXPECT_EQ(doc_.expr(v.operands[1]).kind, fe::ExprKind::Int);
}

TEST_F(AppendixB, Case77_ThisAgainstGlobal) {
  parse("x is Real: 100.0\nRoot:\n    x is Real: 1.0\n    y is Real: this.x + 1\n");
  EXPECT_EQ(shape(),
            "global x is Real = 100.0\nmodel Root:\n  x is Real = 1.0\n  y is Real = (this.x + 1)\n");
  const fe::Expr& sum = doc_.expr(*doc_.find_model("Root")->body.at(1).value);
  const fe::Expr& member = doc_.expr(sum.operands[0]);
  ASSERT_EQ(member.kind, fe::ExprKind::Member);
  EXPECT_EQ(doc_.expr(member.operands[0]).kind, fe::ExprKind::This);
}

TEST_F(AppendixB, Case78_OutermostScope) {
  parse("Leaf:\n    k is Real: 0.0\nRoot:\n    base is Real: 5.0\n    leaf is Leaf:\n        k: base * 2\n");
  EXPECT_EQ(body_of("Root"), "base is Real = 5.0\nleaf is Leaf:\n  k = (base * 2)\n");
}

TEST_F(AppendixB, Case79_QualifiedNameFromOuterScope) {
  parse("Leaf:\n    k is Real: 3.0\n    m is Real: 0.0\nRoot:\n    leaf is Leaf:\n        m: leaf.k + 1\n");
  EXPECT_EQ(body_of("Root"), "leaf is Leaf:\n  m = (leaf.k + 1)\n");
  // (prop) the variant `m: k + 1` is an unknown-name error; it parses cleanly and is left to sema.
  parse("Leaf:\n    k is Real: 3.0\n    m is Real: 0.0\nRoot:\n    leaf is Leaf:\n        m: k + 1\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(body_of("Root"), "leaf is Leaf:\n  m = (k + 1)\n");
}

TEST_F(AppendixB, Case80_LateBindingInNestedType) {
  parse("A:\n    x is Real: 1.0\n    y is Real: x * 10\nS:\n    a is A:\n        x: 2.0\n");
  EXPECT_EQ(shape(),
            "model A:\n  x is Real = 1.0\n  y is Real = (x * 10)\nmodel S:\n  a is A:\n    x = 2.0\n");
}

TEST_F(AppendixB, Case81_ThisAsValue) {
  parse(
      "Probe:\n"
      "    optional target is Body\n"
      "Body:\n"
      "    mass is Real: 2.0\n"
      "    probe is Probe:\n"
      "        target: this\n"
      "Root:\n"
      "    b is Body\n"
      "    m is Real: b.probe.target.mass\n");
  EXPECT_EQ(shape(),
            "model Probe:\n  optional target is Body\n"
            "model Body:\n  mass is Real = 2.0\n  probe is Probe:\n    target = this\n"
            "model Root:\n  b is Body\n  m is Real = b.probe.target.mass\n");
  const fe::Member& target = doc_.find_model("Body")->body.at(1).block.at(0);
  EXPECT_EQ(doc_.expr(*target.value).kind, fe::ExprKind::This);
}

TEST_F(AppendixB, Case82_VectorOperators) {
  parse(
      "Root:\n"
      "    a is Math.Vec3: Math.Vec3.from_xyz(1, 2, 3)\n"
      "    b is Math.Vec3: {2, 3, 4}\n"
      "    s is Math.Vec3: a + b\n"
      "    d is Real: a * b\n"
      "    k is Math.Vec3: 3 * a\n"
      "    h is Math.Vec3: b / 2\n"
      "    n is Math.Vec3: -a\n");
  EXPECT_EQ(body_of("Root"),
            "a is Math.Vec3 = Math.Vec3.from_xyz(1, 2, 3)\n"
            "b is Math.Vec3 = {2, 3, 4}\n"
            "s is Math.Vec3 = (a + b)\n"
            "d is Real = (a * b)\n"
            "k is Math.Vec3 = (3 * a)\n"
            "h is Math.Vec3 = (b / 2)\n"
            "n is Math.Vec3 = (-a)\n");
}

TEST_F(AppendixB, Case83_InstanceCalls) {
  parse(
      "Root:\n"
      "    l is Real: Math.Vec3.from_xyz(3, 4, 0).length()\n"
      "    u is Math.Vec3: Math.Vec3.from_xyz(0, 0, 5).normal()\n");
  EXPECT_EQ(body_of("Root"),
            "l is Real = Math.Vec3.from_xyz(3, 4, 0).length()\n"
            "u is Math.Vec3 = Math.Vec3.from_xyz(0, 0, 5).normal()\n");
  const fe::Expr& call = doc_.expr(*doc_.decls.at(0).body.at(0).value);
  ASSERT_EQ(call.kind, fe::ExprKind::Call);
  EXPECT_EQ(doc_.expr(call.operands[0]).text, "length");
}

TEST_F(AppendixB, Case84_InitializerAsOperand) {
  // (prop) the initializer takes the expected type of the whole division (sema).
  parse("Root:\n    m is Math.Vec3: {2, 4, 6} / 2\n");
  EXPECT_EQ(body_of("Root"), "m is Math.Vec3 = ({2, 4, 6} / 2)\n");
  const fe::Expr& div = doc_.expr(*doc_.decls.at(0).body.at(0).value);
  EXPECT_EQ(doc_.expr(div.operands[0]).kind, fe::ExprKind::Initializer);
}

TEST_F(AppendixB, Case85_InitializerArity) {
  // semantic error expected: checked by the semantics issue ((prop) initializer arity).
  parse("Root:\n    v is Math.Vec3: {1, 2, 3, 4}\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(body_of("Root"), "v is Math.Vec3 = {1, 2, 3, 4}\n");
}

TEST_F(AppendixB, Case86_ConstantsAndFunctions) {
  parse("Root:\n    h is Real: Math.PI / 2\n    r is Real: Math.Functions.sqrt(16)\n");
  EXPECT_EQ(body_of("Root"), "h is Real = (Math.PI / 2)\nr is Real = Math.Functions.sqrt(16)\n");
}

TEST_F(AppendixB, Case87_Quaternion) {
  parse(
      "Root:\n"
      "    q is Math.Quat: Math.Quat.angle_axis(Math.PI, Math.Vec3.Z_AXIS())\n"
      "    v is Math.Vec3: q.rotate(Math.Vec3.X_AXIS())\n");
  EXPECT_EQ(body_of("Root"),
            "q is Math.Quat = Math.Quat.angle_axis(Math.PI, Math.Vec3.Z_AXIS())\n"
            "v is Math.Vec3 = q.rotate(Math.Vec3.X_AXIS())\n");
}

TEST_F(AppendixB, Case88_Vec3WithoutValue) {
  parse("Root:\n    p is Math.Vec3\n");
  EXPECT_EQ(body_of("Root"), "p is Math.Vec3\n");
  EXPECT_FALSE(doc_.decls.at(0).body.at(0).value.has_value());
}

TEST_F(AppendixB, Case89_CallingVoidMethod) {
  // semantic error expected: checked by the semantics issue ((prop) method has no return value).
  parse("Gadget:\n    fn reset()\nRoot:\n    g is Gadget\n    x is Real: g.reset()\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(shape(), "model Gadget:\n  fn reset()\nmodel Root:\n  g is Gadget\n  x is Real = g.reset()\n");
}

TEST_F(AppendixB, Case90_NoOperatorForTypes) {
  // semantic error expected: checked by the semantics issue ((prop) no operator + for T and T).
  parse("T:\n    a is Int: 0\nRoot:\n    p is T\n    q is T\n    r is T: p + q\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(body_of("Root"), "p is T\nq is T\nr is T = (p + q)\n");
}

TEST_F(AppendixB, Case91_DeclaredOperator) {
  // semantic error expected: checked by the semantics issue ((prop) type-checks; evaluating it without a
  // native implementation is `No implementation for operator`).
  parse(
      "Money:\n    c is Int: 0\noperator +(lhs: Money, rhs: Money) -> Money\n"
      "Root:\n    a is Money\n    b is Money\n    t is Money: a + b\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(shape(),
            "model Money:\n  c is Int = 0\noperator +(lhs: Money, rhs: Money) -> Money\n"
            "model Root:\n  a is Money\n  b is Money\n  t is Money = (a + b)\n");
}

TEST_F(AppendixB, Case92_StaticCallOnInstance) {
  // semantic error expected: checked by the semantics issue ((prop) static method called on instance).
  parse("Vec:\n    static fn make() -> Vec\nRoot:\n    v is Vec\n    w is Vec: v.make()\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(shape(),
            "model Vec:\n  static fn make() -> Vec\nmodel Root:\n  v is Vec\n  w is Vec = v.make()\n");
}

// ---------------------------------------------------------------- Imports and bundles

TEST_F(AppendixB, Case93_MissingImport) {
  // semantic error expected: checked by the semantics issue ((prop) could not find imported file).
  parse("import @\"nope.obj\"\nRoot\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(shape(), "import @\"nope.obj\"\nmodel Root\n");
}

TEST_F(AppendixB, Case94_UnknownPlugin) {
  // semantic error expected: checked by the semantics issue ((prop) no plugin for `.xyz`).
  parse("import @\"data.xyz\" as Thing\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(shape(), "import @\"data.xyz\" as Thing\n");
}

TEST_F(AppendixB, Case95_BundleNamespace) {
  parse("config is BundleConfig:\n    name: \"Shop\"\n", "B/shop/config.openplx");
  // §3.1: `config is BundleConfig:` with a block is a model deriving from BundleConfig.
  EXPECT_EQ(shape(), "model config is BundleConfig:\n  name = \"Shop\"\n");
  parse("Hammer:\n    kg is Real: 1.2\n", "B/shop/Items/Tools.openplx");
  EXPECT_EQ(shape(), "model Hammer:\n  kg is Real = 1.2\n");
  parse("Bench:\n    h is Items.Hammer\n", "B/shop/scene.openplx");
  EXPECT_EQ(shape(), "model Bench:\n  h is Items.Hammer\n");
  EXPECT_TRUE(clean());
}

TEST_F(AppendixB, Case96_FromOutsideTheBundle) {
  parse("Yard:\n    h is Shop.Items.Hammer\n");
  EXPECT_EQ(shape(), "model Yard:\n  h is Shop.Items.Hammer\n");
  EXPECT_EQ(doc_.decls.at(0).body.at(0).type.alternatives[0].name.parts.size(), 3u);
}

TEST_F(AppendixB, Case97_SameNamespaceWithoutQualification) {
  parse("Kit:\n    tool is Hammer\n", "B/shop/Items/Kit.openplx");
  EXPECT_EQ(shape(), "model Kit:\n  tool is Hammer\n");
}

TEST_F(AppendixB, Case98_FileNameIsNotANamespace) {
  // semantic error expected: checked by the semantics issue ((prop) unknown name).
  parse("Yard:\n    x is Shop.Items.Tools.Hammer\n");
  EXPECT_TRUE(clean());
  EXPECT_EQ(shape(), "model Yard:\n  x is Shop.Items.Tools.Hammer\n");
}

TEST_F(AppendixB, Case99_GlobalInAFolder) {
  parse("MAXKG is Real: 9.0\n", "B/shop/Items/Limits.openplx");
  EXPECT_EQ(shape(), "global MAXKG is Real = 9.0\n");
  parse("Root:\n    m is Real: Shop.Items.MAXKG\n");
  EXPECT_EQ(shape(), "model Root:\n  m is Real = Shop.Items.MAXKG\n");
}

TEST_F(AppendixB, Case100_DependencySyntax) {
  parse("config is BundleConfig:\n    name: \"Shop\"\n    dependencies: [\"Math\", \"Other@1.2.3\"]\n",
        "B/shop/config.openplx");
  EXPECT_EQ(
      shape(),
      "model config is BundleConfig:\n  name = \"Shop\"\n  dependencies = [\"Math\", \"Other@1.2.3\"]\n");
  const fe::Expr& deps = doc_.expr(*doc_.decls.at(0).body.at(1).value);
  ASSERT_EQ(deps.kind, fe::ExprKind::Array);
  ASSERT_EQ(deps.operands.size(), 2u);
  EXPECT_EQ(doc_.expr(deps.operands[0]).string_value, "Math");
  EXPECT_EQ(doc_.expr(deps.operands[1]).string_value, "Other@1.2.3");
}

TEST_F(AppendixB, Case101_UndeclaredBundle) {
  // semantic error expected: checked by the semantics issue ((prop) unknown name / undeclared dependency).
  parse("Bench:\n    s is Physics3D.System\n", "B/shop/scene.openplx");
  EXPECT_TRUE(clean());
  EXPECT_EQ(shape(), "model Bench:\n  s is Physics3D.System\n");
}

}  // namespace
