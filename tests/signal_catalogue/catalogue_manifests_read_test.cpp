// The runtime's manifest reader refuses none of the signal catalogue's manifests (every bundle signal type on
// every source fixture that accepts it, and each fixture alone): its checks of field types, duplicate paths
// and value kinds against quantities hold for the widest range of bindings the emitter writes.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "contract/manifest_reader.h"
#include "tests/signal_catalogue/catalogue_probes.h"
#include "tests/signal_catalogue/probe_conversion.h"
#include "tests/signal_catalogue/source_fixtures.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace cat = openplx::catalogue;

TEST(SignalCatalogueManifests, EveryCatalogueManifestReadsBack) {
  const std::vector<cat::SignalType> types = cat::bundle_types();
  const openplx::testing::ScratchDir dir;
  size_t read = 0;
  auto check = [&](const std::string& name, const cat::Conversion& c) {
    if (c.status != 0) return;  // the catalogue lists these as errors
    EXPECT_NO_THROW(openplx::mjcf::parse_manifest(c.manifest, name + ".signals.json")) << name;
    ++read;
  };
  int n = 0;
  for (const cat::SourceFixture& fixture : cat::source_fixtures()) {
    const std::string name = "f" + std::to_string(n++);
    check(name, cat::convert(dir.path(), name, fixture.text));
    const cat::Evaluated e = cat::evaluate(dir / (name + ".openplx"), fixture, types);
    for (const cat::SignalType* t : e.accepting) {
      if (fixture.probe_lines.find("relative_to") != std::string::npos && !t->has_relative_to) continue;
      const std::string probe = name + "_" + std::to_string(read);
      check(probe, cat::convert(dir.path(), probe, fixture.text + cat::probe_lines(*t, fixture)));
    }
  }
  EXPECT_GE(read, 450u);
}

}  // namespace
