// What SignalBridge::attach refuses in a manifest edited by hand or broken in transit: a format_version that
// is no whole number of a format (1e300 converted to an int was undefined behaviour), a field of the wrong
// JSON type, a signal path listed twice, a value kind its quantity cannot give or take (a vec3 joint
// position read three numbers of which the runtime wrote one). Each is a LoadError naming the field and,
// inside a signal, its path.
#include <mujoco/mujoco.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "openplx/runtime/signal_bridge.h"
#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace fs = std::filesystem;
namespace rt = openplx::runtime;
using nlohmann::json;

// The cart-pole sample converted into `dir`, compiled, and its manifest.
class CartPole {
 public:
  explicit CartPole(const fs::path& dir) : xml_(dir / "cart_pole.xml") {
    const openplx::testing::Conversion c =
        openplx::testing::cli({std::string(OPENPLX_SAMPLES_DIR) + "/cart_pole.openplx", "-o", xml_.string()});
    EXPECT_EQ(c.status, 0) << c.errors;
    manifest_ = json::parse(std::ifstream(dir / "cart_pole.signals.json"));
    char error[1000] = "";
    m_ = mj_loadXML(xml_.c_str(), nullptr, error, sizeof(error));
    EXPECT_NE(m_, nullptr) << error;
    if (m_) d_ = mj_makeData(m_);
  }
  ~CartPole() {
    if (d_) mj_deleteData(d_);
    if (m_) mj_deleteModel(m_);
  }
  CartPole(const CartPole&) = delete;
  CartPole& operator=(const CartPole&) = delete;

  const json& manifest() const { return manifest_; }
  // The index of the first signal of `quantity`.
  size_t signal_of(const std::string& quantity) const {
    for (size_t k = 0; k < manifest_.at("signals").size(); ++k) {
      if (manifest_["signals"][k].at("quantity") == quantity) return k;
    }
    ADD_FAILURE() << "no " << quantity << " signal";
    return 0;
  }

  // Attaches `edited` (written to a file of its own); the LoadError's text, "" when it attached.
  std::string attach(const json& edited, const fs::path& file) const {
    std::ofstream(file) << edited.dump(1);
    return attach_text(file);
  }
  std::string attach_text(const fs::path& file) const {
    mjData* d = mj_makeData(m_);
    std::string error;
    try {
      rt::SignalBridge::attach(file.string(), m_, d);
    } catch (const rt::LoadError& e) {
      error = e.what();
    }
    mj_deleteData(d);
    return error;
  }

 private:
  fs::path xml_;
  json manifest_;
  mjModel* m_ = nullptr;
  mjData* d_ = nullptr;
};

#define EXPECT_REFUSED_WITH(error, text) \
  EXPECT_NE((error).find(text), std::string::npos) << "expected `" << (text) << "` in: " << (error)

TEST(ManifestFields, TheConvertedManifestAttaches) {
  const openplx::testing::ScratchDir dir;
  const CartPole sample(dir.path());
  EXPECT_EQ(sample.attach(sample.manifest(), dir / "same.signals.json"), "");
  json whole = sample.manifest();
  whole["format_version"] = 1.0;  // JSON's integers may carry a zero fraction
  EXPECT_EQ(sample.attach(whole, dir / "one_point_zero.signals.json"), "");
}

TEST(ManifestFields, AFormatVersionThatIsNoWholeNumberOfAFormatIsRefused) {
  const openplx::testing::ScratchDir dir;
  const CartPole sample(dir.path());
  const std::vector<json> versions = {1e300, 1e308, 18446744073709551616.0, -1, 1.5, 0, "1", true, nullptr};
  for (const json& version : versions) {
    json edited = sample.manifest();
    edited["format_version"] = version;
    const std::string error = sample.attach(edited, dir / "version.signals.json");
    EXPECT_REFUSED_WITH(error,
                        "version.signals.json: error: format_version must be a whole number from 1 to 1")
        << " (format_version " << version.dump() << ")";
  }
  // A whole number above this runtime's is a newer format.
  json newer = sample.manifest();
  newer["format_version"] = 7;
  EXPECT_REFUSED_WITH(sample.attach(newer, dir / "newer.signals.json"),
                      "the manifest's format_version is 7 but this runtime reads up to 1");
}

// The text itself, as another program would write it: 2^64 and 1e400 are no int64 and no double.
TEST(ManifestFields, NumbersBeyondEveryTypeAreRefused) {
  const openplx::testing::ScratchDir dir;
  const CartPole sample(dir.path());
  const std::string text = sample.manifest().dump(1);
  const std::string version = "\"format_version\": 1";
  ASSERT_NE(text.find(version), std::string::npos);
  for (const std::string written : {"18446744073709551616", "1e300", "-9223372036854775809"}) {
    std::string edited = text;
    edited.replace(edited.find(version), version.size(), "\"format_version\": " + written);
    std::ofstream(dir / "text.signals.json") << edited;
    EXPECT_REFUSED_WITH(sample.attach_text(dir / "text.signals.json"),
                        "format_version must be a whole number")
        << written;
  }
}

TEST(ManifestFields, AFieldOfTheWrongTypeIsRefusedNamingItAndTheSignal) {
  const openplx::testing::ScratchDir dir;
  const CartPole sample(dir.path());
  const size_t k = sample.signal_of("joint_position");
  const std::string path = sample.manifest()["signals"][k].at("path");
  const std::vector<std::pair<std::string, json>> edits = {
      {"sign", true}, {"initial", json::array()}, {"initial_vector", 5}, {"names", "slider"}, {"enabled", 1},
      {"low", "low"}, {"direction", "sideways"}};
  for (const auto& [field, value] : edits) {
    json edited = sample.manifest();
    edited["signals"][k][field] = value;
    const std::string error = sample.attach(edited, dir / "typed.signals.json");
    EXPECT_REFUSED_WITH(error, "signal `" + path + "`: `" + field + "`") << " (" << value.dump() << ")";
  }
  json missing = sample.manifest();
  missing["signals"][k].erase("sign");
  EXPECT_REFUSED_WITH(sample.attach(missing, dir / "missing.signals.json"),
                      "signal `" + path + "`: `sign` is missing");
  json object = sample.manifest();
  object["signals"] = json::object({{"a", object["signals"][0]}});
  EXPECT_REFUSED_WITH(sample.attach(object, dir / "object.signals.json"), "`signals` must be an array");
  json pathless = sample.manifest();
  pathless["signals"][3]["path"] = 12;
  EXPECT_REFUSED_WITH(sample.attach(pathless, dir / "pathless.signals.json"), "signal 4: `path` must be");
}

TEST(ManifestFields, ASignalPathListedTwiceIsRefused) {
  const openplx::testing::ScratchDir dir;
  const CartPole sample(dir.path());
  const size_t k = sample.signal_of("joint_velocity");
  json edited = sample.manifest();
  json copy = edited["signals"][k];
  copy["quantity"] = "joint_position";  // a different binding, the same name
  edited["signals"].push_back(copy);
  const std::string path = copy.at("path");
  EXPECT_REFUSED_WITH(sample.attach(edited, dir / "twice.signals.json"),
                      "signal `" + path + "` is listed twice");
}

TEST(ManifestFields, AValueKindItsQuantityCannotCarryIsRefused) {
  const openplx::testing::ScratchDir dir;
  const CartPole sample(dir.path());
  const std::vector<std::pair<std::string, std::string>> mismatches = {
      {"joint_position", "vec3"}, {"joint_velocity", "vec2"},      {"body_position", "real"},
      {"mate_force", "vector"},   {"interaction_enabled", "vec3"}, {"ctrl", "vec2"},
      {"constant", "vec3"}};
  for (const auto& [quantity, value] : mismatches) {
    json edited = sample.manifest();
    const size_t k = sample.signal_of(quantity);
    edited["signals"][k]["value"] = value;
    const std::string path = edited["signals"][k].at("path");
    EXPECT_REFUSED_WITH(sample.attach(edited, dir / "kind.signals.json"),
                        "signal `" + path + "`: quantity `" + quantity + "` ")
        << value;
  }
}

}  // namespace
