#include "tools/urdf_survey/survey_summary.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <sstream>

namespace openplx::urdf_survey {

namespace {

std::vector<std::string> split_tabs(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string field; std::getline(in, field, '\t');) fields.push_back(field);
  return fields;
}

}  // namespace

FileResult parse_report(const std::string& name, const std::string& output, const std::string& ending) {
  FileResult r;
  r.name = name;
  bool saw_ours = false, saw_mujoco = false;
  std::stringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    const std::vector<std::string> f = split_tabs(line);
    if (f.size() >= 2 && f[0] == "STUBS") {
      r.stubbed_meshes = std::atoi(f[1].c_str());
    } else if (f.size() >= 2 && f[0] == "OURS") {
      saw_ours = true;
      r.ours = f[1] == "loaded";
      r.ours_reason = f.size() > 2 ? f[2] : "";
    } else if (f.size() >= 2 && f[0] == "MUJOCO") {
      saw_mujoco = true;
      r.mujoco = f[1] == "loaded";
      r.mujoco_reason = f.size() > 2 ? f[2] : "";
    } else if (f.size() >= 6 && f[0] == "PARITY") {
      r.compared = true;
      r.mass_ok = f[2] == "1";
      r.pose_ok = f[3] == "1";
      r.inertia_ok = f[4] == "1";
      r.parity = f[1] + " (" + f[5] + ")";
    }
  }
  if (!saw_ours) r.ours_reason = "survey child " + ending + " before our converter finished";
  if (!saw_mujoco) r.mujoco_reason = "MuJoCo's compiler " + ending;
  if (saw_ours && saw_mujoco && r.ours && r.mujoco && !r.compared) r.parity = "comparison " + ending;
  return r;
}

std::string file_line(const FileResult& r) {
  std::string line = r.name;
  if (r.stubbed_meshes > 0) line += "  (" + std::to_string(r.stubbed_meshes) + " missing mesh files stubbed)";
  line += "\n    ours: " + (r.ours ? "loaded" : "refused: " + r.ours_reason);
  line += "\n    MuJoCo: " + (r.mujoco ? std::string("loaded") : "refused: " + r.mujoco_reason);
  line += "\n    parity: " + (r.parity.empty() ? std::string("n/a") : r.parity);
  return line;
}

std::string reason_group(const std::string& reason) {
  std::string text = reason;
  // Our diagnostics start with the file and position; MuJoCo's with "Error: ".
  if (size_t at = text.find(": error: "); at != std::string::npos) text = text.substr(at + 9);
  if (text.rfind("Error: ", 0) == 0) text = text.substr(7);
  // MuJoCo names the object it was compiling; which one is a particular, not a reason.
  if (size_t at = text.find(" Object name = "); at != std::string::npos) text = text.substr(0, at);
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\'' || c == '"' || c == '`') {
      const size_t close = text.find(c, i + 1);
      if (close != std::string::npos) {
        out += c;
        out += "...";
        out += c;
        i = close;
        continue;
      }
    }
    if (std::isdigit(static_cast<unsigned char>(c))) {
      while (i + 1 < text.size() &&
             (std::isdigit(static_cast<unsigned char>(text[i + 1])) || text[i + 1] == '.'))
        ++i;
      out += 'N';
      continue;
    }
    // A path (a word with a slash) says which file, not why.
    if (c == '/' && (out.empty() || out.back() == ' ')) {
      while (i + 1 < text.size() && text[i + 1] != ' ' && text[i + 1] != ':' && text[i + 1] != ',') ++i;
      out += "PATH";
      continue;
    }
    out += c;
  }
  if (out.size() > 150) out = out.substr(0, 150) + "...";
  return out;
}

namespace {

void print_groups(std::ostream& out, const std::string& title, const std::vector<std::string>& reasons) {
  if (reasons.empty()) return;
  std::map<std::string, size_t> groups;
  for (const std::string& r : reasons) ++groups[reason_group(r)];
  std::vector<std::pair<std::string, size_t>> sorted(groups.begin(), groups.end());
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  out << "  " << title << ":\n";
  for (const auto& [reason, count] : sorted) out << "    " << count << " x " << reason << "\n";
}

}  // namespace

void print_summary(std::ostream& out, const std::string& title, const std::vector<FileResult>& results,
                   size_t xacro_files) {
  size_t ours = 0, theirs = 0, both = 0, mass = 0, pose = 0, inertia = 0, all = 0, ours_only = 0,
         theirs_only = 0;
  std::vector<std::string> our_reasons, their_reasons, ours_only_reasons;
  std::vector<const FileResult*> bugs, mismatches;
  for (const FileResult& r : results) {
    ours += r.ours;
    theirs += r.mujoco;
    if (!r.ours) our_reasons.push_back(r.ours_reason);
    if (!r.mujoco) their_reasons.push_back(r.mujoco_reason);
    if (r.ours && r.mujoco) {
      ++both;
      mass += r.compared && r.mass_ok;
      pose += r.compared && r.pose_ok;
      inertia += r.compared && r.inertia_ok;
      all += r.compared && r.mass_ok && r.pose_ok && r.inertia_ok;
      if (!(r.compared && r.mass_ok && r.pose_ok && r.inertia_ok)) mismatches.push_back(&r);
    }
    if (r.ours && !r.mujoco) {
      ++ours_only;
      ours_only_reasons.push_back(r.mujoco_reason);
    }
    if (!r.ours && r.mujoco) {
      ++theirs_only;
      bugs.push_back(&r);
    }
  }
  out << "== " << title << "\n";
  out << "  files " << results.size() << " | we load " << ours << " | MuJoCo loads " << theirs
      << " | both load " << both << " | mass parity " << mass << " | pose parity " << pose
      << " | inertia parity " << inertia << " | all three " << all << " | we load, MuJoCo does not "
      << ours_only << " | MuJoCo loads, we do not " << theirs_only << " | .xacro seen (not surveyed) "
      << xacro_files << "\n";
  if (!bugs.empty()) {
    out << "  MuJoCo loads and we do not:\n";
    for (const FileResult* r : bugs) out << "    " << r->name << ": " << r->ours_reason << "\n";
  }
  if (!mismatches.empty()) {
    out << "  both load, not equal:\n";
    for (const FileResult* r : mismatches) out << "    " << r->name << ": " << r->parity << "\n";
  }
  print_groups(out, "our refusals, grouped", our_reasons);
  print_groups(out, "MuJoCo's refusals, grouped", their_reasons);
  print_groups(out, "MuJoCo's reasons where we load and it does not", ours_only_reasons);
}

}  // namespace openplx::urdf_survey
