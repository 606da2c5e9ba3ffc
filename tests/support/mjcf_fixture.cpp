#include "tests/support/mjcf_fixture.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace openplx::testing {

MjcfTest::MjcfTest() = default;
MjcfTest::~MjcfTest() = default;

std::string MjcfTest::emit(const std::string& name) {
  system_ = snap::resolve_system(*evaluator_, root_, sink_);
  snap_ = snap::run_snap(system_, sink_);
  mjcf::EmitOptions options;
  options.model_name = evaluator_->root_name();
  options.output_dir = dir();
  emitted_ = mjcf::emit_mjcf(system_, options, sink_);
  xml_ = emitted_.document.to_string();
  const std::string path = dir() + "/" + name + ".xml";
  std::ofstream(path) << xml_;
  return path;
}

bool MjcfTest::load_corpus(const std::string& file, const char* model) {
  return load_file((std::filesystem::path(OPENPLX_CORPUS_DIR) / "agxunity" / file).string(), model);
}

mjModel* MjcfTest::load_mujoco(const std::string& path) {
  char error[1000] = "";
  mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof(error));
  EXPECT_NE(m, nullptr) << error << "\n" << xml_;
  return m;
}

const mjcf::SignalBinding& MjcfTest::binding(const std::string& path) const {
  for (const mjcf::SignalBinding& b : emitted_.signals) {
    if (b.path == path) return b;
  }
  ADD_FAILURE() << "no binding for " << path;
  static const mjcf::SignalBinding none;
  return none;
}

}  // namespace openplx::testing
