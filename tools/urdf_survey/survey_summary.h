// What the survey learnt about one file (read back from the child's report lines) and the tallies over a
// folder: how many files each importer loads, how many agree, and the refusal reasons grouped.
#pragma once

#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace openplx::urdf_survey {

struct FileResult {
  std::string name;  // relative to the surveyed folder
  bool ours = false, mujoco = false;
  std::string ours_reason, mujoco_reason;
  bool compared = false, mass_ok = false, pose_ok = false, inertia_ok = false;
  std::string parity;      // "ok (...)" or the mismatches
  int stubbed_meshes = 0;  // --stub-missing-meshes: how many mesh files the copy replaced
};

// Reads the child's OURS / MUJOCO / PARITY lines; whatever is missing is put down to how the child ended
// (`ending`: "crashed (signal 11)", "timeout after 120 s").
FileResult parse_report(const std::string& name, const std::string& output, const std::string& ending);

// The line printed for one file.
std::string file_line(const FileResult& r);

// A refusal reason with its particulars (paths, names, numbers) blanked, so like reasons group together.
std::string reason_group(const std::string& reason);

// The summary table and the grouped reasons for `results` (titled `title`).
void print_summary(std::ostream& out, const std::string& title, const std::vector<FileResult>& results,
                   size_t xacro_files);

}  // namespace openplx::urdf_survey
