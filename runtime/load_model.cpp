#include "runtime/load_model.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "frontend/diagnostics/diagnostics.h"
#include "frontend/pipeline.h"
#include "frontend/urdf/urdf_importer.h"
#include "mjcf_emitter/emitter.h"
#include "openplx/runtime/simulation.h"
#include "runtime/mujoco_messages.h"
#include "snap/resolve_system.h"
#include "snap/snap.h"

namespace openplx::runtime {

namespace fe = openplx::frontend;
namespace fs = std::filesystem;

std::vector<std::string>& default_bundle_dirs() {
  static std::vector<std::string> dirs;
  return dirs;
}

void add_default_bundle_dir(const std::string& dir) {
  auto& dirs = default_bundle_dirs();
  if (std::find(dirs.begin(), dirs.end(), dir) == dirs.end()) dirs.push_back(dir);
}

void add_urdf_module(const std::string& path) {
  frontend::add_urdf_module_candidate(path);
}

namespace {

// mj_loadXML reads files only: write the XML to a private temporary file, load it, remove it.
mjModel* load_xml(const std::string& xml, std::string& error) {
  std::string pattern = (fs::temp_directory_path() / "openplx-runtime-XXXXXX.xml").string();
  const int fd = ::mkstemps(pattern.data(), 4);
  if (fd < 0) {
    error = "cannot create a temporary file for the MJCF";
    return nullptr;
  }
  ::close(fd);
  std::ofstream(pattern, std::ios::binary) << xml;
  char message[1024] = "";
  mjModel* model = nullptr;
  std::string stopped;  // an mju_error inside the compiler (runtime/mujoco_messages.h)
  if (!call_mujoco(
          nullptr, [&] { model = mj_loadXML(pattern.c_str(), nullptr, message, sizeof(message)); }, stopped))
    std::snprintf(message, sizeof(message), "%s", stopped.c_str());
  std::error_code ec;
  fs::remove(pattern, ec);
  if (!model) error = message;
  return model;
}

}  // namespace

LoadedModel load_model(const std::string& path, const std::string& model,
                       const std::vector<std::string>& bundle_paths, double timestep, bool default_bundles) {
  fe::SourceManager sources;
  fe::DiagnosticSink sink;
  fe::LoadRequest request;
  request.path = path;
  if (!model.empty()) request.model = model;
  request.bundle_dirs = bundle_paths;
  request.default_bundles = default_bundles;
  if (default_bundles) {
    for (const std::string& dir : default_bundle_dirs()) request.bundle_dirs.push_back(dir);
  }
  fe::Evaluation evaluation = fe::evaluate_file(request, sources, sink);
  LoadedModel loaded;
  mjcf::Emitted emitted;
  if (evaluation.root != fe::kNoObject && !sink.has_errors()) {
    snap::ResolvedSystem system = snap::resolve_system(*evaluation.evaluator, evaluation.root, sink);
    snap::run_snap(system, sink);
    mjcf::EmitOptions options;
    options.model_name = evaluation.evaluator->root_name();
    options.timestep = timestep;
    emitted = mjcf::emit_mjcf(system, options, sink);
    loaded.root_name = options.model_name;
  }
  for (const fe::Diagnostic& d : sink.diagnostics()) {
    std::ostringstream text;
    fe::print_diagnostic(text, sources, d);
    if (d.severity != fe::Severity::Error) loaded.warnings.push_back(text.str());
  }
  if (sink.has_errors() || evaluation.root == fe::kNoObject) {
    std::ostringstream text;
    fe::print_diagnostics(text, sources, sink.diagnostics());
    throw LoadError(text.str().empty() ? path + ": error: the model could not be loaded\n" : text.str());
  }
  for (size_t id = 0; id < sources.size(); ++id) {
    const std::string& file = sources.file(static_cast<fe::FileId>(id)).path();
    if (!file.empty() && file.front() != '<') loaded.files_read.push_back(file);  // not "<builtin>"
  }
  for (const mjcf::ConvertedMesh& mesh : emitted.converted_meshes) loaded.files_read.push_back(mesh.source);
  std::vector<const mjcf::Element*> elements{&emitted.document};
  while (!elements.empty()) {  // the assets MuJoCo reads itself (absolute paths)
    const mjcf::Element* e = elements.back();
    elements.pop_back();
    if (const std::string* file = e->get("file")) loaded.files_read.push_back(*file);
    for (const auto& child : e->children()) elements.push_back(child.get());
  }
  loaded.xml = emitted.document.to_string();
  loaded.signals = std::move(emitted.signals);
  loaded.laws = std::move(emitted.laws);
  std::string error;
  loaded.model = load_xml(loaded.xml, error);
  if (!loaded.model) throw LoadError(path + ": error: MuJoCo rejected the emitted MJCF: " + error + "\n");
  return loaded;
}

}  // namespace openplx::runtime
