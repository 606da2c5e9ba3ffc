// urdf-survey FOLDER...: every .urdf under each folder (sorted, one child process each, with a time limit)
// through our converter and through MuJoCo's own URDF compiler, compared body by body; one report per file,
// then a summary per folder and over all of them. See docs/urdf.md.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "tools/urdf_survey/child_process.h"
#include "tools/urdf_survey/survey_file.h"
#include "tools/urdf_survey/survey_summary.h"

namespace fs = std::filesystem;
using namespace openplx::urdf_survey;

namespace {

const char* kUsage =
    "usage: urdf-survey [--timeout SECONDS] [--converter PATH] [--keep DIR] [--stub-missing-meshes] "
    "FOLDER...\n"
    "  every .urdf under each FOLDER through openplx2mjcf (FILE -o OUT --check, then MuJoCo loads OUT) and\n"
    "  through MuJoCo 2.2.2's own URDF compiler; per body: mass, principal inertia (relative 1e-9) and "
    "world\n"
    "  pose at the zero configuration (1e-9). package:// names resolve through ROS_PACKAGE_PATH as in ROS.\n"
    "  --timeout  per file, for each importer (default 120)\n"
    "  --stub-missing-meshes  give both importers a copy in which every missing mesh file is one small cube\n"
    "             (so robots shipped without meshes still compare; see stub_meshes.h)\n"
    "  --keep     write both models of every file under DIR (default: a temporary folder, removed)\n";

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g s", s);
  return text;
}

// The child's description of how it ended, for whatever it did not report.
std::string ending(const ChildResult& run, double timeout) {
  if (run.timed_out) return "timed out after " + seconds(timeout);
  if (run.signal != 0) return "crashed (signal " + std::to_string(run.signal) + ")";
  if (run.exit_code != 0) return "exited with " + std::to_string(run.exit_code);
  return "stopped";
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  FileOptions options;
  options.converter = OPENPLX2MJCF_PATH;
  double timeout = 120;
  std::string keep;
  std::vector<std::string> folders;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const bool has_value = i + 1 < args.size();
    if (a == "--one" && i + 2 < args.size()) {  // internal: the child process for one file
      for (size_t k = i + 3; k + 1 < args.size(); k += 2) {
        if (args[k] == "--converter") options.converter = args[k + 1];
        if (args[k] == "--timeout") options.converter_timeout = std::atof(args[k + 1].c_str());
        if (args[k] == "--stub-missing-meshes") options.stub_missing_meshes = args[k + 1] == "1";
      }
      survey_file(args[i + 1], args[i + 2], options);
      std::fflush(stdout);
      std::_Exit(0);  // MuJoCo's global state needs no orderly teardown
    } else if (a == "--timeout" && has_value) {
      timeout = std::atof(args[++i].c_str());
    } else if (a == "--converter" && has_value) {
      options.converter = args[++i];
    } else if (a == "--stub-missing-meshes") {
      options.stub_missing_meshes = true;
    } else if (a == "--keep" && has_value) {
      keep = args[++i];
    } else if (a == "-h" || a == "--help") {
      std::cout << kUsage;
      return 0;
    } else if (!a.empty() && a[0] == '-') {
      std::cerr << "urdf-survey: unknown option " << a << "\n" << kUsage;
      return 2;
    } else {
      folders.push_back(a);
    }
  }
  if (folders.empty() || timeout <= 0) {
    std::cerr << kUsage;
    return 2;
  }
  const fs::path self = fs::read_symlink("/proc/self/exe");
  fs::path work_root;
  if (keep.empty()) {
    std::string pattern = (fs::temp_directory_path() / "urdf-survey-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) {
      std::cerr << "urdf-survey: cannot make a temporary folder\n";
      return 1;
    }
    work_root = pattern;
  } else {
    work_root = keep;
    fs::create_directories(work_root);
  }
  std::cout << "converter: " << options.converter
            << (options.stub_missing_meshes ? "\nmissing mesh files: stubbed by a 2 cm cube in both importers"
                                            : "")
            << "\nROS_PACKAGE_PATH: "
            << (std::getenv("ROS_PACKAGE_PATH") ? std::getenv("ROS_PACKAGE_PATH") : "(unset)") << "\n";

  std::vector<FileResult> everything;
  size_t all_xacro = 0, index = 0;
  for (const std::string& folder : folders) {
    std::vector<fs::path> files;
    size_t xacro = 0;
    std::error_code ec;
    for (auto it =
             fs::recursive_directory_iterator(folder, fs::directory_options::skip_permission_denied, ec);
         it != fs::recursive_directory_iterator(); it.increment(ec)) {
      if (ec || !it->is_regular_file()) continue;
      const std::string name = lower(it->path().filename().string());
      if (lower(it->path().extension().string()) == ".urdf") files.push_back(it->path());
      if (name.find(".xacro") != std::string::npos) ++xacro;
    }
    std::sort(files.begin(), files.end());
    std::vector<FileResult> results;
    for (const fs::path& urdf : files) {
      const fs::path work = work_root / std::to_string(index++);
      fs::create_directories(work);
      const ChildResult run =
          run_child({self.string(), "--one", fs::absolute(urdf).string(), work.string(), "--converter",
                     options.converter, "--timeout", std::to_string(timeout), "--stub-missing-meshes",
                     options.stub_missing_meshes ? "1" : "0"},
                    2 * timeout + 30);
      FileResult r =
          parse_report(fs::relative(urdf, folder).string(), run.output, ending(run, 2 * timeout + 30));
      std::cout << file_line(r) << std::endl;
      results.push_back(r);
    }
    print_summary(std::cout, folder, results, xacro);
    everything.insert(everything.end(), results.begin(), results.end());
    all_xacro += xacro;
  }
  if (folders.size() > 1) print_summary(std::cout, "all folders", everything, all_xacro);
  if (keep.empty()) fs::remove_all(work_root);
  return 0;
}
