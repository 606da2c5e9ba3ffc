// Files of many top-level declarations cost work linear in their number. Each shape is checked at N and
// 4N models by the steps Program::name_steps() counts (namespaces asked for a name, models compared for
// an inherited attribute, names offered to a "did you mean"): linear work grows about 4 times, a walk over
// every earlier model 16 times. A count, not a clock: the seconds are bench/declaration_scaling.sh's.
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "frontend/pipeline.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace fe = openplx::frontend;

struct Outcome {
  size_t steps = 0;
  size_t errors = 0;
  std::string printed;  // the diagnostics as the command line prints them
  std::string first_message;
};

// Writes `main` (and `others`, by relative path) into a fresh folder and runs the front end on it.
Outcome check(const std::string& main, const std::vector<std::pair<std::string, std::string>>& others = {}) {
  openplx::testing::ScratchDir dir;
  for (const auto& [path, text] : others) std::ofstream(dir / path, std::ios::binary) << text;
  const std::string path = (dir / "main.openplx").generic_string();
  std::ofstream(path, std::ios::binary) << main;
  fe::SourceManager sources;
  fe::DiagnosticSink sink;
  fe::Evaluation evaluation =
      fe::evaluate_file(fe::LoadRequest{path, std::nullopt, {}, std::nullopt}, sources, sink);
  Outcome out;
  out.steps = evaluation.program->name_steps();
  out.errors = sink.error_count();
  std::ostringstream printed;
  fe::print_diagnostics(printed, sources, sink.diagnostics());
  out.printed = printed.str();
  if (!sink.diagnostics().empty()) out.first_message = sink.diagnostics().front().message;
  return out;
}

std::string repeat(int n, const std::function<std::string(int)>& line) {
  std::string text;
  for (int i = 0; i < n; ++i) text += line(i);
  return text;
}

// The steps for n and 4n models: about 4 times as many when linear, 16 when quadratic.
void expect_linear(const std::function<Outcome(int)>& shape, int n) {
  const Outcome small = shape(n);
  const Outcome large = shape(4 * n);
  EXPECT_EQ(small.errors, 0u) << small.printed;
  EXPECT_EQ(large.errors, 0u) << large.printed;
  EXPECT_GT(small.steps, 0u);
  EXPECT_LE(large.steps, 5 * small.steps)
      << n << " models: " << small.steps << " steps; " << 4 * n << " models: " << large.steps << " steps";
}

std::string number(int i) {
  return std::to_string(i);
}

TEST(DeclarationScaling, EveryModelDeclaringTheSameAttribute) {
  // Each new `a` was compared with every earlier model declaring one.
  expect_linear(
      [](int n) { return check(repeat(n, [](int i) { return "M" + number(i) + ":\n    a is Real: 1\n"; })); },
      1000);
}

TEST(DeclarationScaling, EveryModelExtendingOneBundleModel) {
  expect_linear(
      [](int n) {
        return check(repeat(n, [](int i) {
          return "M" + number(i) +
                 " is Physics3D.Bodies.RigidBody:\n    a is Real: 1\n    inner is "
                 "Physics3D.Bodies.RigidBody:\n"
                 "        b is Real: 2\n    c is Real: a + 1\n";
        }));
      },
      500);
}

TEST(DeclarationScaling, ChainWhoseNamesUnrelatedModelsDeclareToo) {
  // Each `Mk is M(k-1)` declares xk, which `Uk` declares too: was Uk above Mk? Listing the chain above each
  // model to answer is quadratic.
  expect_linear(
      [](int n) {
        return check(
            repeat(n, [](int i) { return "U" + number(i) + ":\n    x" + number(i) + " is Real: 1\n"; }) +
            "M0:\n    x0 is Real: 0\n" + repeat(n - 1, [](int k) {
              return "M" + number(k + 1) + " is M" + number(k) + ":\n    x" + number(k + 1) + " is Real: 1\n";
            }));
      },
      1000);
}

TEST(DeclarationScaling, ManyImportedFiles) {
  // `Mi is Fi` where Fi comes from the i-th import: the imports were asked one by one.
  expect_linear(
      [](int n) {
        std::vector<std::pair<std::string, std::string>> files;
        for (int i = 0; i < n; ++i)
          files.emplace_back("f" + number(i) + ".openplx", "F" + number(i) + ":\n    f is Real: 1\n");
        return check(
            repeat(n, [](int i) { return "import @\"f" + number(i) + ".openplx\"\n"; }) +
                repeat(n,
                       [](int i) { return "M" + number(i) + " is F" + number(i) + ":\n    a is Real: 1\n"; }),
            files);
      },
      300);
}

TEST(DeclarationScaling, OneFileImportedAgainAndAgain) {
  expect_linear(
      [](int n) {
        return check(
            repeat(n, [](int) { return std::string("import @\"other.openplx\"\n"); }) +
                repeat(n,
                       [](int i) {
                         return "M" + number(i) + " is O" + number(i % 10) + ":\n    a is Real: 1\n";
                       }),
            {{"other.openplx", repeat(10, [](int i) { return "O" + number(i) + ":\n    o is Real: 1\n"; })}});
      },
      1000);
}

TEST(DeclarationScaling, LastModelHoldingEveryOther) {
  expect_linear(
      [](int n) {
        return check(repeat(n, [](int i) { return "M" + number(i) + ":\n    a is Real: 1\n"; }) + "Root:\n" +
                     repeat(n, [](int i) { return "    m" + number(i) + " is M" + number(i) + "\n"; }));
      },
      1000);
}

TEST(DeclarationScaling, UnknownNameInEveryModel) {
  // Each unknown name offered every name of the file to a "did you mean": only the printed ones do now.
  auto shape = [](int n) {
    return check(
        repeat(n, [](int i) { return "M" + number(i) + " is Mx" + number(i) + ":\n    a is Real: 1\n"; }));
  };
  const Outcome small = shape(1000);
  const Outcome large = shape(4000);
  EXPECT_EQ(small.errors, 1000u);
  EXPECT_EQ(large.errors, 4000u);
  EXPECT_LE(large.steps, 5 * small.steps) << small.steps << " steps, then " << large.steps;
  // The printout is as it was: 100 errors, each with its suggestion, then the note that stops there.
  EXPECT_EQ(small.first_message, "Unknown name Mx0; did you mean `M0`?");
  size_t printed = 0;
  for (size_t at = large.printed.find("error: "); at != std::string::npos;
       at = large.printed.find("error: ", at + 1))
    ++printed;
  EXPECT_EQ(printed, fe::kMaxPrintedErrors);
  EXPECT_NE(large.printed.find("Unknown name Mx99; did you mean `M"), std::string::npos) << large.printed;
  EXPECT_NE(large.printed.find("too many errors, stopping after 100"), std::string::npos);
}

TEST(DeclarationScaling, FirstImportDeclaringANameWins) {
  // Both files declare Shared; only a.openplx's has `only_in_a`.
  const Outcome both =
      check("import @\"a.openplx\"\nimport @\"b.openplx\"\nScene is Shared:\n    check is Real: only_in_a\n",
            {{"a.openplx", "Shared:\n    only_in_a is Real: 1\n"},
             {"b.openplx", "Shared:\n    only_in_b is Real: 2\n"}});
  EXPECT_EQ(both.errors, 0u) << both.printed;
  const Outcome swapped =
      check("import @\"b.openplx\"\nimport @\"a.openplx\"\nScene is Shared:\n    check is Real: only_in_a\n",
            {{"a.openplx", "Shared:\n    only_in_a is Real: 1\n"},
             {"b.openplx", "Shared:\n    only_in_b is Real: 2\n"}});
  EXPECT_EQ(swapped.errors, 1u) << swapped.printed;
}

TEST(DeclarationScaling, AttributeDeclaredAgainDownAChainIsStillReported) {
  // The chain check (a declarer on the bases above) finds what listing every ancestor found.
  std::string text =
      repeat(300, [](int i) { return "U" + number(i) + ":\n    x" + number(i) + " is Real: 1\n"; });
  text += "M0:\n    x0 is Real: 0\n";
  for (int k = 1; k < 300; ++k)
    text += "M" + number(k) + " is M" + number(k - 1) + ":\n    x" + number(k) + " is Real: 1\n";
  const Outcome clash = check(text + "Scene is M299:\n    x5 is Real: 9\n    u is U5\n");
  EXPECT_EQ(clash.errors, 1u) << clash.printed;
  EXPECT_EQ(clash.first_message, "Duplicate attribute name x5 (already declared in M5)");
  const Outcome apart = check(text + "Scene is U5:\n    x7 is Real: 9\n");
  EXPECT_EQ(apart.errors, 0u) << apart.printed;
}

}  // namespace
