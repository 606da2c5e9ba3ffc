// The signal catalogue (docs/signal-catalogue.md): every Input and Output type the bundles declare, attached
// to every source fixture its `source` accepts, converted; the document must say what the converter does
// today. With OPENPLX_UPDATE_CATALOGUE=1 the test writes the document instead of comparing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "frontend/pipeline.h"
#include "tests/signal_catalogue/catalogue_document.h"
#include "tests/signal_catalogue/catalogue_probes.h"
#include "tests/signal_catalogue/probe_conversion.h"
#include "tests/signal_catalogue/signal_types.h"
#include "tests/signal_catalogue/source_fixtures.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace fe = openplx::frontend;
namespace fs = std::filesystem;
namespace cat = openplx::catalogue;

const fs::path kDocument = fs::path(OPENPLX_TEST_DATA_DIR).parent_path() / "docs" / "signal-catalogue.md";

using cat::bundle_types;
using cat::evaluate;
using cat::Evaluated;
using cat::probe_lines;

// The first line where `a` and `b` differ, for the failure message.
std::string first_difference(const std::string& a, const std::string& b) {
  std::istringstream x(a), y(b);
  std::string l, r;
  for (int line = 1;; ++line) {
    const bool more_l = static_cast<bool>(std::getline(x, l)), more_r = static_cast<bool>(std::getline(y, r));
    if (!more_l && !more_r) return "";
    if (l != r || more_l != more_r)
      return "line " + std::to_string(line) + ":\n  document: " + (more_l ? l : "<end>") +
             "\n  code:     " + (more_r ? r : "<end>");
  }
}

TEST(SignalCatalogue, TheBundlesDeclareSignalsOfEveryFamily) {
  const std::vector<cat::SignalType> types = bundle_types();
  EXPECT_GE(types.size(), 50u);
  auto has = [&](const std::string& name) {
    return std::any_of(types.begin(), types.end(), [&](const cat::SignalType& t) { return t.name == name; });
  };
  for (const char* name : {"Physics.Signals.AngleOutput", "Physics3D.Signals.Torque3DInput",
                           "DriveTrain.Signals.TorqueConverterPumpTorqueOutput", "Sensors.Signals.IMUOutput",
                           "Robotics.Signals.RobotInput", "Control.Virtual.BroadcastInput"})
    EXPECT_TRUE(has(name)) << name;
  EXPECT_FALSE(has("Physics.Signals.Input"));  // the bases themselves are not signal types
}

TEST(SignalCatalogue, DocumentSaysWhatTheConverterDoes) {
  const std::vector<cat::SignalType> types = bundle_types();
  const openplx::testing::ScratchDir dir;
  std::vector<cat::FixtureInfo> fixtures;
  std::vector<cat::Row> rows;
  std::set<std::string> attached;
  int n = 0;
  for (const cat::SourceFixture& fixture : cat::source_fixtures()) {
    SCOPED_TRACE(fixture.kind);
    const std::string name = "f" + std::to_string(n++);
    const cat::Conversion alone = cat::convert(dir.path(), name, fixture.text);
    ASSERT_EQ(alone.status, 0) << (alone.errors.empty() ? "" : alone.errors.front());
    const Evaluated e = evaluate(dir / (name + ".openplx"), fixture, types);
    ASSERT_FALSE(e.source_type.empty()) << "no source at " << fixture.source;
    fixtures.push_back({fixture.kind, e.source_type, fixture.source});
    for (const cat::SignalType* t : e.accepting) {
      // A fixture that sets `relative_to` is for the signals that have one.
      if (fixture.probe_lines.find("relative_to") != std::string::npos && !t->has_relative_to) continue;
      const cat::Conversion c = cat::convert(dir.path(), name + "_" + std::to_string(rows.size()),
                                             fixture.text + probe_lines(*t, fixture));
      rows.push_back({t->name, fixture.kind, cat::outcome_of(c, "probe")});
      attached.insert(t->name);
    }
  }
  for (const cat::SignalType& t : types) {
    if (attached.count(t.name)) continue;
    std::string accepts;
    for (const std::string& a : t.accepts) accepts += (accepts.empty() ? "`" : " or `") + a + "`";
    rows.push_back({t.name,
                    "",
                    {cat::Outcome::Kind::Error,
                     accepts.empty() ? "it names no source" : "no fixture's source is a " + accepts}});
  }
  const std::string document = cat::catalogue_document(types, fixtures, rows);
  const char* update = std::getenv("OPENPLX_UPDATE_CATALOGUE");
  if (update && std::string(update) == "1") {
    std::ofstream(kDocument, std::ios::binary) << document;
    std::cout << "wrote " << kDocument.string() << '\n';
    return;
  }
  const std::string checked_in = cat::detail::read_file(kDocument);
  EXPECT_TRUE(checked_in == document) << kDocument.string() << " differs from what the converter does; "
                                      << first_difference(checked_in, document)
                                      << "\nIf the change is intended, regenerate it: " << cat::kRegenerate;
}

}  // namespace
