// The manifests of the signal catalogue's conversions (every bundle signal type on every source fixture that
// accepts it, and each fixture alone) validate against docs/signals.schema.json in ajv at its defaults: the
// widest range of quantities, reasons and names a manifest holds, checked by a standard validator.
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "tests/signal_catalogue/catalogue_probes.h"
#include "tests/signal_catalogue/probe_conversion.h"
#include "tests/signal_catalogue/source_fixtures.h"
#include "tests/support/schema_validators.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace fs = std::filesystem;
namespace cat = openplx::catalogue;

TEST(SignalCatalogueManifests, EveryCatalogueManifestValidatesInAjv) {
  const std::vector<cat::SignalType> types = cat::bundle_types();
  const openplx::testing::ScratchDir dir;
  std::vector<std::string> manifests;
  size_t refused = 0;
  auto keep = [&](const std::string& name, const cat::Conversion& c) {
    if (c.status != 0) {
      ++refused;  // the catalogue lists these as errors
      return;
    }
    manifests.push_back((dir / (name + ".signals.json")).string());
  };
  int n = 0;
  for (const cat::SourceFixture& fixture : cat::source_fixtures()) {
    const std::string name = "f" + std::to_string(n++);
    keep(name, cat::convert(dir.path(), name, fixture.text));
    const cat::Evaluated e = cat::evaluate(dir / (name + ".openplx"), fixture, types);
    for (const cat::SignalType* t : e.accepting) {
      if (fixture.probe_lines.find("relative_to") != std::string::npos && !t->has_relative_to) continue;
      const std::string probe = name + "_" + std::to_string(manifests.size() + refused);
      keep(probe, cat::convert(dir.path(), probe, fixture.text + cat::probe_lines(*t, fixture)));
    }
  }
  // The catalogue's counts (docs/signal-catalogue.md): 53 fixtures, 457 combinations, a few errors.
  EXPECT_GE(manifests.size(), 450u);
  EXPECT_LE(refused, 10u);
  for (const std::string& m : manifests) ASSERT_TRUE(fs::exists(m)) << m;
  const openplx::testing::Validation v = openplx::testing::ajv_validate(
      fs::path(OPENPLX_TEST_DATA_DIR).parent_path() / "docs" / "signals.schema.json", manifests);
  ASSERT_EQ(v.failure, "");
  EXPECT_TRUE(v.warnings.empty()) << "ajv's strict mode logged: " << v.warnings.front();
  size_t valid = 0;
  for (const std::string& m : manifests) {
    const openplx::testing::Verdict& verdict = v.by_file.at(m);
    valid += verdict.valid;
    EXPECT_TRUE(verdict.valid) << m << ": " << verdict.details.substr(0, 2000);
  }
  std::cout << valid << " of " << manifests.size() << " catalogue manifests valid for ajv\n";
}

}  // namespace
