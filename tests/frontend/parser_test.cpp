// Unit tests of the parser's AST (../shared/spec/openplx-language.md §3): every declaration and member form,
// the expression grammar with its binding strength, source ranges, and the Document helpers.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "frontend/syntax/ast.h"
#include "frontend/syntax/ast_dump.h"
#include "tests/support/parse_fixture.h"

namespace {

namespace fe = openplx::frontend;

class ParserTest : public openplx::testing::ParseTest {
 protected:
  std::string str(fe::ExprId id) const { return fe::expr_to_string(doc_, id); }
  std::string str(const std::optional<fe::ExprId>& id) const { return id ? str(*id) : "<none>"; }
  const fe::Expr& ex(fe::ExprId id) const { return doc_.expr(id); }

  // Parses `x is Real: <expression>` as a global attribute and returns its value printed fully parenthesised.
  std::string value(const std::string& expression) {
    const fe::Document& doc = parse("x is Real: " + expression + "\n");
    if (doc.decls.size() != 1 || doc.decls[0].kind != fe::DeclKind::GlobalAttribute || !doc.decls[0].value) {
      ADD_FAILURE() << "`" << expression << "` did not parse as one global attribute:\n" << all_diags();
      return "<no value>";
    }
    return str(*doc.decls[0].value);
  }
  fe::ExprId value_id() const { return *doc_.decls.at(0).value; }

  std::string pos(uint32_t offset) const {
    fe::LineCol lc = sources_.file(file_).line_col(offset);
    return std::to_string(lc.line) + ":" + std::to_string(lc.col);
  }
  std::string range(fe::SourceRange r) const { return pos(r.begin) + "-" + pos(r.end); }

  static std::string type(const fe::TypeExpr& t) {
    std::string out;
    for (size_t i = 0; i < t.alternatives.size(); ++i) {
      out += (i ? " or " : "") + fe::to_string(t.alternatives[i].name) +
             (t.alternatives[i].is_array ? "[]" : "");
    }
    for (size_t i = 0; i < t.traits.size(); ++i) out += (i ? ", " : " with ") + fe::to_string(t.traits[i]);
    return out;
  }
  static std::string type_ref(const fe::TypeRef& t) {
    return fe::to_string(t.name) + (t.is_array ? "[]" : "");
  }
  static std::string params(const std::vector<fe::Param>& ps) {
    std::string out;
    for (size_t i = 0; i < ps.size(); ++i) {
      out += (i ? ", " : "") + std::string(ps[i].name.text) + ": " + type_ref(ps[i].type);
    }
    return out;
  }
};

// ---- models

TEST_F(ParserTest, PlainModel) {
  parse("Root:\n    a is Int: 1\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const fe::Decl& d = doc_.decls[0];
  EXPECT_EQ(d.kind, fe::DeclKind::Model);
  EXPECT_EQ(d.name.text, "Root");
  EXPECT_FALSE(d.name.quoted);
  EXPECT_FALSE(d.is_const);
  EXPECT_FALSE(d.base.has_value());
  EXPECT_TRUE(d.traits.empty());
  EXPECT_TRUE(d.has_body);
  ASSERT_EQ(d.body.size(), 1u);
  EXPECT_EQ(d.body[0].kind, fe::MemberKind::Attribute);
  EXPECT_EQ(fe::to_string(d.body[0].path), "a");
  EXPECT_EQ(type(d.body[0].type), "Int");
  EXPECT_EQ(str(d.body[0].value), "1");
}

TEST_F(ParserTest, ModelWithBase) {
  parse("D is Base:\n    x: 3\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const fe::Decl& d = doc_.decls[0];
  EXPECT_EQ(d.kind, fe::DeclKind::Model);
  ASSERT_TRUE(d.base.has_value());
  EXPECT_EQ(fe::to_string(*d.base), "Base");
  ASSERT_EQ(d.body.size(), 1u);
  EXPECT_EQ(d.body[0].kind, fe::MemberKind::Assignment);
}

TEST_F(ParserTest, ModelWithQualifiedBase) {
  parse("Car is Vehicles.Wheeled.Car:\n    wheels: 4\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  ASSERT_TRUE(doc_.decls[0].base.has_value());
  EXPECT_EQ(doc_.decls[0].base->parts.size(), 3u);
  EXPECT_EQ(fe::to_string(*doc_.decls[0].base), "Vehicles.Wheeled.Car");
}

TEST_F(ParserTest, ConstModel) {
  parse("const Settings:\n    gain is Real: 3.0\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  EXPECT_EQ(doc_.decls[0].kind, fe::DeclKind::Model);
  EXPECT_TRUE(doc_.decls[0].is_const);
  EXPECT_EQ(doc_.decls[0].name.text, "Settings");
  EXPECT_EQ(doc_.decls[0].body.size(), 1u);
}

TEST_F(ParserTest, ConstEmptyDerivedModel) {
  parse("const GroundMaterial is Physics.Geometries.Material\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const fe::Decl& d = doc_.decls[0];
  EXPECT_EQ(d.kind, fe::DeclKind::Model);
  EXPECT_TRUE(d.is_const);
  ASSERT_TRUE(d.base.has_value());
  EXPECT_EQ(fe::to_string(*d.base), "Physics.Geometries.Material");
  EXPECT_FALSE(d.has_body);
}

TEST_F(ParserTest, EmptyModelWithoutColon) {
  parse("Lonely\nAlias is Base\n");
  ASSERT_EQ(doc_.decls.size(), 2u);
  EXPECT_EQ(doc_.decls[0].kind, fe::DeclKind::Model);
  EXPECT_EQ(doc_.decls[0].name.text, "Lonely");
  EXPECT_FALSE(doc_.decls[0].has_body);
  EXPECT_FALSE(doc_.decls[0].base.has_value());
  EXPECT_TRUE(doc_.decls[0].body.empty());
  EXPECT_EQ(doc_.decls[1].kind, fe::DeclKind::Model);
  EXPECT_EQ(doc_.decls[1].name.text, "Alias");
  ASSERT_TRUE(doc_.decls[1].base.has_value());
  EXPECT_EQ(fe::to_string(*doc_.decls[1].base), "Base");
  EXPECT_FALSE(doc_.decls[1].has_body);
}

TEST_F(ParserTest, ModelWithTraitShorthand) {
  // Proposed (§3 notes): `Model is Base with T1, T2` is shorthand for `with` lines in the body.
  parse("M is Base with T1, Ns.T2:\n    a is Int: 1\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const fe::Decl& d = doc_.decls[0];
  EXPECT_EQ(d.kind, fe::DeclKind::Model);
  ASSERT_TRUE(d.base.has_value());
  EXPECT_EQ(fe::to_string(*d.base), "Base");
  ASSERT_EQ(d.traits.size(), 2u);
  EXPECT_EQ(fe::to_string(d.traits[0]), "T1");
  EXPECT_EQ(fe::to_string(d.traits[1]), "Ns.T2");
  EXPECT_EQ(d.body.size(), 1u);
}

TEST_F(ParserTest, BlockOpenerWithoutColonIsAcceptedWithAWarning) {
  // Proposed (§2.3 leniency): a missing final `:` before a deeper block is taken as there, with a warning.
  parse("M is Base with T1, T2\n    a is Int: 1\n");
  expect_diag(fe::DiagCode::MissingColon, 1, 22);
  ASSERT_EQ(doc_.decls.size(), 1u);
  EXPECT_TRUE(doc_.decls[0].has_body);
  EXPECT_EQ(doc_.decls[0].traits.size(), 2u);
  EXPECT_EQ(doc_.decls[0].body.size(), 1u);
}

TEST_F(ParserTest, QuotedModelName) {
  parse("`my model`:\n    a is Int: 1\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  EXPECT_EQ(doc_.decls[0].name.text, "my model");
  EXPECT_TRUE(doc_.decls[0].name.quoted);
}

TEST_F(ParserTest, ModelBaseCannotBeAUnionOrArray) {
  parse("M is A or B:\n    a is Int: 1\n");
  expect_diag(fe::DiagCode::InvalidModelBase, 1, 6);
  EXPECT_EQ(doc_.find_model("M"), nullptr);
}

// ---- traits

TEST_F(ParserTest, Trait) {
  parse("trait Named:\n    id is Int: 7\n    fn name() -> String\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const fe::Decl& d = doc_.decls[0];
  EXPECT_EQ(d.kind, fe::DeclKind::Trait);
  EXPECT_EQ(d.name.text, "Named");
  EXPECT_FALSE(d.base.has_value());
  ASSERT_EQ(d.body.size(), 2u);
  EXPECT_EQ(d.body[0].kind, fe::MemberKind::Attribute);
  EXPECT_EQ(d.body[1].kind, fe::MemberKind::Method);
}

TEST_F(ParserTest, TraitExtendingTrait) {
  parse("trait Q is Ns.P:\n    b is Int: 2\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  EXPECT_EQ(doc_.decls[0].kind, fe::DeclKind::Trait);
  ASSERT_TRUE(doc_.decls[0].base.has_value());
  EXPECT_EQ(fe::to_string(*doc_.decls[0].base), "Ns.P");
}

TEST_F(ParserTest, EmptyTrait) {
  parse("trait Marker\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  EXPECT_EQ(doc_.decls[0].kind, fe::DeclKind::Trait);
  EXPECT_FALSE(doc_.decls[0].has_body);
}

TEST_F(ParserTest, TraitWithoutColonBeforeBlock) {
  // Proposed (§2.3 leniency, `trait BoxGeometry` in S11/S12): the colon is taken as there, with a warning.
  parse("trait BoxGeometry\n    size is Real: 1.0\n");
  expect_diag(fe::DiagCode::MissingColon, 1, 18);
  ASSERT_EQ(doc_.decls.size(), 1u);
  EXPECT_EQ(doc_.decls[0].kind, fe::DeclKind::Trait);
  EXPECT_TRUE(doc_.decls[0].has_body);
  EXPECT_EQ(doc_.decls[0].body.size(), 1u);
}

TEST_F(ParserTest, ColonWithoutBlockAtTopLevelRecovers) {
  parse("Broken:\n# nothing\nNext:\n    a is Int: 1\n");
  EXPECT_EQ(expect_diag(fe::DiagCode::ExpectedIndentedBlock, 1, 7), "Expected indented block");
  EXPECT_EQ(doc_.find_model("Broken"), nullptr);
  ASSERT_NE(doc_.find_model("Next"), nullptr);
  EXPECT_EQ(doc_.find_model("Next")->body.size(), 1u);
}

TEST_F(ParserTest, TraitHeadCannotUseWith) {
  parse("trait T with U:\n    a is Int: 1\n");
  expect_diag(fe::DiagCode::MisplacedDeclaration, 1, 9);
  EXPECT_TRUE(doc_.decls.empty());
}

// ---- global attributes

TEST_F(ParserTest, GlobalAttribute) {
  parse("PI is Real: 3.14\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const fe::Decl& d = doc_.decls[0];
  EXPECT_EQ(d.kind, fe::DeclKind::GlobalAttribute);
  EXPECT_EQ(d.name.text, "PI");
  EXPECT_EQ(type(d.type), "Real");
  ASSERT_TRUE(d.value.has_value());
  EXPECT_EQ(ex(*d.value).kind, fe::ExprKind::Real);
  EXPECT_DOUBLE_EQ(ex(*d.value).real_value, 3.14);
}

TEST_F(ParserTest, GlobalAttributeOfModelType) {
  parse("AlongAxle is Math.Vec3: Math.Vec3.Y_AXIS()\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  EXPECT_EQ(doc_.decls[0].kind, fe::DeclKind::GlobalAttribute);
  EXPECT_EQ(type(doc_.decls[0].type), "Math.Vec3");
  EXPECT_EQ(str(doc_.decls[0].value), "Math.Vec3.Y_AXIS()");
}

TEST_F(ParserTest, NameIsTypeColonBlockIsAModel) {
  // §3.1: `Name is T:` followed by a block declares a model deriving from T.
  parse("config is BundleConfig:\n    name: \"Shop\"\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  EXPECT_EQ(doc_.decls[0].kind, fe::DeclKind::Model);
  EXPECT_EQ(doc_.decls[0].name.text, "config");
  ASSERT_TRUE(doc_.decls[0].base.has_value());
  EXPECT_EQ(fe::to_string(*doc_.decls[0].base), "BundleConfig");
}

TEST_F(ParserTest, ConstGlobalIsRejected) {
  parse("const g is Real: 1.0\n");
  expect_diag(fe::DiagCode::MisplacedDeclaration, 1, 1);
  EXPECT_TRUE(doc_.decls.empty());
}

// ---- imports

TEST_F(ParserTest, ImportWithoutAlias) {
  parse("import @\"x.urdf\"\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const fe::Decl& d = doc_.decls[0];
  EXPECT_EQ(d.kind, fe::DeclKind::Import);
  ASSERT_TRUE(d.value.has_value());
  EXPECT_EQ(ex(*d.value).kind, fe::ExprKind::PathString);
  EXPECT_EQ(ex(*d.value).string_value, "x.urdf");
  EXPECT_FALSE(ex(*d.value).quoted);
  EXPECT_FALSE(d.alias.has_value());
}

TEST_F(ParserTest, DollarImportWithDottedAlias) {
  parse("import $\"r.urdf\" as a.b\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const fe::Decl& d = doc_.decls[0];
  EXPECT_EQ(d.kind, fe::DeclKind::Import);
  ASSERT_TRUE(d.value.has_value());
  EXPECT_EQ(ex(*d.value).kind, fe::ExprKind::PathString);
  EXPECT_EQ(ex(*d.value).string_value, "r.urdf");
  EXPECT_TRUE(ex(*d.value).quoted);  // written with `$`
  ASSERT_TRUE(d.alias.has_value());
  EXPECT_EQ(fe::to_string(*d.alias), "a.b");
  EXPECT_EQ(d.alias->parts.size(), 2u);
}

TEST_F(ParserTest, ImportWithSimpleAlias) {
  parse("import @\"checkerboardRGBA.png\" as Checkerboard\nRoot\n");
  ASSERT_EQ(doc_.decls.size(), 2u);
  ASSERT_TRUE(doc_.decls[0].alias.has_value());
  EXPECT_EQ(fe::to_string(*doc_.decls[0].alias), "Checkerboard");
  EXPECT_EQ(doc_.decls[1].kind, fe::DeclKind::Model);
}

TEST_F(ParserTest, ImportNeedsAPathString) {
  parse("import \"x.urdf\"\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 1, 8);
  EXPECT_TRUE(doc_.decls.empty());
}

TEST_F(ParserTest, DollarPathOutsideImportIsAnError) {
  parse("R:\n    p is String: $\"a.obj\"\n");
  expect_diag(fe::DiagCode::DollarPathOutsideImport, 2, 18);
}

TEST_F(ParserTest, AsIsAnOrdinaryNameOutsideImport) {
  parse("R:\n    as is Int: 1\n    from is Int: 2\n    type is Int: 3\n    range is Int: 4\n    to: as\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  ASSERT_EQ(doc_.decls[0].body.size(), 5u);
  EXPECT_EQ(fe::to_string(doc_.decls[0].body[0].path), "as");
  EXPECT_EQ(fe::to_string(doc_.decls[0].body[3].path), "range");
  EXPECT_EQ(doc_.decls[0].body[4].kind, fe::MemberKind::Assignment);
  EXPECT_EQ(str(doc_.decls[0].body[4].value), "as");
}

// ---- attribute declarations

TEST_F(ParserTest, AttributeForms) {
  parse(
      "R:\n"
      "    a is Int\n"
      "    b is Real: 2.5\n"
      "    optional label is String\n"
      "    pet is Cat or Dog or Ns.Fish\n"
      "    crate is Crate with Red, Heavy\n"
      "    xs is Real[]: [1, 2]\n"
      "    u is A[] or B with T\n"
      "    front is Wheel:\n"
      "        r: 0.5\n"
      "        psi is Real: 2.2\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const auto& body = doc_.decls[0].body;
  ASSERT_EQ(body.size(), 8u);
  for (const fe::Member& m : body) EXPECT_EQ(m.kind, fe::MemberKind::Attribute);
  EXPECT_EQ(type(body[0].type), "Int");
  EXPECT_FALSE(body[0].value.has_value());
  EXPECT_FALSE(body[0].has_block);
  EXPECT_FALSE(body[0].is_optional);
  EXPECT_EQ(str(body[1].value), "2.5");
  EXPECT_TRUE(body[2].is_optional);
  EXPECT_EQ(fe::to_string(body[2].path), "label");
  EXPECT_FALSE(body[2].value.has_value());
  ASSERT_EQ(body[3].type.alternatives.size(), 3u);
  EXPECT_EQ(type(body[3].type), "Cat or Dog or Ns.Fish");
  ASSERT_EQ(body[4].type.traits.size(), 2u);
  EXPECT_EQ(type(body[4].type), "Crate with Red, Heavy");
  ASSERT_EQ(body[5].type.alternatives.size(), 1u);
  EXPECT_TRUE(body[5].type.alternatives[0].is_array);
  EXPECT_EQ(str(body[5].value), "[1, 2]");
  EXPECT_EQ(type(body[6].type), "A[] or B with T");
  EXPECT_TRUE(body[7].has_block);
  EXPECT_FALSE(body[7].value.has_value());
  ASSERT_EQ(body[7].block.size(), 2u);
  EXPECT_EQ(body[7].block[0].kind, fe::MemberKind::Assignment);
  EXPECT_EQ(str(body[7].block[0].value), "0.5");
  EXPECT_EQ(body[7].block[1].kind, fe::MemberKind::Attribute);
  EXPECT_EQ(fe::to_string(body[7].block[1].path), "psi");
}

TEST_F(ParserTest, AttributeWithTraitsAndBlock) {
  parse("Yard:\n    crate is Crate with Red, Heavy:\n        kg: 60.0\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const fe::Member& m = doc_.decls[0].body.at(0);
  EXPECT_EQ(type(m.type), "Crate with Red, Heavy");
  EXPECT_TRUE(m.has_block);
  ASSERT_EQ(m.block.size(), 1u);
  EXPECT_EQ(fe::to_string(m.block[0].path), "kg");
}

// 0.20's releases re-type nested attributes by path: `a.b is Int: 1` is the block `a:` / `b is Int: 1`.
TEST_F(ParserTest, DottedDeclarationIsANestedBlock) {
  parse("R:\n    a.b.c is Int: 1\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const fe::Member& a = doc_.decls[0].body.at(0);
  EXPECT_EQ(a.kind, fe::MemberKind::Assignment);
  EXPECT_EQ(fe::to_string(a.path), "a");
  ASSERT_TRUE(a.has_block);
  const fe::Member& b = a.block.at(0);
  EXPECT_EQ(fe::to_string(b.path), "b");
  const fe::Member& c = b.block.at(0);
  EXPECT_EQ(c.kind, fe::MemberKind::Attribute);
  EXPECT_EQ(fe::to_string(c.path), "c");
  EXPECT_TRUE(c.value.has_value());
}

TEST_F(ParserTest, ReferenceAttribute) {
  parse("R:\n    link is Physics3D.Interactions.MateConnector reference\n    reference is Int: 2\n");
  const auto& body = doc_.decls.at(0).body;
  ASSERT_EQ(body.size(), 2u);
  EXPECT_TRUE(body[0].is_reference);
  EXPECT_FALSE(body[1].is_reference);  // `reference` is a contextual word: still a name
}

TEST_F(ParserTest, OptionalNeedsIs) {
  parse("R:\n    optional a: 1\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 2, 15);
}

// ---- assignments

TEST_F(ParserTest, Assignments) {
  parse(
      "Top is Mid:\n"
      "    x: 3\n"
      "    mid.inner.v: 5.0\n"
      "    y : 4\n"
      "    inner:\n"
      "        v: 1.0\n"
      "        position.z: 0.5\n"
      "    kinematics.local_transform.position.x: -0.3\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const auto& body = doc_.decls[0].body;
  ASSERT_EQ(body.size(), 5u);
  for (const fe::Member& m : body) EXPECT_EQ(m.kind, fe::MemberKind::Assignment);
  EXPECT_EQ(fe::to_string(body[0].path), "x");
  EXPECT_EQ(str(body[0].value), "3");
  EXPECT_EQ(body[1].path.parts.size(), 3u);
  EXPECT_EQ(fe::to_string(body[1].path), "mid.inner.v");
  EXPECT_EQ(str(body[1].value), "5.0");
  EXPECT_EQ(fe::to_string(body[2].path), "y");  // space before the colon
  EXPECT_EQ(str(body[2].value), "4");
  EXPECT_TRUE(body[3].has_block);
  EXPECT_FALSE(body[3].value.has_value());
  ASSERT_EQ(body[3].block.size(), 2u);
  EXPECT_EQ(fe::to_string(body[3].block[1].path), "position.z");
  EXPECT_EQ(body[4].path.parts.size(), 4u);
  EXPECT_EQ(str(body[4].value), "(-0.3)");
}

TEST_F(ParserTest, AssignmentPathWithBacktickPart) {
  parse("R is Base:\n    `a.b`.k: 3\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  ASSERT_EQ(doc_.decls[0].body.size(), 1u);
  const fe::Member& m = doc_.decls[0].body[0];
  EXPECT_EQ(m.kind, fe::MemberKind::Assignment);
  ASSERT_EQ(m.path.parts.size(), 2u);
  EXPECT_EQ(m.path.parts[0].text, "a.b");
  EXPECT_TRUE(m.path.parts[0].quoted);
  EXPECT_EQ(fe::to_string(m.path), "`a.b`.k");
}

TEST_F(ParserTest, AssignmentBlockHoldsEveryNestedMemberKind) {
  parse(
      "Root is Base:\n"
      "    leaf:\n"
      "        .hidden: true\n"
      "        with Tagged\n"
      "        k: 1\n"
      "        shape becomes Box\n"
      "        extra is Real: 2.0\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const fe::Member& m = doc_.decls[0].body.at(0);
  ASSERT_EQ(m.block.size(), 5u);
  EXPECT_EQ(m.block[0].kind, fe::MemberKind::Annotation);
  EXPECT_EQ(m.block[1].kind, fe::MemberKind::TraitUse);
  EXPECT_EQ(m.block[2].kind, fe::MemberKind::Assignment);
  EXPECT_EQ(m.block[3].kind, fe::MemberKind::Becomes);
  EXPECT_EQ(m.block[4].kind, fe::MemberKind::Attribute);
}

TEST_F(ParserTest, AssignmentColonWithoutBlockOrValue) {
  parse("R:\n    a:\n    b: 1\n");
  EXPECT_EQ(expect_diag(fe::DiagCode::ExpectedIndentedBlock, 2, 6), "Expected indented block");
}

TEST_F(ParserTest, BareNameIsExpectedIs) {
  parse("Thing:\n    speed 3\n");
  EXPECT_EQ(expect_diag(fe::DiagCode::ExpectedIs, 2, 11), "Expected an is keyword");
}

// ---- becomes

TEST_F(ParserTest, BecomesForms) {
  parse(
      "Special is Holder:\n"
      "    s becomes Square\n"
      "    t becomes Square: Square.make()\n"
      "    tracks.link_description becomes Physics3D.Geometries.Box:\n"
      "        size: {1, 1, 1}\n"
      "    u becomes A with T\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const auto& body = doc_.decls[0].body;
  ASSERT_EQ(body.size(), 4u);
  for (const fe::Member& m : body) EXPECT_EQ(m.kind, fe::MemberKind::Becomes);
  EXPECT_EQ(fe::to_string(body[0].path), "s");
  EXPECT_EQ(type(body[0].type), "Square");
  EXPECT_FALSE(body[0].value.has_value());
  EXPECT_FALSE(body[0].has_block);
  EXPECT_EQ(str(body[1].value), "Square.make()");
  EXPECT_EQ(fe::to_string(body[2].path), "tracks.link_description");
  EXPECT_EQ(type(body[2].type), "Physics3D.Geometries.Box");
  EXPECT_TRUE(body[2].has_block);
  ASSERT_EQ(body[2].block.size(), 1u);
  EXPECT_EQ(str(body[2].block[0].value), "{1, 1, 1}");
  EXPECT_EQ(type(body[3].type), "A with T");
}

// ---- annotations

TEST_F(ParserTest, AnnotationValues) {
  parse(
      "R:\n"
      "    .doc: \"text\"\n"
      "    .long: \"\"\"a\n"
      "b\"\"\"\n"
      "    .offset: -2.5\n"
      "    .prio: -3\n"
      "    .n: 7\n"
      "    .hidden: true\n"
      "    .shown: false\n"
      "    .agx_enable_full_dof: true\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const auto& body = doc_.decls[0].body;
  ASSERT_EQ(body.size(), 8u);
  for (const fe::Member& m : body) {
    EXPECT_EQ(m.kind, fe::MemberKind::Annotation);
    EXPECT_EQ(m.path.parts.size(), 1u);
  }
  EXPECT_EQ(fe::to_string(body[0].path), "doc");
  EXPECT_EQ(ex(*body[0].value).kind, fe::ExprKind::String);
  EXPECT_EQ(ex(*body[0].value).string_value, "text");
  EXPECT_FALSE(ex(*body[0].value).multiline);
  EXPECT_TRUE(ex(*body[1].value).multiline);
  EXPECT_EQ(ex(*body[1].value).string_value, "a\nb");
  EXPECT_EQ(str(body[2].value), "(-2.5)");
  EXPECT_EQ(str(body[3].value), "(-3)");
  EXPECT_EQ(ex(*body[4].value).int_value, 7);
  EXPECT_EQ(ex(*body[5].value).kind, fe::ExprKind::Bool);
  EXPECT_TRUE(ex(*body[5].value).bool_value);
  EXPECT_FALSE(ex(*body[6].value).bool_value);
  EXPECT_EQ(fe::to_string(body[7].path), "agx_enable_full_dof");
}

TEST_F(ParserTest, AnnotationNameMayBeABacktickIdentifier) {
  // §2.5 (proposed): backtick identifiers are allowed anywhere a plain identifier is.
  parse("R:\n    .`unit.si`: \"m\"\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  ASSERT_EQ(doc_.decls[0].body.size(), 1u);
  const fe::Member& m = doc_.decls[0].body[0];
  EXPECT_EQ(m.kind, fe::MemberKind::Annotation);
  ASSERT_EQ(m.path.parts.size(), 1u);
  EXPECT_EQ(m.path.parts[0].text, "unit.si");
  EXPECT_TRUE(m.path.parts[0].quoted);
}

TEST_F(ParserTest, AnnotationValueMustBeConstant) {
  parse("R:\n    .a: leaf\n    .b: 1 + 2\n    .c: -\"s\"\n    .d: [1]\n    .ok: 1\n");
  expect_diag(fe::DiagCode::AnnotationNotConstant, 2, 9);
  expect_diag(fe::DiagCode::AnnotationNotConstant, 3, 9);
  expect_diag(fe::DiagCode::AnnotationNotConstant, 4, 9);
  expect_diag(fe::DiagCode::AnnotationNotConstant, 5, 9);
  ASSERT_EQ(doc_.decls.size(), 1u);
  ASSERT_EQ(doc_.decls[0].body.size(), 1u);
  EXPECT_EQ(fe::to_string(doc_.decls[0].body[0].path), "ok");
}

// ---- methods and operators

TEST_F(ParserTest, Methods) {
  parse(
      "Vec3:\n"
      "    fn length() -> Real\n"
      "    fn on_init()\n"
      "    static fn from_xyz(x: Real, y: Real, z: Real) -> Vec3\n"
      "    fn rotate(q : Quat, v: Math.Vec3) -> Math.Vec3\n"
      "    static fn mean(values: Real[]) -> Real\n"
      "    fn all() -> Vec3[]\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const auto& body = doc_.decls[0].body;
  ASSERT_EQ(body.size(), 6u);
  for (const fe::Member& m : body) EXPECT_EQ(m.kind, fe::MemberKind::Method);
  EXPECT_EQ(fe::to_string(body[0].path), "length");
  EXPECT_FALSE(body[0].is_static);
  EXPECT_TRUE(body[0].params.empty());
  ASSERT_TRUE(body[0].return_type.has_value());
  EXPECT_EQ(type_ref(*body[0].return_type), "Real");
  EXPECT_FALSE(body[1].return_type.has_value());
  EXPECT_TRUE(body[2].is_static);
  EXPECT_EQ(params(body[2].params), "x: Real, y: Real, z: Real");
  EXPECT_EQ(type_ref(*body[2].return_type), "Vec3");
  EXPECT_EQ(params(body[3].params), "q: Quat, v: Math.Vec3");
  EXPECT_EQ(params(body[4].params), "values: Real[]");
  EXPECT_EQ(type_ref(*body[5].return_type), "Vec3[]");
}

TEST_F(ParserTest, MethodsAreNotAllowedInNestedBlocks) {
  parse("R:\n    a is A:\n        fn f() -> Real\n        x: 1\n");
  expect_diag(fe::DiagCode::MisplacedDeclaration, 3, 9);
  ASSERT_EQ(doc_.decls.size(), 1u);
  ASSERT_EQ(doc_.decls[0].body.at(0).block.size(), 1u);  // parsing goes on with the next line
}

TEST_F(ParserTest, BinaryOperatorDeclaration) {
  parse("operator +(lhs: A, rhs: B) -> C\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const fe::Decl& d = doc_.decls[0];
  EXPECT_EQ(d.kind, fe::DeclKind::Operator);
  EXPECT_EQ(d.op, '+');
  EXPECT_EQ(params(d.params), "lhs: A, rhs: B");
  ASSERT_TRUE(d.return_type.has_value());
  EXPECT_EQ(type_ref(*d.return_type), "C");
}

TEST_F(ParserTest, UnaryOperatorDeclaration) {
  parse("operator -(operand: V) -> V\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  EXPECT_EQ(doc_.decls[0].kind, fe::DeclKind::Operator);
  EXPECT_EQ(doc_.decls[0].op, '-');
  EXPECT_EQ(params(doc_.decls[0].params), "operand: V");
  EXPECT_EQ(type_ref(*doc_.decls[0].return_type), "V");
}

TEST_F(ParserTest, AllOperatorSymbols) {
  parse(
      "operator *(lhs: Real, rhs: Math.Vec3) -> Math.Vec3\n"
      "operator /(lhs: Math.Vec3, rhs: Real) -> Math.Vec3\n"
      "operator -(lhs: V, rhs: V) -> V\n");
  ASSERT_EQ(doc_.decls.size(), 3u);
  EXPECT_EQ(doc_.decls[0].op, '*');
  EXPECT_EQ(doc_.decls[1].op, '/');
  EXPECT_EQ(doc_.decls[2].op, '-');
  EXPECT_EQ(params(doc_.decls[0].params), "lhs: Real, rhs: Math.Vec3");
}

TEST_F(ParserTest, MemberOnlyFormsAtTopLevelAreMisplaced) {
  parse("fn f() -> Real\nRoot\n");
  expect_diag(fe::DiagCode::MisplacedDeclaration, 1, 1);
  ASSERT_EQ(doc_.decls.size(), 1u);
  EXPECT_EQ(doc_.decls[0].name.text, "Root");
}

TEST_F(ParserTest, TopLevelOnlyFormsInABodyAreMisplaced) {
  parse("R:\n    operator +(a: A, b: A) -> A\n    x: 1\n");
  expect_diag(fe::DiagCode::MisplacedDeclaration, 2, 5);
  ASSERT_EQ(doc_.decls.size(), 1u);
  EXPECT_EQ(doc_.decls[0].body.size(), 1u);
}

// ---- expressions

TEST_F(ParserTest, MultiplicationBindsTighterThanAddition) {
  EXPECT_EQ(value("2 + 3 * 4"), "(2 + (3 * 4))");
}

TEST_F(ParserTest, SubtractionIsLeftAssociative) {
  EXPECT_EQ(value("10 - 4 - 3"), "((10 - 4) - 3)");
}

TEST_F(ParserTest, DivisionIsLeftAssociative) {
  EXPECT_EQ(value("8 / 2 / 2"), "((8 / 2) / 2)");
}

TEST_F(ParserTest, UnaryMinusBindsTighterThanMultiplication) {
  EXPECT_EQ(value("-2 * 3"), "((-2) * 3)");
  const fe::Expr& e = ex(value_id());
  ASSERT_EQ(e.kind, fe::ExprKind::Binary);
  EXPECT_EQ(e.op, '*');
  EXPECT_EQ(ex(e.operands[0]).kind, fe::ExprKind::Unary);
  EXPECT_EQ(ex(e.operands[0]).op, '-');
}

TEST_F(ParserTest, UnaryMinusNegatesTheWholeCall) {
  EXPECT_EQ(value("-Math.Vec3.Z_AXIS()"), "(-Math.Vec3.Z_AXIS())");
  const fe::Expr& e = ex(value_id());
  ASSERT_EQ(e.kind, fe::ExprKind::Unary);
  EXPECT_EQ(ex(e.operands[0]).kind, fe::ExprKind::Call);
}

TEST_F(ParserTest, ParenthesesGroup) {
  EXPECT_EQ(value("(2+3)*4"), "((2 + 3) * 4)");
  EXPECT_EQ(value("2 * (3 - (4 - 5))"), "(2 * (3 - (4 - 5)))");
}

TEST_F(ParserTest, MixedPrecedence) {
  EXPECT_EQ(value("a * b + c / d - e"), "(((a * b) + (c / d)) - e)");
  EXPECT_EQ(value("a - -b"), "(a - (-b))");
  EXPECT_EQ(value("--a"), "(-(-a))");
  EXPECT_EQ(value("-a.b * -c"), "((-a.b) * (-c))");
}

TEST_F(ParserTest, Calls) {
  EXPECT_EQ(value("f()"), "f()");
  {
    const fe::Expr& e = ex(value_id());
    ASSERT_EQ(e.kind, fe::ExprKind::Call);
    ASSERT_EQ(e.operands.size(), 1u);
    EXPECT_EQ(ex(e.operands[0]).kind, fe::ExprKind::Name);
    EXPECT_EQ(ex(e.operands[0]).text, "f");
  }
  EXPECT_EQ(value("f(1)"), "f(1)");
  EXPECT_EQ(ex(value_id()).operands.size(), 2u);
  EXPECT_EQ(value("f(1, a + 2, g(3), [4])"), "f(1, (a + 2), g(3), [4])");
  EXPECT_EQ(ex(value_id()).operands.size(), 5u);
  EXPECT_EQ(value("Math.Functions.sqrt(16)"), "Math.Functions.sqrt(16)");
}

TEST_F(ParserTest, ChainedMemberCalls) {
  EXPECT_EQ(value("Math.Vec3.from_xyz(3, 4, 0).length()"), "Math.Vec3.from_xyz(3, 4, 0).length()");
  const fe::Expr& outer = ex(value_id());
  ASSERT_EQ(outer.kind, fe::ExprKind::Call);
  ASSERT_EQ(outer.operands.size(), 1u);
  const fe::Expr& length = ex(outer.operands[0]);
  ASSERT_EQ(length.kind, fe::ExprKind::Member);
  EXPECT_EQ(length.text, "length");
  const fe::Expr& inner = ex(length.operands[0]);
  ASSERT_EQ(inner.kind, fe::ExprKind::Call);
  ASSERT_EQ(inner.operands.size(), 4u);
  const fe::Expr& callee = ex(inner.operands[0]);
  ASSERT_EQ(callee.kind, fe::ExprKind::Member);
  EXPECT_EQ(callee.text, "from_xyz");
  EXPECT_EQ(ex(callee.operands[0]).kind, fe::ExprKind::Member);
  EXPECT_EQ(ex(callee.operands[0]).text, "Vec3");
  EXPECT_EQ(ex(ex(callee.operands[0]).operands[0]).text, "Math");
}

TEST_F(ParserTest, MemberAccessOnCallResult) {
  EXPECT_EQ(value("q.rotate(Math.Vec3.X_AXIS()).x"), "q.rotate(Math.Vec3.X_AXIS()).x");
  EXPECT_EQ(ex(value_id()).kind, fe::ExprKind::Member);
}

TEST_F(ParserTest, PostfixOnParenthesisedExpression) {
  EXPECT_EQ(value("(a + b).length() * 2"), "((a + b).length() * 2)");
  const fe::Expr& call = ex(ex(value_id()).operands[0]);
  ASSERT_EQ(call.kind, fe::ExprKind::Call);
  const fe::Expr& member = ex(call.operands[0]);
  ASSERT_EQ(member.kind, fe::ExprKind::Member);
  EXPECT_EQ(ex(member.operands[0]).kind, fe::ExprKind::Binary);
}

TEST_F(ParserTest, CallOnACallIsRejected) {
  // §3: arguments follow a name or a member only.
  parse("x is Real: f()(1)\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 1, 15);
}

TEST_F(ParserTest, ArrayLiterals) {
  EXPECT_EQ(value("[]"), "[]");
  EXPECT_EQ(ex(value_id()).kind, fe::ExprKind::Array);
  EXPECT_TRUE(ex(value_id()).operands.empty());
  EXPECT_EQ(value("[1, 2.5, -3]"), "[1, 2.5, (-3)]");
  EXPECT_EQ(value("[[1, 2], [], [[3]]]"), "[[1, 2], [], [[3]]]");
  EXPECT_EQ(value("[a, box.connector]"), "[a, box.connector]");
}

TEST_F(ParserTest, ArrayLiteralSpanningLines) {
  parse("R:\n    zs is Int[]: [1,\n        2,\n            3]\n    y is Int: 4\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  ASSERT_EQ(doc_.decls[0].body.size(), 2u);
  EXPECT_EQ(str(doc_.decls[0].body[0].value), "[1, 2, 3]");
  EXPECT_EQ(str(doc_.decls[0].body[1].value), "4");
}

TEST_F(ParserTest, Initializers) {
  EXPECT_EQ(value("{1, 1, 1}"), "{1, 1, 1}");
  EXPECT_EQ(ex(value_id()).kind, fe::ExprKind::Initializer);
  EXPECT_EQ(value("{-1.0, 2.0}"), "{(-1.0), 2.0}");
  EXPECT_EQ(value("{a.x, a.y, a.z} / 2"), "({a.x, a.y, a.z} / 2)");
  EXPECT_EQ(value("{2, 4, 6} / 2 + {1}"), "(({2, 4, 6} / 2) + {1})");
}

TEST_F(ParserTest, EmptyInitializer) {
  EXPECT_EQ(value("{}"), "{}");
  EXPECT_EQ(ex(value_id()).kind, fe::ExprKind::Initializer);
}

TEST_F(ParserTest, ThisAndThisMember) {
  EXPECT_EQ(value("this"), "this");
  EXPECT_EQ(ex(value_id()).kind, fe::ExprKind::This);
  EXPECT_EQ(value("this.x + 1"), "(this.x + 1)");
  const fe::Expr& member = ex(ex(value_id()).operands[0]);
  ASSERT_EQ(member.kind, fe::ExprKind::Member);
  EXPECT_EQ(member.text, "x");
  EXPECT_EQ(ex(member.operands[0]).kind, fe::ExprKind::This);
}

TEST_F(ParserTest, Literals) {
  value("true");
  EXPECT_EQ(ex(value_id()).kind, fe::ExprKind::Bool);
  EXPECT_TRUE(ex(value_id()).bool_value);
  value("false");
  EXPECT_EQ(ex(value_id()).kind, fe::ExprKind::Bool);
  EXPECT_FALSE(ex(value_id()).bool_value);
  value("\"a\\tb\"");
  EXPECT_EQ(ex(value_id()).kind, fe::ExprKind::String);
  EXPECT_EQ(ex(value_id()).string_value, "a\tb");
  value("@\"mesh/part.obj\"");
  EXPECT_EQ(ex(value_id()).kind, fe::ExprKind::PathString);
  EXPECT_EQ(ex(value_id()).string_value, "mesh/part.obj");
  value("42");
  EXPECT_EQ(ex(value_id()).kind, fe::ExprKind::Int);
  EXPECT_EQ(ex(value_id()).int_value, 42);
  value("1E5");
  EXPECT_EQ(ex(value_id()).kind, fe::ExprKind::Real);
  EXPECT_DOUBLE_EQ(ex(value_id()).real_value, 1e5);
  value("2.5e-3");
  EXPECT_DOUBLE_EQ(ex(value_id()).real_value, 2.5e-3);
}

TEST_F(ParserTest, LongLiterals) {
  value("3.14159265358979323846264338327950288419716939937510");
  EXPECT_EQ(ex(value_id()).kind, fe::ExprKind::Real);
  EXPECT_DOUBLE_EQ(ex(value_id()).real_value, 3.141592653589793);
  value("12345678901234567890123456789012345678901234567890");
  EXPECT_EQ(ex(value_id()).kind, fe::ExprKind::Int);
  EXPECT_FALSE(ex(value_id()).int_value.has_value());  // does not fit in 64 bits
  EXPECT_NEAR(ex(value_id()).real_value, 1.2345678901234568e49, 1e35);
  value("9223372036854775807");
  EXPECT_EQ(ex(value_id()).int_value, INT64_MAX);
}

TEST_F(ParserTest, QuotedNamesInExpressions) {
  EXPECT_EQ(value("`a.b`.k + 1"), "(`a.b`.k + 1)");
  const fe::Expr& member = ex(ex(value_id()).operands[0]);
  ASSERT_EQ(member.kind, fe::ExprKind::Member);
  const fe::Expr& name = ex(member.operands[0]);
  EXPECT_EQ(name.kind, fe::ExprKind::Name);
  EXPECT_EQ(name.text, "a.b");
  EXPECT_TRUE(name.quoted);
}

TEST_F(ParserTest, Indexing) {
  // As the 0.20 releases write it: `links[0].end`, written directly after its operand.
  EXPECT_EQ(value("links[0].end"), "links[0].end");
  EXPECT_EQ(value("xs[i + 1] * 2"), "(xs[(i + 1)] * 2)");
  parse("x is Real: xs [0]\n");  // with a space it is no index
  expect_diag(fe::DiagCode::UnexpectedToken, 1, 15);
}

TEST_F(ParserTest, TrailingCommaIsRejected) {
  // Proposed (§3 notes): no trailing commas.
  parse("x is Real: [1, 2,]\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 1, 18);
}

TEST_F(ParserTest, MissingOperandIsReported) {
  parse("x is Real: 1 +\nR\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 1, 15);
  ASSERT_NE(doc_.find_model("R"), nullptr);  // the next line still parses
}

// ---- source ranges

TEST_F(ParserTest, SourceRangesOfDeclMemberExprAndIdent) {
  parse("Root:\n    a is Real: 2 + 3 * 4\n    b is Leaf:\n        k: 1\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  const fe::Decl& d = doc_.decls[0];
  EXPECT_EQ(range(d.range), "1:1-4:13");
  EXPECT_EQ(range(d.name.range), "1:1-1:5");
  ASSERT_EQ(d.body.size(), 2u);
  const fe::Member& a = d.body[0];
  EXPECT_EQ(range(a.range), "2:5-2:25");
  EXPECT_EQ(range(a.path.range), "2:5-2:6");
  EXPECT_EQ(range(a.path.parts[0].range), "2:5-2:6");
  EXPECT_EQ(range(a.type.range), "2:10-2:14");
  const fe::Expr& sum = ex(*a.value);
  EXPECT_EQ(range(sum.range), "2:16-2:25");
  EXPECT_EQ(range(ex(sum.operands[0]).range), "2:16-2:17");
  EXPECT_EQ(range(ex(sum.operands[1]).range), "2:20-2:25");
  const fe::Member& b = d.body[1];
  EXPECT_EQ(range(b.range), "3:5-4:13");
  ASSERT_EQ(b.block.size(), 1u);
  EXPECT_EQ(range(b.block[0].range), "4:9-4:13");
}

TEST_F(ParserTest, SourceRangesOfCallsUnaryAndParens) {
  parse("x is Real: Math.Vec3.from_xyz(3, 4, 0).length()\ny is Real: -(a + b)\n");
  ASSERT_EQ(doc_.decls.size(), 2u);
  EXPECT_EQ(range(doc_.decls[0].range), "1:1-1:48");
  const fe::Expr& call = ex(*doc_.decls[0].value);
  EXPECT_EQ(range(call.range), "1:12-1:48");
  const fe::Expr& member = ex(call.operands[0]);
  EXPECT_EQ(range(member.range), "1:12-1:46");
  const fe::Expr& neg = ex(*doc_.decls[1].value);
  EXPECT_EQ(range(neg.range), "2:12-2:20");
  // Decision: a parenthesised expression's range covers its parentheses (the text as written).
  EXPECT_EQ(range(ex(neg.operands[0]).range), "2:13-2:20");
}

TEST_F(ParserTest, SourceRangeOfBinaryCoversParenthesisedOperands) {
  parse("x is Real: (a + b) * (c)\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  EXPECT_EQ(range(ex(*doc_.decls[0].value).range), "1:12-1:25");
}

TEST_F(ParserTest, SourceRangesOfOtherDecls) {
  parse(
      "import @\"a.urdf\" as Ns.A\n"
      "trait T:\n"
      "    .doc: \"d\"\n"
      "    fn f(p: Real) -> Real\n"
      "operator +(l: A, r: A) -> A\n"
      "xs is Int[]: [1,\n"
      "    2]\n");
  ASSERT_EQ(doc_.decls.size(), 4u);
  EXPECT_EQ(range(doc_.decls[0].range), "1:1-1:25");
  EXPECT_EQ(range(doc_.decls[0].alias->range), "1:21-1:25");
  EXPECT_EQ(range(doc_.decls[1].range), "2:1-4:26");
  ASSERT_EQ(doc_.decls[1].body.size(), 2u);
  EXPECT_EQ(range(doc_.decls[1].body[0].range), "3:5-3:14");
  EXPECT_EQ(range(doc_.decls[1].body[1].range), "4:5-4:26");
  EXPECT_EQ(range(doc_.decls[1].body[1].params[0].range), "4:10-4:17");
  EXPECT_EQ(range(doc_.decls[2].range), "5:1-5:28");
  EXPECT_EQ(range(doc_.decls[3].range), "6:1-7:7");
  EXPECT_EQ(range(ex(*doc_.decls[3].value).range), "6:14-7:7");
}

TEST_F(ParserTest, SourceRangeOfQuotedIdentIncludesBackticks) {
  parse("Root:\n    `a.b` is Leaf\n");
  ASSERT_EQ(doc_.decls.size(), 1u);
  ASSERT_EQ(doc_.decls[0].body.size(), 1u);
  ASSERT_EQ(doc_.decls[0].body[0].path.parts.size(), 1u);
  const fe::Ident& name = doc_.decls[0].body[0].path.parts[0];
  EXPECT_EQ(name.text, "a.b");
  EXPECT_TRUE(name.quoted);
  EXPECT_EQ(range(name.range), "2:5-2:10");
}

// ---- Document helpers

TEST_F(ParserTest, LastModelSkipsTraitsGlobalsImportsAndOperators) {
  parse(
      "import @\"x.urdf\"\n"
      "A:\n"
      "    a is Int: 1\n"
      "B:\n"
      "    b is Int: 2\n"
      "trait T:\n"
      "    t is Int: 0\n"
      "g is Real: 1.0\n"
      "operator +(l: B, r: B) -> B\n");
  ASSERT_EQ(doc_.decls.size(), 6u);
  const fe::Decl* last = doc_.last_model();
  ASSERT_NE(last, nullptr);
  EXPECT_EQ(last->name.text, "B");
  const fe::Decl* a = doc_.find_model("A");
  ASSERT_NE(a, nullptr);
  ASSERT_EQ(a->body.size(), 1u);
  EXPECT_EQ(fe::to_string(a->body[0].path), "a");
  EXPECT_EQ(doc_.find_model("T"), nullptr);  // a trait is not a model
  EXPECT_EQ(doc_.find_model("g"), nullptr);  // nor is a global
  EXPECT_EQ(doc_.find_model("Z"), nullptr);
}

TEST_F(ParserTest, LastModelIsNullWithoutModels) {
  parse("trait Solo:\n    a is Int: 1\nk is Int: 3\n");
  ASSERT_EQ(doc_.decls.size(), 2u);
  EXPECT_EQ(doc_.last_model(), nullptr);
  EXPECT_EQ(doc_.find_model("Solo"), nullptr);
}

TEST_F(ParserTest, LastModelCountsEmptyAndConstModels) {
  parse("A:\n    a is Int: 1\nconst C:\n    c is Int: 1\n");
  ASSERT_NE(doc_.last_model(), nullptr);
  EXPECT_EQ(doc_.last_model()->name.text, "C");
  parse("A:\n    a is Int: 1\nE is A\n");
  ASSERT_NE(doc_.last_model(), nullptr);
  EXPECT_EQ(doc_.last_model()->name.text, "E");
}

// ---- layout at the parser level

TEST_F(ParserTest, TopLevelIndentationIsAnError) {
  parse("  Root:\n    a is Int: 1\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 1, 3);
}

TEST_F(ParserTest, DeeperLineWithoutOpenerStaysInItsBlock) {
  // Proposed (§2.3 leniency, World.openplx): a deeper line after a member that opens no block joins the
  // current block, with a warning.
  parse("World:\n    .doc: \"w\"\n        a: 1\n        b: 2\n    c: 3\n");
  expect_diag(fe::DiagCode::UnexpectedIndent, 3, 9);
  ASSERT_EQ(doc_.decls.size(), 1u);
  const auto& body = doc_.decls[0].body;
  ASSERT_EQ(body.size(), 4u);
  EXPECT_EQ(fe::to_string(body[1].path), "a");
  EXPECT_EQ(fe::to_string(body[3].path), "c");
}

TEST_F(ParserTest, ErrorRecoveryReportsEveryBrokenLine) {
  parse("R:\n    a is : 1\n    b is Int: 2\n    c d\n    e is Int: 3\n");
  expect_diag(fe::DiagCode::UnexpectedToken, 2, 10);
  expect_diag(fe::DiagCode::ExpectedIs, 4, 7);
  ASSERT_EQ(doc_.decls.size(), 1u);
  ASSERT_EQ(doc_.decls[0].body.size(), 2u);
  EXPECT_EQ(fe::to_string(doc_.decls[0].body[0].path), "b");
  EXPECT_EQ(fe::to_string(doc_.decls[0].body[1].path), "e");
}

TEST_F(ParserTest, DumpShowsTheTreeWithRanges) {
  parse("Root:\n    a is Real: 2 + 3 * 4\n");
  std::ostringstream out;
  fe::dump_ast(out, sources_.file(file_), doc_);
  EXPECT_EQ(out.str(), "model Root @1:1-2:25\n  attr a is Real = (2 + (3 * 4)) @2:5-2:25\n");
}

}  // namespace
