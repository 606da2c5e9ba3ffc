// A test fixture that loads OpenPLX, assembles it and emits MJCF into the test's folder, and loads MJCF in
// MuJoCo.
#pragma once

#include <mujoco/mujoco.h>

#include <string>

#include "mjcf_emitter/emitter.h"
#include "snap/resolve_system.h"
#include "snap/snap.h"
#include "tests/support/eval_fixture.h"

namespace openplx::testing {

class MjcfTest : public EvalTest {
 protected:
  MjcfTest();
  ~MjcfTest() override;

  // Emits the loaded model into dir()/name.xml; returns the path ("" on errors).
  std::string emit(const std::string& name);
  // Loads ../shared/corpus/agxunity/<file> (root `model`, else the file's last).
  bool load_corpus(const std::string& file, const char* model = nullptr);
  // The MJCF file at `path` loaded in MuJoCo (a test failure with MuJoCo's error and nullptr when it does not
  // load); the caller deletes it.
  mjModel* load_mujoco(const std::string& path);
  // The binding the last emit made for the signal at `path` (a test failure and an empty binding if none).
  const mjcf::SignalBinding& binding(const std::string& path) const;

  snap::ResolvedSystem system_;
  snap::SnapResult snap_;
  mjcf::Emitted emitted_;
  std::string xml_;
};

}  // namespace openplx::testing
