// The command line's documentation against its parser: every option parse_options takes is in --help and in
// README's "Command line" section, and every option --help names is taken. --depfile names what was read.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace fs = std::filesystem;
namespace cli = openplx::cli;

namespace {

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

const fs::path kSource = fs::path(OPENPLX_TEST_DATA_DIR).parent_path();

// The option names written as string literals in parse_options (tools/cli/cli.cpp).
std::set<std::string> parsed_options() {
  const std::string source = read(kSource / "tools/cli/cli.cpp");
  const size_t begin = source.find("std::optional<CliOptions> parse_options(");
  const size_t end = source.find("\nint run(", begin);
  EXPECT_NE(begin, std::string::npos);
  const std::string body = source.substr(begin, end - begin);
  std::set<std::string> names;
  const std::regex literal("\"(--?[A-Za-z][A-Za-z0-9-]*|--)\"");
  for (auto it = std::sregex_iterator(body.begin(), body.end(), literal); it != std::sregex_iterator(); ++it)
    names.insert((*it)[1]);
  return names;
}

bool mentions(const std::string& text, const std::string& option) {
  const std::regex word("(^|[^A-Za-z0-9-])" + std::regex_replace(option, std::regex("-"), "\\-") +
                        "($|[^A-Za-z0-9-])");
  return std::regex_search(text, word);
}

TEST(CliOptions, HelpAndReadmeListEveryOption) {
  const std::set<std::string> parsed = parsed_options();
  ASSERT_GT(parsed.size(), 15u);
  const std::string help = cli::usage();
  const std::string readme = read(kSource / "README.md");
  const size_t begin = readme.find("## Command line");
  const std::string command_line = readme.substr(begin, readme.find("\n## ", begin + 1) - begin);
  for (const std::string& option : parsed) {
    EXPECT_TRUE(mentions(help, option)) << option << " is not in --help";
    EXPECT_TRUE(mentions(command_line, option)) << option << " is not in README's Command line";
  }
  // And the other way: every option --help lists at the start of a line is one the parser takes.
  const std::regex listed("\n  (--?[A-Za-z][A-Za-z0-9-]*)");
  for (auto it = std::sregex_iterator(help.begin(), help.end(), listed); it != std::sregex_iterator(); ++it)
    EXPECT_TRUE(parsed.count((*it)[1])) << (*it)[1] << " is in --help but not parsed";
  // What -o does by default is said as it is.
  EXPECT_NE(help.find("Without -o nothing is written"), std::string::npos);
}

TEST(CliOptions, DepfileNamesTheModelItsImportsAndBundles) {
  const openplx::testing::ScratchDir dir;
  const std::string model = std::string(OPENPLX_SAMPLES_DIR) + "/urdf_pantilt.openplx";
  const std::string out = (dir.path() / "pan tilt.xml").string();  // a space, escaped in the depfile
  const std::string dep = (dir.path() / "pan tilt.d").string();
  std::ostringstream o, e;
  ASSERT_EQ(cli::run({model, "-o", out, "--depfile", dep}, o, e), 0) << e.str();
  const std::string text = read(dep);
  auto escaped = [](std::string path) { return std::regex_replace(path, std::regex(" "), "\\ "); };
  EXPECT_EQ(text.rfind(escaped(out) + ":", 0), 0u) << text;
  EXPECT_NE(text.find(fs::canonical(model).string()), std::string::npos) << text;
  EXPECT_NE(text.find(fs::canonical(kSource / "tests/corpus/urdf/bullet3/pantilt.urdf").string()),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("/Physics3D/Bodies/RigidBody.openplx"), std::string::npos) << text;
  // Without a file to name, a depfile is a usage error.
  EXPECT_EQ(cli::run({model, "--depfile", dep}, o, e), 2);
  EXPECT_EQ(cli::run({model, "-o", "-", "--depfile", dep}, o, e), 2);
}

}  // namespace
