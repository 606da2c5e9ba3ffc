// Evaluation behaviour beyond the Appendix B checklist: bundle search path, imports, explicit-vs-default
// bookkeeping, owned values with part assignments, and the values dump.
#include <cstdlib>

#include "tests/support/eval_fixture.h"

namespace {

namespace fe = openplx::frontend;

class Semantics : public openplx::testing::EvalTest {};

TEST_F(Semantics, ExplicitAssignmentsAreRecordedPerAttribute) {
  ASSERT_TRUE(
      load("Frame:\n"
           "    position is Math.Vec3\n"
           "    rotation is Math.Quat\n"
           "Body:\n"
           "    frame is Frame\n"
           "    other is Frame\n"
           "    mass is Real: 1.0\n"
           "Scene:\n"
           "    a is Body:\n"
           "        frame.position.z: 0.5\n"
           "    b is Body:\n"
           "        mass: 2.0\n"))
      << all_diags();
  EXPECT_TRUE(slot("a.frame")->explicit_value);  // a part of it was assigned
  EXPECT_TRUE(slot("a.frame.position")->explicit_value);
  EXPECT_FALSE(slot("a.frame.rotation")->explicit_value);
  EXPECT_FALSE(slot("a.other")->explicit_value);
  EXPECT_FALSE(slot("a.mass")->explicit_value);  // the declaration's default
  EXPECT_TRUE(slot("b.mass")->explicit_value);
  EXPECT_FALSE(slot("b.frame")->explicit_value);
}

TEST_F(Semantics, PartOfAnOwnedValueCanBeAssignedFromNearerTheRoot) {
  ASSERT_TRUE(
      load("Body:\n"
           "    position is Math.Vec3: {1, 2, 3}\n"
           "    axis is Math.Vec3: Math.Vec3.Z_AXIS()\n"
           "Scene:\n"
           "    body is Body:\n"
           "        position.z: 9\n"
           "        axis.x: 5\n"))
      << all_diags();
  EXPECT_EQ(value("body.position"), "{1.0, 2.0, 9.0}");
  EXPECT_EQ(value("body.axis"), "{5.0, 0.0, 1.0}");
}

TEST_F(Semantics, WholeValueFromTheOwnerBeatsPartDefaultsInTheType) {
  ASSERT_TRUE(
      load("Body:\n"
           "    position is Math.Vec3:\n"
           "        z: 4\n"
           "Scene:\n"
           "    body is Body:\n"
           "        position: {1, 1, 1}\n"))
      << all_diags();
  EXPECT_EQ(value("body.position"), "{1.0, 1.0, 1.0}");
}

TEST_F(Semantics, ExtraBundleFoldersFromFlagAndEnvironment) {
  write("flag/Tools/config.openplx", "config is BundleConfig:\n    name: \"Tools\"\n");
  write("flag/Tools/Hammer.openplx", "Hammer:\n    kg is Real: 1.5\n");
  write("env/Parts/config.openplx", "config is BundleConfig:\n    name: \"Parts\"\n");
  write("env/Parts/Sub/Bolt.openplx", "Bolt:\n    d is Real: 0.01\n");
  setenv("OPENPLX_BUNDLE_PATH", (dir() + "/env/Parts").c_str(), 1);
  const std::string main = write("main.openplx", "Kit:\n    h is Tools.Hammer\n    b is Parts.Sub.Bolt\n");
  const bool ok = load_file(main, nullptr, {dir() + "/flag"});  // a folder of bundles
  unsetenv("OPENPLX_BUNDLE_PATH");
  ASSERT_TRUE(ok) << all_diags();
  EXPECT_EQ(value("h.kg"), "1.5");
  EXPECT_EQ(value("b.d"), "0.01");
}

TEST_F(Semantics, FirstBundleOfANameWins) {
  write("one/Dup/config.openplx", "config is BundleConfig:\n    name: \"Dup\"\n");
  write("one/Dup/A.openplx", "A:\n    v is Int: 1\n");
  write("two/Dup/config.openplx", "config is BundleConfig:\n    name: \"Dup\"\n");
  write("two/Dup/A.openplx", "A:\n    v is Int: 2\n");
  const std::string main = write("main.openplx", "M:\n    a is Dup.A\n");
  ASSERT_TRUE(load_file(main, nullptr, {dir() + "/one", dir() + "/two"})) << all_diags();
  EXPECT_EQ(value("a.v"), "1");
}

TEST_F(Semantics, ImportOfOpenplxFileWithAndWithoutAlias) {
  write("parts.openplx", "Wheel:\n    r is Real: 0.3\n");
  write("lib/more.openplx", "Axle:\n    l is Real: 1.2\n");
  ASSERT_TRUE(
      load("import @\"parts.openplx\"\n"
           "import @\"lib/more.openplx\" as More\n"
           "Car:\n"
           "    w is Wheel\n"
           "    a is More.Axle\n"))
      << all_diags();
  EXPECT_EQ(value("w.r"), "0.3");
  EXPECT_EQ(value("a.l"), "1.2");
}

TEST_F(Semantics, MeshImportBecomesAModelWithItsPath) {
  write("Icosahedron.obj", "v 0 0 0\n");
  ASSERT_TRUE(load("import @\"Icosahedron.obj\" as Mesh\nScene:\n    mesh is Mesh\n")) << all_diags();
  EXPECT_EQ(value("mesh.path"), "\"" + dir() + "/Icosahedron.obj\"");
}

TEST_F(Semantics, AgxImportIsAnErrorAtItsLine) {
  write("pendulum.agx", "binary");
  EXPECT_FALSE(load("# scene\nimport @\"pendulum.agx\"\nScene:\n    x is Real: 1\n"));
  EXPECT_NE(expect_diag(fe::DiagCode::UnsupportedImport, 2, 1).find(".agx"), std::string::npos);
}

TEST_F(Semantics, UnusedDeclarationsOfTheFileAreChecked) {
  EXPECT_FALSE(load("A is B:\n    x is Int: 1\nB is A:\n    y is Int: 2\nRoot:\n    z is Int: 3\n"));
  expect_diag_containing(fe::DiagCode::CyclicInheritance, "Cyclic inheritance involving");
}

TEST_F(Semantics, DidYouMeanForMembersAndNames) {
  EXPECT_FALSE(load("Root:\n    speed is Real: 1\n    v is Real: sped * 2\n"));
  EXPECT_EQ(expect_diag(fe::DiagCode::UnknownName, 3, 16), "Unknown name sped; did you mean `speed`?");
}

TEST_F(Semantics, ValuesDumpIsInDeclarationOrder) {
  ASSERT_TRUE(
      load("Base:\n"
           "    b is Int: 1\n"
           "Leaf is Base:\n"
           "    c is String: \"x\\ny\"\n"
           "Root:\n"
           "    z is Bool: true\n"
           "    leaf is Leaf\n"
           "    q is Math.Quat\n"
           "    xs is Real[]: [1, 2.5]\n"
           "    ref is Leaf: leaf\n"))
      << all_diags();
  EXPECT_EQ(values(),
            "z = true\n"
            "leaf = Leaf\n"
            "leaf.b = 1\n"
            "leaf.c = \"x\\ny\"\n"
            "q = {0.0, 0.0, 0.0, 1.0}\n"
            "xs = [1.0, 2.5]\n"
            "ref = -> leaf\n");
}

TEST_F(Semantics, RecursiveOwnershipIsAnErrorNotACrash) {
  EXPECT_FALSE(load("Node:\n    child is Node\n"));
  expect_diag_containing(fe::DiagCode::EvaluationTooDeep, "Node contains itself");
}

TEST_F(Semantics, LongDependencyChainIsAnErrorNotACrash) {
  // a0 needs a1, which needs a2, ...: evaluating a0 first would recurse 5,000 deep.
  std::string text = "Root:\n";
  for (int i = 0; i < 5000; ++i) {
    text += "    a" + std::to_string(i) + " is Real: a" + std::to_string(i + 1) + " + 1\n";
  }
  text += "    a5000 is Real: 1\n";
  EXPECT_FALSE(load(text));
  accept_all_diags();
  EXPECT_GE(count(fe::DiagCode::EvaluationTooDeep), 1u);
}

}  // namespace
