#include "frontend/natives/host_declarations.h"

#include <array>
#include <cstdint>

namespace openplx::natives {
namespace {

// Found by tests/frontend/release_0_20_2_test.cpp (HostDeclaresExactlyWhatTheReleaseLeavesUndeclared): with
// these off, resolving every model, trait and member type of the 0.20.2 release's 477 files leaves these two
// names unknown, and nothing else. (Evaluating each of its models as the root adds none.)
constexpr std::array<HostDeclaration, 2> kRelease0_20 = {{
    // As in our Physics bundle: an empty model that MateConnector (Physics1D and Physics3D) extends and
    // `Interaction.connectors` holds.
    {"Physics.Interactions", "Connector",
     "# Declared by the host for bundle releases 0.20: the base of everything an interaction attaches to.\n"
     "Connector\n"},
    // `Sensors.Signals.SensorOutputSignal.data is Blob: {}`: AGX's opaque buffer for sensor data that the
    // runtime fills. No member of it is read while a model is converted.
    {"", "Blob",
     "# Declared by the host for bundle releases 0.20: an opaque block of data (a sensor's output).\n"
     "Blob\n"},
}};

constexpr std::array<HostGeneration, 1> kGenerations = {{
    {"0.20", kRelease0_20},
}};

int64_t next_number(std::string_view& v) {
  int64_t n = 0;
  size_t i = 0;
  for (; i < v.size() && v[i] != '.'; ++i) {
    if (v[i] >= '0' && v[i] <= '9' && n < (int64_t{1} << 50)) n = n * 10 + (v[i] - '0');
  }
  v.remove_prefix(i < v.size() ? i + 1 : i);
  return n;
}

}  // namespace

int compare_versions(std::string_view a, std::string_view b) {
  while (!a.empty() || !b.empty()) {
    const int64_t x = next_number(a), y = next_number(b);
    if (x != y) return x < y ? -1 : 1;
  }
  return 0;
}

std::span<const HostGeneration> host_generations() {
  return kGenerations;
}

const HostGeneration& host_generation(std::string_view version) {
  const HostGeneration* found = &kGenerations.front();
  for (const HostGeneration& generation : kGenerations) {
    if (compare_versions(generation.first_version, version) <= 0) found = &generation;
  }
  return *found;
}

const HostDeclaration* find_host_declaration(std::string_view version, std::string_view ns,
                                             std::string_view name) {
  for (const HostDeclaration& declaration : host_generation(version).declarations) {
    if (declaration.ns == ns && declaration.name == name) return &declaration;
  }
  return nullptr;
}

}  // namespace openplx::natives
