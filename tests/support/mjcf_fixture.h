// A test fixture that loads OpenPLX, assembles it and emits MJCF into the test's folder, and loads MJCF in
// MuJoCo.
#pragma once

#include <mujoco/mujoco.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "mjcf_emitter/emitter.h"
#include "snap/resolve_system.h"
#include "snap/snap.h"
#include "tests/support/eval_fixture.h"

namespace openplx::testing {

class MjcfTest : public EvalTest {
 protected:
  // Emits the loaded model into dir()/name.xml; returns the path ("" on errors).
  std::string emit(const std::string& name) {
    view_ = snap::resolve_system(*evaluator_, root_, sink_);
    snap_ = snap::run_snap(view_, sink_);
    mjcf::EmitOptions options;
    options.model_name = evaluator_->root_name();
    options.output_dir = dir();
    emitted_ = mjcf::emit_mjcf(view_, options, sink_);
    xml_ = emitted_.document.to_string();
    const std::string path = dir() + "/" + name + ".xml";
    std::ofstream(path) << xml_;
    return path;
  }
  // Loads ../shared/corpus/agxunity/<file> (root `model`, else the file's last).
  bool load_corpus(const std::string& file, const char* model = nullptr) {
    return load_file((std::filesystem::path(OPENPLX_CORPUS_DIR) / "agxunity" / file).string(), model);
  }
  mjModel* load_mujoco(const std::string& path) {
    char error[1000] = "";
    mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof(error));
    EXPECT_NE(m, nullptr) << error << "\n" << xml_;
    return m;
  }
  // The binding the last emit made for the signal at `path` (a test failure and an empty binding if none).
  const mjcf::SignalBinding& binding(const std::string& path) const {
    for (const mjcf::SignalBinding& b : emitted_.signals) {
      if (b.path == path) return b;
    }
    ADD_FAILURE() << "no binding for " << path;
    static const mjcf::SignalBinding none;
    return none;
  }

  snap::ResolvedSystem view_;
  snap::SnapResult snap_;
  mjcf::Emitted emitted_;
  std::string xml_;
};

}  // namespace openplx::testing
