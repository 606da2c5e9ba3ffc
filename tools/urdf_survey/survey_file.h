// One URDF through both importers: ours (the built openplx2mjcf, exactly as `openplx2mjcf FILE -o OUT
// --check`, then MuJoCo loading OUT) and MuJoCo's own URDF compiler, then the two models compared body by
// body. Runs inside a child process of the survey; it reports on standard output in lines the parent reads
// (see survey_summary.h), each written as soon as it is known, so a crash in MuJoCo's compiler still leaves
// our result behind.
#pragma once

#include <filesystem>
#include <string>

namespace openplx::urdf_survey {

struct FileOptions {
  std::string converter;  // path of openplx2mjcf
  double converter_timeout = 60;
  bool stub_missing_meshes = false;  // see stub_meshes.h
};

// Prints the OURS, MUJOCO and PARITY lines for `urdf`, using `work_dir` for the files it writes.
void survey_file(const std::filesystem::path& urdf, const std::filesystem::path& work_dir,
                 const FileOptions& options);

}  // namespace openplx::urdf_survey
