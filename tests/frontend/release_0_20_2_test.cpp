// The official OpenPLX bundle release 0.20.2 (as AGXUnity ships it) as a user's only bundles:
// `--no-default-bundles -B RELEASE`. Every file parses; the names it leaves to its host are exactly those
// natives/host_declarations.cpp declares for its generation; the corpus models whose names all exist in it
// convert to the same MJCF as with our bundles; newer names get a note saying so.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "frontend/bundles/bundles.h"
#include "frontend/natives/host_declarations.h"
#include "frontend/semantics/program.h"
#include "frontend/syntax/parser.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;
namespace fe = openplx::frontend;

const fs::path kShared = fs::path(OPENPLX_SHARED_CORPUS_DIR) / ".." / "bundles-0.20.2";
const fs::path kVendored = fs::path(OPENPLX_TEST_DATA_DIR) / "bundle_releases" / "0.20.2";
const fs::path kCorpus = fs::path(OPENPLX_CORPUS_DIR) / "agxunity";

fs::path release_dir() {
  return fs::is_directory(kShared) ? kShared : kVendored;
}

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<fs::path> release_files() {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(release_dir())) {
    if (entry.path().extension() == ".openplx") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

int convert(const std::vector<std::string>& args, std::string* out, std::string* err) {
  std::ostringstream o, e;
  const int status = openplx::cli::run(args, o, e);
  if (out) *out = o.str();
  if (err) *err = e.str();
  return status;
}

TEST(Release0202, VendoredCopyMatchesShared) {
  if (!fs::is_directory(kShared)) GTEST_SKIP() << "no ../shared/bundles-0.20.2 in this checkout";
  for (const auto& entry : fs::recursive_directory_iterator(kShared)) {
    if (!entry.is_regular_file()) continue;
    const fs::path copy = kVendored / fs::relative(entry.path(), kShared);
    EXPECT_EQ(read(copy), read(entry.path())) << copy;
  }
}

// All 490 files parse. The layouts the release writes that the spec's rule does not cover are warnings:
// lines deeper than their block after a `.doc` (unexpected-indent, §2.3's leniency) and TIM150's line one
// column short of its block (misaligned-indent).
TEST(Release0202, EveryFileParses) {
  std::map<std::string, int> warnings;
  size_t files = 0;
  for (const fs::path& path : release_files()) {
    fe::SourceManager sources;
    fe::DiagnosticSink sink;
    std::string error;
    const std::optional<fe::FileId> id = sources.load(path.string(), error);
    ASSERT_TRUE(id) << error;
    fe::parse_file(sources, *id, sink);
    ++files;
    for (const fe::Diagnostic& d : sink.diagnostics()) {
      EXPECT_NE(d.severity, fe::Severity::Error) << path << ": " << d.message;
      const fe::SourceFile& file = sources.file(d.range.file);
      warnings[fs::relative(path, release_dir()).generic_string() + ":" +
               std::to_string(file.line_col(d.range.begin).line) + " " +
               std::string(fe::code_name(d.code))]++;
    }
  }
  EXPECT_EQ(files, 490u);
  const std::map<std::string, int> expected = {
      {"Physics3D/Interactions/World.openplx:5 unexpected-indent", 1},
      {"Robotics/Signals/RobotInput.openplx:7 unexpected-indent", 1},  // 2-space `.doc`, 4-space body
      {"Robotics/Signals/RobotOutput.openplx:13 unexpected-indent", 1},
      {"Sensors/Library/LIDARs/SICK/TIM150.openplx:35 misaligned-indent", 1}};
  EXPECT_EQ(warnings, expected);
}

// Resolves every type a member names (attribute, `becomes` and parameter types, traits), in nested blocks
// too.
void resolve_member_types(fe::Program& program, fe::DocumentInfo* doc,
                          const std::vector<fe::Member>& members) {
  static const std::set<std::string> kPrimitive = {"Real", "Int", "Bool", "String"};
  auto resolve = [&](const fe::QualifiedName& name) {
    if (!kPrimitive.count(fe::to_string(name))) program.resolve_model_name(doc, name);
  };
  for (const fe::Member& m : members) {
    for (const fe::TypeRef& type : m.type.alternatives) resolve(type.name);
    for (const fe::QualifiedName& trait : m.type.traits) resolve(trait);
    if (m.kind == fe::MemberKind::TraitUse) resolve(m.path);
    for (const fe::Param& param : m.params) resolve(param.type.name);
    if (m.return_type) resolve(m.return_type->name);
    resolve_member_types(program, doc, m.block);
  }
}

// Loads every file of the release as a bundle file and resolves every model and trait in it (bases, traits)
// and every type its members name. Returns the names reported unknown.
std::set<std::string> unknown_names(bool host_declarations, size_t* models) {
  fe::SourceManager sources;
  fe::DiagnosticSink sink;
  fe::Program program(sources, sink);
  program.set_host_declarations(host_declarations);
  program.set_bundles(
      fe::discover_bundles(fe::bundle_search_path({release_dir().string()}, false), sources, sink));
  *models = 0;
  for (const fs::path& path : release_files()) {
    if (path.filename() == "config.openplx") continue;  // a bundle's description, not part of it
    fe::DocumentInfo* doc = program.load_main(path.string());
    if (!doc) continue;
    for (const fe::Decl& decl : doc->doc.decls) {
      if (decl.kind != fe::DeclKind::Model && decl.kind != fe::DeclKind::Trait) continue;
      if (fe::ModelInfo* model = program.lookup_in(doc->ns, decl.name.text).model) {
        program.resolve(model);
        ++*models;
      }
      resolve_member_types(program, doc, decl.body);
    }
  }
  std::set<std::string> names;
  const std::regex unknown("^Unknown name ([A-Za-z0-9_.]+)(: no `([A-Za-z0-9_]+)` in ([A-Za-z0-9_.]+))?");
  for (const fe::Diagnostic& d : sink.diagnostics()) {
    if (d.code != fe::DiagCode::UnknownName) continue;
    std::smatch m;
    if (!std::regex_search(d.message, m, unknown)) {
      ADD_FAILURE() << d.message;
      continue;
    }
    names.insert(m[2].matched ? m[4].str() + "." + m[3].str() : m[1].str());
  }
  return names;
}

// The names the release references and none of its files declares: found by resolving everything with the
// host's declarations off. They are exactly the 0.20 generation's host declarations, and with those on
// nothing is unknown.
TEST(Release0202, HostDeclaresExactlyWhatTheReleaseLeavesUndeclared) {
  size_t models = 0;
  const std::set<std::string> missing = unknown_names(false, &models);
  EXPECT_GT(models, 500u);
  std::set<std::string> declared;
  for (const openplx::natives::HostDeclaration& d : openplx::natives::host_generation("0.20.2").declarations)
    declared.insert(d.ns.empty() ? std::string(d.name) : std::string(d.ns) + "." + std::string(d.name));
  EXPECT_EQ(missing, declared);
  EXPECT_EQ(unknown_names(true, &models), std::set<std::string>{});
}

// The release's triaxial sensor outputs compute their marshalling natively, as its host does: 8 bytes (a
// double) per axis listed.
TEST(Release0202, TriaxialOutputsHaveTheirNatives) {
  const openplx::testing::ScratchDir dir;
  std::ofstream(dir / "gyro.openplx") << "Readings:\n"
                                         "    gyro is Sensors.Signals.GyroscopeOutput:\n"
                                         "        fields: [Sensors.Signals.TriaxialOutputField.X_F64,\n"
                                         "                 Sensors.Signals.TriaxialOutputField.Z_F64]\n";
  std::ofstream(dir / "magnet.openplx") << "Readings:\n"
                                           "    magnet is Sensors.Signals.MagnetometerOutput:\n"
                                           "        fields: [4]\n";
  std::string values, err;
  ASSERT_EQ(convert({(dir / "gyro.openplx").string(), "--no-default-bundles", "-B", release_dir().string(),
                     "--dump=values"},
                    &values, &err),
            0)
      << err;
  EXPECT_NE(values.find("gyro.marshalling.size = 16"), std::string::npos) << values;
  EXPECT_EQ(convert({(dir / "magnet.openplx").string(), "--no-default-bundles", "-B", release_dir().string(),
                     "--dump=values"},
                    &values, &err),
            1);
  EXPECT_NE(err.find("unknown triaxial output field 4 [native-error]"), std::string::npos) << err;
}

// Corpus models written with names the release has: with it as the only bundles they pass --check and give
// the MJCF our bundles give, byte for byte. Their signal manifests differ only in disabled outputs the two
// generations declare differently (0.20.2's RigidBody has `rpy_output`; its LinearRange no
// `position_output`).
TEST(Release0202, CorpusConvertsAsWithOurBundles) {
  const openplx::testing::ScratchDir dir;
  const char* models[] = {
      "LinearRangeTest", "LinearSpringTest",  "differential_test",         "drive_train_velocity_input",
      "material_scene",  "multi_interaction", "obj_import_test",           "shovel",
      "signal_test",     "simple_lidar",      "simpler_inverted_pendulum", "torque_range"};
  auto enabled_signals = [](const std::string& manifest) {
    std::set<std::string> lines;
    std::istringstream in(manifest);
    for (std::string line; std::getline(in, line);) {
      if (line.find("\"enabled\": false") == std::string::npos) lines.insert(line.substr(0, line.rfind('}')));
    }
    return lines;
  };
  for (const char* name : models) {
    SCOPED_TRACE(name);
    const std::string model = (kCorpus / (std::string(name) + ".openplx")).string();
    const fs::path theirs = dir.path() / (std::string(name) + "_release.xml");
    const fs::path ours = dir.path() / (std::string(name) + "_ours.xml");
    std::string err_theirs, err_ours;
    ASSERT_EQ(convert({model, "--no-default-bundles", "-B", release_dir().string(), "--check", "-o",
                       theirs.string()},
                      nullptr, &err_theirs),
              0)
        << err_theirs;
    ASSERT_EQ(convert({model, "--check", "-o", ours.string()}, nullptr, &err_ours), 0) << err_ours;
    EXPECT_EQ(read(theirs), read(ours));
    EXPECT_EQ(err_theirs, err_ours);  // the same warnings, at the user's lines
    const auto manifest = [](const fs::path& xml) {
      return fs::path(xml).replace_extension(".signals.json");
    };
    EXPECT_EQ(enabled_signals(read(manifest(theirs))), enabled_signals(read(manifest(ours))));
  }
}

// Models using names newer than the release: the usual unknown-name error, and a note naming the release
// found and its version.
TEST(Release0202, NewerNamesSayTheReleaseIsOlder) {
  const openplx::testing::ScratchDir dir;
  const std::map<std::string, std::string> models = {
      {"visual_mat",
       "`Visuals.Materials.SurfaceFeatures` is newer than the bundle release found, Visuals 0.20.2"},
      {"track_system", "`Vehicles.TrackSystem` is newer than the bundle release found, Vehicles 0.20.2"},
      {"visual_mesh_import",
       "`Visuals.Geometries.ExternalTriMeshGeometry` is newer than the bundle release found, Visuals "
       "0.20.2"}};
  for (const auto& [name, note] : models) {
    SCOPED_TRACE(name);
    std::string err;
    EXPECT_EQ(convert({(kCorpus / (name + ".openplx")).string(), "--no-default-bundles", "-B",
                       release_dir().string(), "-o", (dir.path() / "x.xml").string()},
                      nullptr, &err),
              1);
    EXPECT_NE(err.find("[unknown-name]"), std::string::npos) << err;
    EXPECT_NE(err.find("note: " + note), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(dir.path() / "x.xml"));
  }
  // A whole bundle the release does not have.
  std::ofstream(dir.path() / "control.openplx") << "Root is Control.Nothing\n";
  std::string err;
  EXPECT_EQ(convert({(dir.path() / "control.openplx").string(), "--no-default-bundles", "-B",
                     release_dir().string(), "--dump=values"},
                    nullptr, &err),
            1);
  EXPECT_NE(err.find("note: bundle `Control` is newer than the bundle release found"), std::string::npos)
      << err;
  EXPECT_NE(err.find(" 0.20.2 ("), std::string::npos) << err;
}

// use_test_bundle.openplx names bundle `Test`, which its neighbour folder TestBundle/ holds.
TEST(Release0202, BundleFolderBesideTheModelIsSuggested) {
  const openplx::testing::ScratchDir dir;
  const std::string model = (kCorpus / "use_test_bundle.openplx").string();
  std::string err;
  EXPECT_EQ(convert({model, "--no-default-bundles", "-B", release_dir().string(), "-o",
                     (dir.path() / "x.xml").string()},
                    nullptr, &err),
            1);
  EXPECT_NE(err.find("Unknown name Test [unknown-name]"), std::string::npos) << err;
  EXPECT_NE(err.find("add `-B " + (kCorpus / "TestBundle").generic_string() + "`"), std::string::npos) << err;
  const fs::path theirs = dir.path() / "release.xml", ours = dir.path() / "ours.xml";
  ASSERT_EQ(convert({model, "--no-default-bundles", "-B", release_dir().string(), "-B",
                     (kCorpus / "TestBundle").string(), "--check", "-o", theirs.string()},
                    nullptr, &err),
            0)
      << err;
  ASSERT_EQ(convert({model, "-B", (kCorpus / "TestBundle").string(), "-o", ours.string()}, nullptr, &err), 0)
      << err;
  EXPECT_EQ(read(theirs), read(ours));
}

}  // namespace
