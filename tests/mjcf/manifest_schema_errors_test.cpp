// docs/signals.schema.json in the standard validators a user runs, each at its defaults: ajv (the Ajv class,
// under Node), ajv-cli (`ajv validate -s SCHEMA -d FILE`) and Python's jsonschema (`jsonschema.validate`).
// Each passes the samples' manifests and the checked-in golden ones, and refuses a broken manifest with one
// error that names the place and what is wanted (an enum's allowed values, the missing field, the type).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/support/schema_validators.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;
namespace t = openplx::testing;
using nlohmann::json;

const fs::path kSchema = fs::path(OPENPLX_TEST_DATA_DIR).parent_path() / "docs" / "signals.schema.json";

// Converts a sample to DIR/NAME.xml; its manifest's path, or "" when refused.
std::string sample_manifest(const fs::path& source, const fs::path& dir) {
  const std::string xml = (dir / (source.stem().string() + ".xml")).string();
  std::ostringstream out, err;
  if (openplx::cli::run({source.string(), "-o", xml}, out, err) != 0) return "";
  return openplx::cli::manifest_path(xml);
}

std::vector<std::string> files_in(const fs::path& dir, const std::string& ending) {
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.size() > ending.size() && name.compare(name.size() - ending.size(), ending.size(), ending) == 0)
      found.push_back(entry.path().string());
  }
  std::sort(found.begin(), found.end());
  return found;
}

TEST(ManifestSchemaValidators, SamplesAndGoldenManifestsPassAjvAjvCliAndPythonJsonschemaAtTheirDefaults) {
  const t::ScratchDir dir;
  std::vector<std::string> manifests =
      files_in(fs::path(OPENPLX_TEST_DATA_DIR) / "golden" / "mjcf", ".signals.json");
  EXPECT_GE(manifests.size(), 5u);
  for (const std::string& source : files_in(OPENPLX_SAMPLES_DIR, ".openplx")) {
    manifests.push_back(sample_manifest(source, dir.path()));
    EXPECT_NE(manifests.back(), "") << source << " did not convert";
  }
  std::erase(manifests, "");
  for (const auto& validate : {t::ajv_validate, t::ajv_cli_validate, t::python_validate}) {
    const t::Validation v = validate(kSchema, manifests);
    ASSERT_EQ(v.failure, "");
    EXPECT_TRUE(v.warnings.empty()) << "ajv's strict mode logged: " << v.warnings.front();
    for (const std::string& file : manifests)
      EXPECT_TRUE(v.by_file.at(file).valid) << file << ": " << v.by_file.at(file).details.substr(0, 2000);
  }
}

struct Breakage {
  std::string what;
  std::function<void(json&)> spoil;
  std::string place;        // the JSON pointer of the error (ajv's instancePath)
  std::string ajv_says;     // in ajv's error object, as JSON
  std::string python_says;  // in Python's message
};

TEST(ManifestSchemaValidators, ABrokenManifestGivesOneClearErrorInEachValidator) {
  const t::ScratchDir dir;
  const std::string good = sample_manifest(fs::path(OPENPLX_SAMPLES_DIR) / "cart_pole.openplx", dir.path());
  ASSERT_NE(good, "");
  const json manifest = json::parse(std::ifstream(good));
  const json law = {{"kind", "rocket"},          {"path", "p"},      {"actuators", json::array()},
                    {"curve_x", {1.0}},          {"curve_y", {2.0}}, {"curve2_x", json::array()},
                    {"curve2_y", json::array()}, {"parameter", 0}};
  const std::vector<Breakage> broken = {
      {"a missing field", [](json& j) { j["signals"][3].erase("sign"); }, "/signals/3",
       R"("missingProperty":"sign")", "'sign' is a required property"},
      {"a missing top-level field", [](json& j) { j.erase("format_version"); }, "",
       R"("missingProperty":"format_version")", "'format_version' is a required property"},
      {"a wrong type", [](json& j) { j["signals"][0]["enabled"] = "yes"; }, "/signals/0/enabled",
       R"("message":"must be boolean")", "'yes' is not of type 'boolean'"},
      {"a wrong type for a number", [](json& j) { j["signals"][0]["sign"] = true; }, "/signals/0/sign",
       R"("message":"must be number")", "True is not of type 'number'"},
      {"a string for a number", [](json& j) { j["signals"][0]["sign"] = "one"; }, "/signals/0/sign",
       R"("allowedValues":["inf","-inf","nan"])", "'one' is not one of ['inf', '-inf', 'nan']"},
      {"a wrong value kind", [](json& j) { j["signals"][0]["value"] = "complex"; }, "/signals/0/value",
       R"("allowedValues":["real","bool","int","vec2","vec3","vector"])", "'complex' is not one of ['real'"},
      {"a wrong quantity", [](json& j) { j["signals"][1]["quantity"] = "warp_drive"; }, "/signals/1/quantity",
       R"("allowedValues":["none","ctrl","force_range",)", "'warp_drive' is not one of ['none', 'ctrl'"},
      {"an unknown field", [](json& j) { j["signals"][2]["colour"] = "red"; }, "/signals/2",
       R"("additionalProperty":"colour")", "('colour' was unexpected)"},
      {"a newer format", [](json& j) { j["format_version"] = 2; }, "/format_version", R"("allowedValue":1)",
       "1 was expected"},
      {"a time step of zero", [](json& j) { j["timestep"] = 0; }, "/timestep", R"("message":"must be > 0")",
       "0 is less than or equal to the minimum of 0"},
      {"an unknown law", [&](json& j) { j["laws"] = json::array({law}); }, "/laws/0/kind",
       R"("allowedValues":["engine","torque_converter",)", "'rocket' is not one of ['engine'"},
  };
  std::vector<std::string> files;
  for (size_t k = 0; k < broken.size(); ++k) {
    json bad = manifest;
    broken[k].spoil(bad);
    ASSERT_NE(bad, manifest) << broken[k].what;
    files.push_back((dir / ("broken_" + std::to_string(k) + ".signals.json")).string());
    std::ofstream(files.back()) << bad.dump(1);
  }
  const t::Validation ajv = t::ajv_validate(kSchema, files), cli = t::ajv_cli_validate(kSchema, files),
                      python = t::python_validate(kSchema, files);
  ASSERT_EQ(ajv.failure + cli.failure + python.failure, "");
  for (size_t k = 0; k < broken.size(); ++k) {
    const Breakage& b = broken[k];
    SCOPED_TRACE(b.what);
    const t::Verdict& v = ajv.by_file.at(files[k]);
    EXPECT_FALSE(v.valid);
    EXPECT_EQ(v.errors, 1) << v.details;
    EXPECT_NE(v.details.find(R"("instancePath":")" + b.place + '"'), std::string::npos) << v.details;
    EXPECT_NE(v.details.find(b.ajv_says), std::string::npos) << v.details;
    const t::Verdict& c = cli.by_file.at(files[k]);
    EXPECT_FALSE(c.valid);
    EXPECT_EQ(c.errors, 1) << c.details;
    EXPECT_NE(c.details.find("instancePath: '" + b.place + "'"), std::string::npos) << c.details;
    const t::Verdict& p = python.by_file.at(files[k]);
    EXPECT_FALSE(p.valid);
    EXPECT_EQ(p.errors, 1) << p.details;
    EXPECT_NE(p.details.find(b.python_says), std::string::npos) << p.details;
  }
}

}  // namespace
