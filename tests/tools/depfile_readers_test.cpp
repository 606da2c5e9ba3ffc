// --depfile as the real readers see it: GNU Make includes it and Ninja ingests it (deps = gcc), for an output
// and inputs whose names hold a space, ':', '$', '#', ',', '!', '@' and brackets; each must find the output
// up to date, then out of date once an input is touched. A name neither can carry is a located refusal that
// names the character.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace fs = std::filesystem;
using openplx::testing::cli;
using openplx::testing::Conversion;

void write(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The shell's quoting of `text`, for std::system.
std::string quoted(const std::string& text) {
  std::string q = "'";
  for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

int shell(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Model files in a folder with an awkward name, converted with a depfile beside them.
struct Converted {
  openplx::testing::ScratchDir scratch;
  fs::path folder = scratch / "we ird:$#,!@[x]";
  fs::path part = folder / "pa rt$#.openplx", output = folder / "o u:t#$.xml", dep = scratch / "dep.d";
  Conversion run;
  Converted() {
    fs::create_directories(folder);
    write(part, "Part is Physics3D.Bodies.RigidBody:\n    inertia.mass: 2.0\n");
    write(folder / "m.openplx",
          "import @\"pa rt$#.openplx\"\n\nScene is Physics3D.System:\n    body is Part\n");
    run = cli({(folder / "m.openplx").string(), "-o", output.string(), "--depfile", dep.string()});
  }
  // Outputs newer than every input, as after a build.
  void settle() {
    const auto old = fs::file_time_type::clock::now() - std::chrono::hours(1);
    fs::last_write_time(part, old);
    fs::last_write_time(folder / "m.openplx", old);
  }
  void touch_input() { fs::last_write_time(part, fs::file_time_type::clock::now() + std::chrono::hours(1)); }
};

TEST(DepfileReaders, MakeReadsAwkwardNames) {
  Converted c;
  ASSERT_EQ(c.run.status, 0) << c.run.errors;
  const std::string text = read(c.dep);
  // The depfile's own target line gives the rule a recipe, so `make -q` answers for it (the default goal).
  const std::string target = text.substr(0, text.find(": \\\n"));
  write(c.scratch / "Makefile", "include dep.d\n" + target + ":\n\t@echo remade\n");
  const std::string make = "cd " + quoted(c.scratch.path().string()) + " && make -q >/dev/null 2>&1";
  c.settle();
  EXPECT_EQ(shell(make), 0) << text;  // up to date
  c.touch_input();
  EXPECT_EQ(shell(make), 1) << text;  // an input changed
}

TEST(DepfileReaders, NinjaReadsAwkwardNames) {
  Converted c;
  ASSERT_EQ(c.run.status, 0) << c.run.errors;
  // build.ninja's own escapes for the output: '$' before '$', ' ' and ':'.
  std::string output;
  for (char ch : c.output.string()) {
    if (ch == '$' || ch == ' ' || ch == ':') output += '$';
    output += ch;
  }
  // Ninja moves the depfile into its log (and deletes it) when the command has run: a command that does
  // nothing, with the depfile the converter wrote.
  write(c.scratch / "build.ninja",
        "rule convert\n  command = true\n  depfile = dep.d\n  deps = gcc\nbuild " + output + ": convert\n");
  const std::string in = "cd " + quoted(c.scratch.path().string()) + " && ";
  c.settle();
  ASSERT_EQ(shell(in + "ninja >/dev/null"), 0);
  ASSERT_EQ(shell(in + "ninja -t deps > deps.txt"), 0);
  const std::string deps = read(c.scratch / "deps.txt");
  EXPECT_NE(deps.find("\n    " + c.part.string() + "\n"), std::string::npos) << deps;
  EXPECT_NE(deps.find("\n    " + (c.folder / "m.openplx").string() + "\n"), std::string::npos) << deps;
  ASSERT_EQ(shell(in + "ninja -n > plan.txt"), 0);
  EXPECT_NE(read(c.scratch / "plan.txt").find("no work to do"), std::string::npos);
  c.touch_input();
  ASSERT_EQ(shell(in + "ninja -n > plan.txt"), 0);
  EXPECT_EQ(read(c.scratch / "plan.txt").find("no work to do"), std::string::npos);
}

TEST(DepfileReaders, NamesNeitherReadsAreRefusedByCharacter) {
  const openplx::testing::ScratchDir dir;
  const std::string model = std::string(OPENPLX_SAMPLES_DIR) + "/pendulum.openplx";
  // Each measured with Make 4.3 and Ninja 1.11 (tools/cli/depfile.h): Ninja ends a name at * ? " | &,
  // Make reads ( = ; % (in the target) and a newline as syntax.
  for (const std::string bad :
       {"a*b", "a?b", "a\"b", "a|b", "a&b", "a(b)", "a=b", "a;b", "a%b", "a\nb", "a\tb"}) {
    SCOPED_TRACE(bad);
    const std::string output = (dir / (bad + ".xml")).string(), dep = (dir / "dep.d").string();
    const Conversion r = cli({model, "-o", output, "--depfile", dep});
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.errors.find(dep + ": error: cannot write a depfile naming"), std::string::npos) << r.errors;
    const std::string character = bad == "a\nb"   ? "a newline"
                                  : bad == "a\tb" ? "a tab"
                                                  : "'" + bad.substr(1, 1) + "'";
    EXPECT_NE(r.errors.find("its name has " + character), std::string::npos) << r.errors;
    EXPECT_FALSE(fs::exists(output));
    EXPECT_FALSE(fs::exists(dep));
  }
}

}  // namespace
