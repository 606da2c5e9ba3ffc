// A model converted by the command line into a test's folder and loaded as a user would: plain mj_loadXML,
// its "initial" keyframe when it has one, then mj_forward. Owns the MuJoCo model and data. Header-only: for
// the test programs that link the command line (openplx_cli).
#pragma once

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <filesystem>
#include <string>

#include "tests/support/cli_run.h"

namespace openplx::testing {

struct ConvertedModel {
  std::filesystem::path xml, manifest;  // DIR/STEM.xml and DIR/STEM.signals.json
  mjModel* m = nullptr;
  mjData* d = nullptr;

  ConvertedModel(const std::filesystem::path& dir, const std::string& source, const std::string& stem = "m")
      : xml(dir / (stem + ".xml")), manifest(dir / (stem + ".signals.json")) {
    const Conversion c = cli({source, "-o", xml.string()});
    EXPECT_EQ(c.status, 0) << c.errors;
    char error[1000] = "";
    m = mj_loadXML(xml.c_str(), nullptr, error, sizeof(error));
    EXPECT_NE(m, nullptr) << error;
    if (!m) return;
    d = mj_makeData(m);
    if (const int key = mj_name2id(m, mjOBJ_KEY, "initial"); key >= 0) mj_resetDataKeyframe(m, d, key);
    mj_forward(m, d);
  }
  ConvertedModel(const ConvertedModel&) = delete;
  ConvertedModel& operator=(const ConvertedModel&) = delete;
  ~ConvertedModel() {
    if (d) mj_deleteData(d);
    if (m) mj_deleteModel(m);
  }
};

}  // namespace openplx::testing
