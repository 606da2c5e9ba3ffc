#include "tools/cli/cli.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string_view>

#include "frontend/bundles/bundles.h"
#include "frontend/diagnostics/diagnostics.h"
#include "frontend/evaluation/evaluator.h"
#include "frontend/evaluation/value_format.h"
#include "frontend/pipeline.h"
#include "frontend/semantics/program.h"
#include "frontend/syntax/ast_dump.h"
#include "frontend/syntax/lexer.h"
#include "frontend/syntax/parser.h"
#include "mjcf_emitter/check.h"
#include "mjcf_emitter/document_fingerprint.h"
#include "mjcf_emitter/emitter.h"
#include "mjcf_emitter/mesh_files.h"
#include "mjcf_emitter/mujoco3_collision.h"
#include "mjcf_emitter/timestep_dependence.h"
#include "snap/resolve_system.h"
#include "snap/snap.h"
#include "snap/snap_dump.h"
#include "tools/cli/atomic_file.h"
#include "tools/cli/crash_cleanup.h"
#include "tools/cli/depfile.h"
#include "tools/cli/memory/conversion_memory.h"
#include "tools/cli/output_set.h"

#ifndef OPENPLX_VERSION
#define OPENPLX_VERSION "0.0.0"
#endif

namespace openplx::cli {
namespace {

namespace fe = openplx::frontend;

// Matches `--name VALUE`, `--name=VALUE` and, for one-letter options, `-xVALUE`.
bool take_value(const std::vector<std::string>& args, size_t& i, std::string_view long_name,
                std::string_view short_name, std::string& value, std::string& error, bool& matched) {
  const std::string& arg = args[i];
  matched = false;
  for (std::string_view name : {long_name, short_name}) {
    if (name.empty()) continue;
    if (arg == name) {
      matched = true;
      if (i + 1 >= args.size()) {
        error = "option " + std::string(name) + " needs a value";
        return false;
      }
      value = args[++i];
      return true;
    }
    const bool is_long = name.size() > 2;
    std::string prefix = std::string(name) + (is_long ? "=" : "");
    if (arg.size() > prefix.size() && arg.compare(0, prefix.size(), prefix) == 0) {
      matched = true;
      value = arg.substr(prefix.size());
      return true;
    }
  }
  return true;
}

// Why `prefix` cannot begin MuJoCo names ("" when it can): they are written into XML attributes and the
// manifest's JSON strings, and neither carries control characters (XML 1.0 cannot hold most of them at all)
// or bytes that are not UTF-8. Printable characters, unicode letters among them, are escaped where needed.
std::string prefix_problem(const std::string& prefix) {
  auto hex = [](unsigned value, int digits) {
    char text[16];
    std::snprintf(text, sizeof(text), "%0*X", digits, value);
    return std::string(text);
  };
  for (size_t at = 0; at < prefix.size();) {
    const auto lead = static_cast<unsigned char>(prefix[at]);
    // The sequence's length and its smallest code point (shorter forms are not UTF-8).
    const size_t length = lead < 0x80           ? 1
                          : (lead >> 5) == 0x6  ? 2
                          : (lead >> 4) == 0xE  ? 3
                          : (lead >> 3) == 0x1E ? 4
                                                : 0;
    unsigned code = length == 1   ? lead
                    : length == 2 ? lead & 0x1Fu
                    : length == 3 ? lead & 0x0Fu
                                  : lead & 0x07u;
    bool utf8 = length > 0 && at + length <= prefix.size();
    for (size_t k = 1; utf8 && k < length; ++k) {
      const auto next = static_cast<unsigned char>(prefix[at + k]);
      utf8 = (next & 0xC0) == 0x80;
      code = code << 6 | (next & 0x3Fu);
    }
    const unsigned least = length == 2 ? 0x80 : length == 3 ? 0x800 : length == 4 ? 0x10000 : 0;
    if (!utf8 || code < least || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF))
      return "holds byte 0x" + hex(lead, 2) + " (at " + std::to_string(at) + "), which is not UTF-8 text";
    if (code < 0x20 || (code >= 0x7F && code <= 0x9F) || code == 0xFFFE || code == 0xFFFF) {
      return "holds the character U+" + hex(code, 4) + " (at byte " + std::to_string(at) +
             "), which is no printable character: MuJoCo names go into XML and JSON, which carry printable "
             "characters only";
    }
    at += length;
  }
  return "";
}

bool write_mesh_files(const std::string& output, const std::vector<mjcf::MeshFile>& files,
                      std::vector<std::filesystem::path>& written, std::string& error);
void remove_written(const std::vector<std::filesystem::path>& written);

// What --check loads, in the output's folder (so relative paths resolve as in the output): the MJCF, and
// with -o FILE its converted meshes as the files written beside it, in a folder of the check's own so that
// the output's are not touched before the check passes. Named for this process and call; removed, files
// before their folder, when it goes away, whatever the check found.
class CheckFiles {
 public:
  explicit CheckFiles(const std::filesystem::path& dir) {
    static std::atomic<unsigned> counter{0};  // the pid keeps processes apart, this threads and calls
    base_ = dir / (".openplx2mjcf-check-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  }
  ~CheckFiles() {
    crash_cleanup_.reset();
    remove_written(written_);
  }
  CheckFiles(const CheckFiles&) = delete;
  CheckFiles& operator=(const CheckFiles&) = delete;

  std::string xml() const { return base_.string() + ".xml"; }

  // `xml` is `document` printed; with mesh files, the document is printed again naming the check's copies,
  // then named the output's again.
  bool write(const std::string& xml, mjcf::Element& document, std::vector<mjcf::MeshFile>& meshes,
             std::string& error) {
    if (meshes.empty()) return write_xml(xml, error);
    const std::string folder = std::filesystem::path(meshes.front().path).parent_path().generic_string();
    mjcf::move_mesh_folder(document, meshes, base_.filename().string() + ".meshes");
    const bool written =
        write_mesh_files(this->xml(), meshes, written_, error) && write_xml(document.to_string(), error);
    mjcf::move_mesh_folder(document, meshes, folder);
    return written;
  }

  // From here on a crash inside MuJoCo removes the files too.
  void guard_against_crashes() { crash_cleanup_.emplace(written_); }

 private:
  bool write_xml(const std::string& text, std::string& error) {
    if (!write_file_atomically(xml(), text, error)) {
      error = xml() + ": " + error;
      return false;
    }
    written_.emplace_back(xml());
    return true;
  }

  std::filesystem::path base_;
  std::vector<std::filesystem::path> written_;
  std::optional<CrashCleanup> crash_cleanup_;
};

bool progress_on_terminal = false;  // show_progress_on_terminal(): stderr is a terminal someone watches

// --check's simulation, told on one line rewritten in place ("\r") at most four times a second, for a person
// at a terminal: a long --check-time can take minutes. Nothing at all in a pipe or a file, where the line
// would be noise, and nothing for a run shorter than a quarter of a second. The line is blanked at the end
// so that the diagnostics start on a clean one.
class CheckProgress {
 public:
  explicit CheckProgress(std::ostream& err) : err_(err) {}
  ~CheckProgress() {
    if (width_) err_ << '\r' << std::string(width_, ' ') << '\r' << std::flush;
  }
  CheckProgress(const CheckProgress&) = delete;
  CheckProgress& operator=(const CheckProgress&) = delete;

  bool shown() const { return progress_on_terminal; }
  void show(double done, double total) {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < std::chrono::milliseconds(250)) return;
    last_ = now;
    char line[96];
    const int n = std::snprintf(line, sizeof line, "--check: simulated %.1f of %g s", done, total);
    if (n <= 0) return;
    const size_t width = std::min(static_cast<size_t>(n), sizeof line - 1);
    err_ << '\r' << line << std::string(width_ > width ? width_ - width : 0, ' ') << std::flush;
    width_ = std::max(width_, width);
  }

 private:
  std::ostream& err_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
  size_t width_ = 0;  // the longest line shown, 0: none
};

// --check: the emitted XML loaded by MuJoCo itself must put every body where SNAP did, start with no
// collision geometry overlapping, and run for --check-time seconds from its initial state without MuJoCo
// finding it unstable. Findings land at the joint's or body's declaration, else at the root model's. What
// is checked is what is written: `xml` (converted meshes inline), or with `mesh_files` the document naming
// them as files.
void check(const CliOptions& options, const std::string& xml, mjcf::Element& document,
           std::vector<mjcf::MeshFile>& mesh_files, const mjcf::EmitOptions& emit_options,
           const snap::ResolvedSystem& system, const snap::SnapResult& assembled,
           const fe::Evaluation& evaluation, fe::DiagnosticSink& sink, std::ostream& err) {
  namespace fs = std::filesystem;
  // Beside the output (so relative mesh paths resolve), else in the temporary folder.
  CheckFiles files(emit_options.output_dir.empty() ? fs::temp_directory_path()
                                                   : fs::path(emit_options.output_dir));
  const fe::SourceFile& source = evaluation.program->sources().file(evaluation.document->doc.file);
  fe::SourceRange at_root{evaluation.document->doc.file, source.content_begin(), source.content_begin()};
  if (system.root >= 0 && system.nodes[static_cast<size_t>(system.root)].where.file != fe::kNoFile)
    at_root = system.nodes[static_cast<size_t>(system.root)].where;
  // A URDF given directly: the root is declared in a generated one-line document, so what concerns the whole
  // robot goes to the URDF's <robot>, where the imported model's declaration came from.
  if (evaluation.program->urdf_given_directly() && evaluation.root != fe::kNoObject) {
    const fe::SourceManager& sources = evaluation.program->sources();
    for (const fe::ModelInfo* m : evaluation.evaluator->graph().at(evaluation.root).type->linearization()) {
      if (!m->decl || sources.user_range(m->decl->range).file == m->decl->range.file) continue;
      at_root = m->decl->range;
      break;
    }
  }
  auto at = [&](const fe::SourceRange& where) { return where.file != fe::kNoFile ? where : at_root; };
  // --check runs MuJoCo 2.2.2: --mujoco 3's collision settings, which 2.2.2 rejects, stay out of what it
  // loads (without them 2.2.2 collides as they make 3.x do).
  const mjcf::Mujoco3SettingsSetAside for_2_2(document);
  std::string error;
  if (!files.write(for_2_2.any() ? document.to_string() : xml, document, mesh_files, error)) {
    sink.report(fe::DiagCode::MjcfCheckFailed, at_root, "--check cannot write its files: " + error);
    return;
  }
  files.guard_against_crashes();
  mjcf::CheckOptions check_options;
  check_options.simulate_time = options.check_time;
  check_options.emitted_timestep = options.timestep;
  CheckProgress progress(err);
  if (progress.shown())
    check_options.progress = [&](double done, double total) { progress.show(done, total); };
  mjcf::CheckResult result = mjcf::check_mjcf(files.xml(), system, assembled, options.prefix,
                                              evaluation.evaluator->root_name(), check_options);
  if (!result.loaded) {
    sink.report(fe::DiagCode::MjcfCheckFailed, at(result.load_error_where),
                "MuJoCo rejects the emitted MJCF: " + result.load_error);
    return;
  }
  for (size_t k = 0; k < result.problems.size(); ++k) {
    const fe::SourceRange where = k < result.problem_where.size() ? result.problem_where[k] : at_root;
    sink.report(fe::DiagCode::MjcfCheckFailed, at(where), "--check: " + result.problems[k]);
  }
  for (const mjcf::LocatedProblem& p : result.mujoco_warnings)
    sink.report(fe::DiagCode::MuJoCoWarning, at(p.where), p.message);
  for (const mjcf::LocatedProblem& p : result.overlap_reports)
    sink.report(fe::DiagCode::MjcfInitialOverlap, at(p.where), p.message);
  for (const mjcf::LocatedProblem& p : result.instabilities)
    sink.report(fe::DiagCode::MjcfUnstable, at(p.where), p.message);
}

// --check-time's bound: a check is for catching a model that blows up, not for running it.
constexpr double kMaxCheckTime = 100;

bool ending_after_run = false;  // end_process_after_run(): the process exits as soon as run() returns

// Hands `object` to the process's exit instead of freeing it piece by piece (tens of thousands of objects
// for a large model) when nothing runs after run().
template <typename T>
void leave_to_exit(T&& object) {
  if (ending_after_run) (void)new std::decay_t<T>(std::forward<T>(object));
}

// OPENPLX_TIMINGS=1 prints each pass's wall-clock time to stderr: where a user's conversion time goes.
class PassTimer {
 public:
  void lap(const char* pass, size_t objects = 0) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    std::cerr << "openplx2mjcf: " << pass << ' '
              << std::chrono::duration<double, std::milli>(now - last_).count() << " ms";
    if (objects) std::cerr << " (" << objects << " objects)";
    std::cerr << '\n';
    last_ = now;
  }

 private:
  bool enabled_ = std::getenv("OPENPLX_TIMINGS") != nullptr;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// What a conversion with -o writes: the MJCF, and what the signal manifest beside it is written from.
struct Converted {
  std::string xml;
  std::string model_name;
  std::string prefix;
  double timestep = 0;                     // the one the model was emitted for, recorded in the manifest
  std::string mujoco;                      // the MuJoCo its numbers are for (--mujoco), recorded there too
  std::optional<mjcf::Emitted> emitted;    // its signals and laws
  std::vector<mjcf::MeshFile> mesh_files;  // converted meshes, written beside it (mjcf_emitter/mesh_files.h)
  std::vector<std::string> asset_inputs;   // the mesh and texture files it reads (--depfile)
};

// Writes the converted meshes into their folder beside the output, each whole or not at all. `written` gets
// the files written (and the folder, when it was made here) so that a later failure can take them back.
bool write_mesh_files(const std::string& output, const std::vector<mjcf::MeshFile>& files,
                      std::vector<std::filesystem::path>& written, std::string& error) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::absolute(output).parent_path();
  for (const mjcf::MeshFile& file : files) {
    const fs::path path = dir / file.path, folder = path.parent_path();
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) {
      if (!fs::create_directory(folder, ec)) {
        error = "cannot create the mesh folder " + folder.string() + ": " + ec.message();
        return false;
      }
      written.push_back(folder);
    }
    if (!write_file_atomically(path.string(), file.bytes, error)) {
      error = path.string() + ": " + error;
      return false;
    }
    written.push_back(path);
  }
  return true;
}

// Takes back what write_mesh_files wrote, files before their folder.
void remove_written(const std::vector<std::filesystem::path>& written) {
  for (auto it = written.rbegin(); it != written.rend(); ++it) {
    std::error_code ec;
    std::filesystem::remove(*it, ec);  // a folder only if empty
  }
}

// The whole conversion: loads the file with its bundles, picks the root model, evaluates it, resolves the
// system, assembles it (SNAP) and emits the MJCF (and --check's run, --dump's text). False when the file
// cannot be read.
bool convert(const CliOptions& options, fe::SourceManager& sources, fe::DiagnosticSink& sink,
             std::ostream& text, Converted& converted, std::ostream& err) {
  PassTimer timer;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(options.input, ec)) {
    err << options.input << ": error: "
        << (std::filesystem::is_directory(options.input, ec) ? "is a directory, not a file"
                                                             : "cannot open file")
        << " [" << fe::code_name(fe::DiagCode::IoError) << "]\n";
    return false;
  }
  if (ending_after_run) {
    const uintmax_t size = std::filesystem::file_size(options.input, ec);
    if (!ec) prepare_memory_for_input(size);
  }
  fe::LoadRequest request{options.input, options.model, options.bundle_dirs, std::nullopt};
  request.default_bundles = options.default_bundles;
  fe::Evaluation evaluation = fe::evaluate_file(request, sources, sink);
  timer.lap("load and evaluate", evaluation.evaluator ? evaluation.evaluator->graph().objects.size() : 0);
  if (evaluation.root == fe::kNoObject || sink.has_errors()) return true;
  if (options.dump == DumpKind::Values) {
    evaluation.evaluator->evaluate_all(evaluation.root);  // every value printed, read or not
    fe::dump_values(text, *evaluation.evaluator, evaluation.root);
  }
  // Assembly is part of checking a model, so it runs whether or not its frames are printed.
  snap::ResolvedSystem system = snap::resolve_system(*evaluation.evaluator, evaluation.root, sink);
  timer.lap("resolve system", evaluation.evaluator->graph().objects.size());
  const snap::SnapResult& assembled = snap::run_snap(system, sink);
  timer.lap("snap");
  if (options.dump == DumpKind::Snap)
    snap::dump_snap(text, system, assembled, evaluation.evaluator->root_name());
  if (options.dump != DumpKind::None || sink.has_errors()) return true;
  namespace fs = std::filesystem;
  const bool to_file = options.output && *options.output != "-";
  mjcf::EmitOptions emit_options;
  emit_options.model_name = evaluation.evaluator->root_name();
  emit_options.prefix = options.prefix;
  emit_options.timestep = options.timestep;
  emit_options.keyframe = options.keyframe;
  // A file without a keyframe is made for inclusion: the scene lights it (docs/decisions.md "Scenes").
  emit_options.light = options.lights.value_or(options.keyframe);
  emit_options.manifest_text = false;  // written to its file in pieces (write_manifest)
  emit_options.mujoco = options.mujoco3 ? mjcf::EmitOptions::MuJoCo::V3 : mjcf::EmitOptions::MuJoCo::V2;
  emit_options.exclude_initial_overlaps = options.exclude_initial_overlaps;
  emit_options.urdf_exact_mesh_mass = options.urdf_exact_mesh_mass;
  emit_options.collada_up_axis = options.collada_up_axis;
  if (to_file)
    emit_options.output_dir = fs::absolute(*options.output).parent_path().lexically_normal().generic_string();
  mjcf::Emitted emitted = mjcf::emit_mjcf(system, emit_options, sink);
  timer.lap("emit");
  if (sink.has_errors()) return true;
  // What the MJCF reads, taken while converted meshes are inline: their sources are the files read (for
  // --depfile, and so that no output replaces one of them).
  if (to_file) {
    converted.asset_inputs = files_the_mjcf_reads(emitted.document, emit_options.output_dir);
    for (const mjcf::ConvertedMesh& mesh : emitted.converted_meshes)
      converted.asset_inputs.push_back(fs::absolute(mesh.source).lexically_normal().string());
  }
  // Written to a file, converted meshes go into files beside it, and --check loads those files: MuJoCo
  // 2.2.2 can take a mesh from one form and not the other. --pose touches no asset, so the order is free.
  if (to_file && !emitted.converted_meshes.empty())
    converted.mesh_files = mjcf::move_meshes_to_files(emitted, mjcf::mesh_folder_for(*options.output));
  std::string xml = emitted.document.to_string();
  timer.lap("print xml");
  if (options.check)
    check(options, xml, emitted.document, converted.mesh_files, emit_options, system, assembled, evaluation,
          sink, err);
  if (!options.output) return true;  // without -o the model is only checked
  if (options.pose) {
    mjcf::place_model(emitted.document, *options.pose);
    xml = emitted.document.to_string();
  }
  converted.xml = std::move(xml);
  converted.model_name = emit_options.model_name;
  converted.prefix = emit_options.prefix;
  converted.timestep = emit_options.timestep;
  converted.mujoco = options.mujoco3 ? "3" : "2.2.2";
  converted.emitted = std::move(emitted);
  leave_to_exit(std::move(system));
  leave_to_exit(std::move(evaluation));
  return true;
}

// Every file of a run with -o FILE as one set (output_set.h): none of them a file the run read or another
// of them, each written to a temporary first and all renamed only when every one was written. Reports at the
// output concerned and returns false when nothing was written.
bool write_outputs(const CliOptions& options, const fe::SourceManager& sources, const Converted& converted,
                   const std::string& dump, std::ostream& err) {
  namespace fs = std::filesystem;
  const std::string& output = *options.output;
  auto fail = [&](const std::string& where, const std::string& message) {
    err << where << ": error: " << message << " [" << fe::code_name(fe::DiagCode::IoError) << "]\n";
    return false;
  };
  std::vector<std::string> read = source_files(sources);
  read.insert(read.end(), converted.asset_inputs.begin(), converted.asset_inputs.end());
  read.push_back(fs::absolute(options.input).lexically_normal().string());
  const fs::path dir = fs::absolute(output).parent_path();
  std::vector<NamedOutput> outputs{{output, "-o"}};
  if (converted.emitted) outputs.push_back({manifest_path(output), "the signal manifest"});
  if (!converted.mesh_files.empty())
    outputs.push_back({(dir / fs::path(converted.mesh_files.front().path).parent_path()).string(),
                       "the converted meshes' folder"});
  for (const mjcf::MeshFile& file : converted.mesh_files)
    outputs.push_back({(dir / file.path).string(), "a converted mesh"});
  if (options.depfile) outputs.push_back({*options.depfile, "--depfile"});
  std::string bad;
  if (const std::string clash = outputs_clash(outputs, read, bad); !clash.empty()) return fail(bad, clash);
  std::string depfile, error;
  if (options.depfile && !depfile_text(output, read, depfile, error)) return fail(*options.depfile, error);

  OutputSet set;
  // Meshes first and the MJCF after them: the renames go in this order, so the MJCF never names a file not
  // yet there.
  for (const mjcf::MeshFile& file : converted.mesh_files) {
    const fs::path path = dir / file.path;
    if (!set.folder(path.parent_path(), error)) return fail(path.parent_path().string(), error);
    if (!set.stage(path, file.bytes, error)) return fail(path.string(), error);
  }
  if (!set.stage(output, converted.xml.empty() ? dump : converted.xml, error)) return fail(output, error);
  if (converted.emitted) {
    const std::string manifest = manifest_path(output);
    if (!set.stage(
            manifest,
            [&](const PieceWriter& write) {
              // The fingerprint lets a SignalBridge refuse a model this manifest was not written for.
              const mjcf::ManifestModel model{
                  mjcf::model_fingerprint(converted.emitted->document, converted.prefix).text(),
                  converted.timestep, converted.mujoco,
                  mjcf::timestep_choices(converted.emitted->document, converted.emitted->laws)};
              mjcf::write_manifest_json(converted.model_name, converted.prefix, converted.emitted->signals,
                                        converted.emitted->laws, model, write);
            },
            error))
      return fail(manifest, error);
  }
  if (options.depfile && !set.stage(*options.depfile, depfile, error)) return fail(*options.depfile, error);
  if (!set.commit(error)) return fail(output, error);
  return true;
}

}  // namespace

void end_process_after_run() {
  ending_after_run = true;
}

void show_progress_on_terminal() {
  progress_on_terminal = ::isatty(STDERR_FILENO) == 1;
}

std::string manifest_path(const std::string& output) {
  std::filesystem::path path(output);
  if (path.extension() == ".xml") path.replace_extension();
  return path.string() + ".signals.json";
}

std::string usage() {
  return "usage: openplx2mjcf FILE [-o OUT|-] [--model NAME] [-B DIR]... [--prefix P] [--pose POSE]\n"
         "                    [--no-keyframe] [--lights auto|on|off] [--timestep S] [--mujoco 2.2|3]\n"
         "                    [--no-default-bundles]\n"
         "                    [--strict] [--check] [--check-time T] [--exclude-initial-overlaps]\n"
         "                    [--urdf-exact-mesh-mass] [--collada-up-axis] [--depfile DEP]\n"
         "                    [--dump=tokens|ast|values|snap]\n"
         "                    [--help] [--version] [--]\n"
         "\n"
         "Reads an OpenPLX model (or a URDF), evaluates and assembles it, and with -o writes MuJoCo MJCF\n"
         "to OUT with the signal manifest OUT.signals.json beside it. Without -o nothing is written: the\n"
         "model is only converted and its diagnostics printed (a check). With --dump, prints an\n"
         "intermediate form instead.\n"
         "\n"
         "  -o, --output OUT  write the MJCF to OUT and the manifest to OUT.signals.json ('.xml' replaced);\n"
         "                 '-' writes the MJCF to stdout and no manifest. Default: nothing is written.\n"
         "                 All outputs are written or none, and never over a file the run read\n"
         "  --model NAME   the root model (default: the last model in FILE)\n"
         "  -B, --bundle-path DIR  an extra bundle directory (repeatable)\n"
         "  --no-default-bundles  only the bundles of -B and OPENPLX_BUNDLE_PATH (e.g. an AGX "
         "installation's)\n"
         "  --prefix P     prepend P to every MuJoCo name, so that copies can share a scene\n"
         "  --pose POSE    place the model in a bigger scene: 'x y z' or 'x y z qw qx qy qz' moves its\n"
         "                 top-level bodies (free, jointed and static), the world's geoms and sites, "
         "anchors\n"
         "                 in world coordinates and free bodies' keyframe velocities (default: as modelled)\n"
         "  --no-keyframe  no \"initial\" keyframe, for a file <include>d into a bigger scene: MuJoCo\n"
         "                 checks a keyframe against the whole scene, and an included file's keyframe has\n"
         "                 its own model's sizes (MuJoCo rejects the scene: 'invalid ctrl size'); a\n"
         "                 SignalBridge sets the initial controls instead\n"
         "  --lights L     auto (default), on or off: a directional light when the model has none. auto is\n"
         "                 on, but off with --no-keyframe: an included file leaves lighting to its scene\n"
         "                 (each file's light would add to the scene's)\n"
         "  --timestep S   MuJoCo's time step in seconds (default 0.002; OpenPLX has no setting for it)\n"
         "  --mujoco V     2.2 (default) or 3: the MuJoCo whose soft-weld laws set flexible loop closures'\n"
         "                 numbers; 3 also writes <flag nativeccd=\"disable\"/> so that 3.x collides as\n"
         "                 2.2.2 does, and only 3.x loads that file (--check loads it without the flag)\n"
         "  --strict       treat warnings as errors\n"
         "  --check        load the MJCF with MuJoCo and compare every body with its SNAP pose, list\n"
         "                 collision geometry that overlaps at the start, then simulate the model from its\n"
         "                 initial state and report where MuJoCo finds it unstable (an error); the model is\n"
         "                 checked where it was modelled, before --pose\n"
         "  --check-time T how long --check simulates, in seconds (default 1; at most 100)\n"
         "  --exclude-initial-overlaps  exclude contacts between bodies whose collision geometry overlaps\n"
         "                 at the start (<contact><exclude>), for parts meant to overlap\n"
         "  --urdf-exact-mesh-mass  a URDF link without <inertial> takes the exact volume of its collision\n"
         "                 meshes (default: MuJoCo's URDF importer's mass, its legacy mesh volumes)\n"
         "  --collada-up-axis  turn a COLLADA mesh's <up_axis> onto +Z, as the COLLADA standard defines\n"
         "                 (default, or --collada-ignore-up-axis: its coordinates as written, as RViz and\n"
         "                 Gazebo show them; a note names each file whose <up_axis> is not Z_UP)\n"
         "  --depfile DEP  with -o OUT: write DEP, a Make-style dependency file naming every file read\n"
         "                 (the model, OpenPLX files and bundles, URDFs, meshes, textures), for build\n"
         "                 systems (CMake's openplx2mjcf_add_model uses it), escaped for Make and Ninja; a\n"
         "                 name they cannot read (a newline, * ? \" | ( = ; ...) is refused\n"
         "  --dump=KIND    print tokens | ast | values | snap (world frames after assembly) to stdout, or\n"
         "                 to OUT with -o\n"
         "  -h, --help     show this text\n"
         "  --version      show the version\n"
         "  --             what follows is the input file, even if it starts with '-'\n"
         "\n"
         "An <include>d file brings its <option> (time step, gravity, integrator, solver settings) into\n"
         "the scene, overriding the scene's own <option> given before the include (one given after wins):\n"
         "emit with the scene's --timestep. Its <compiler angle=\"radian\"> holds for the whole scene\n"
         "wherever it stands: the scene's own euler/axisangle angles are read in radians too.\n"
         "\n"
         "Exit status: 0 success, 1 errors in the input, 2 usage errors.\n";
}

std::optional<CliOptions> parse_options(const std::vector<std::string>& args, std::string& error) {
  CliOptions options;
  bool inputs_done = false;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    std::string value;
    bool matched = false;
    if (!inputs_done && arg == "--") {
      inputs_done = true;
      continue;
    }
    if (inputs_done || arg.empty() || arg[0] != '-' || arg == "-") {
      if (!options.input.empty()) {
        error = "only one input file is allowed (got '" + options.input + "' and '" + arg + "')";
        return std::nullopt;
      }
      options.input = arg;
      continue;
    }
    if (arg == "--help" || arg == "-h") {
      options.help = true;
      continue;
    }
    if (arg == "--version") {
      options.version = true;
      continue;
    }
    if (arg == "--strict") {
      options.strict = true;
      continue;
    }
    if (arg == "--no-default-bundles") {
      options.default_bundles = false;
      continue;
    }
    if (arg == "--no-keyframe") {
      options.keyframe = false;
      continue;
    }
    if (arg == "--check") {
      options.check = true;
      continue;
    }
    if (arg == "--collada-up-axis" || arg == "--collada-ignore-up-axis") {  // the last one given holds
      options.collada_up_axis = arg == "--collada-up-axis";
      continue;
    }
    if (arg == "--urdf-exact-mesh-mass") {
      options.urdf_exact_mesh_mass = true;
      continue;
    }
    if (arg == "--exclude-initial-overlaps") {
      options.exclude_initial_overlaps = true;
      continue;
    }
    if (!take_value(args, i, "--check-time", "", value, error, matched)) return std::nullopt;
    if (matched) {
      char* end = nullptr;
      options.check_time = std::strtod(value.c_str(), &end);
      if (value.empty() || *end != '\0' || !(options.check_time > 0) ||
          !(options.check_time <= kMaxCheckTime)) {
        error = "--check-time takes a positive number of seconds up to " +
                std::to_string(int(kMaxCheckTime)) + ", not '" + value + "'";
        return std::nullopt;
      }
      continue;
    }
    if (!take_value(args, i, "--pose", "", value, error, matched)) return std::nullopt;
    if (matched) {
      options.pose = mjcf::parse_placement(value, error);
      if (!options.pose) {
        error = "--pose: " + error;
        return std::nullopt;
      }
      continue;
    }
    if (!take_value(args, i, "--lights", "", value, error, matched)) return std::nullopt;
    if (matched) {
      if (value == "auto") {
        options.lights.reset();
      } else if (value == "on" || value == "off") {
        options.lights = value == "on";
      } else {
        error = "--lights takes auto, on or off, not '" + value + "'";
        return std::nullopt;
      }
      continue;
    }
    if (!take_value(args, i, "--depfile", "", value, error, matched)) return std::nullopt;
    if (matched) {
      options.depfile = value;
      continue;
    }
    if (!take_value(args, i, "--prefix", "", value, error, matched)) return std::nullopt;
    if (matched) {
      if (const std::string problem = prefix_problem(value); !problem.empty()) {
        error = "--prefix " + problem;
        return std::nullopt;
      }
      options.prefix = value;
      continue;
    }
    if (!take_value(args, i, "--timestep", "", value, error, matched)) return std::nullopt;
    if (matched) {
      char* end = nullptr;
      options.timestep = std::strtod(value.c_str(), &end);
      // A step MuJoCo can take: below 1 us the simulation never advances; above 1 s nothing stays stable.
      if (value.empty() || *end != '\0' || !(options.timestep >= 1e-6 && options.timestep <= 1)) {
        error = "--timestep takes a positive number of seconds from 1e-06 to 1, not '" + value + "'";
        return std::nullopt;
      }
      continue;
    }
    if (!take_value(args, i, "--mujoco", "", value, error, matched)) return std::nullopt;
    if (matched) {
      if (value == "2" || value == "2.2" || value == "2.2.2") {
        options.mujoco3 = false;
      } else if (value == "3" || value.starts_with("3.")) {
        options.mujoco3 = true;
      } else {
        error = "--mujoco takes 2.2 or 3 (the MuJoCo whose soft-constraint laws to use), not '" + value + "'";
        return std::nullopt;
      }
      continue;
    }
    if (!take_value(args, i, "--model", "", value, error, matched)) return std::nullopt;
    if (matched) {
      options.model = value;
      continue;
    }
    if (!take_value(args, i, "--output", "-o", value, error, matched)) return std::nullopt;
    if (matched) {
      options.output = value;
      continue;
    }
    if (!take_value(args, i, "--bundle-path", "-B", value, error, matched)) return std::nullopt;
    if (matched) {
      options.bundle_dirs.push_back(value);
      continue;
    }
    if (!take_value(args, i, "--dump", "", value, error, matched)) return std::nullopt;
    if (matched) {
      if (value == "tokens") {
        options.dump = DumpKind::Tokens;
      } else if (value == "ast") {
        options.dump = DumpKind::Ast;
      } else if (value == "values") {
        options.dump = DumpKind::Values;
      } else if (value == "snap") {
        options.dump = DumpKind::Snap;
      } else {
        error = "unknown dump kind '" + value + "' (expected tokens, ast, values or snap)";
        return std::nullopt;
      }
      continue;
    }
    error = "unknown option '" + arg + "'";
    return std::nullopt;
  }
  if (options.help || options.version) return options;
  if (options.input.empty()) {
    error = "no input file";
    return std::nullopt;
  }
  for (const std::string& dir : options.bundle_dirs) {
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) {
      error = "bundle directory '" + dir + "' does not exist";
      return std::nullopt;
    }
  }
  if (options.depfile && (!options.output || *options.output == "-" || options.dump != DumpKind::None)) {
    error = "--depfile needs -o FILE (it names what FILE was made from), and no --dump";
    return std::nullopt;
  }
  if (options.output && *options.output != "-") {
    std::error_code ec;
    // The manifest written beside the MJCF counts too: `x.signals.json -o x.xml` would replace
    // x.signals.json.
    for (const std::string& written : {*options.output, manifest_path(*options.output)}) {
      if (std::filesystem::equivalent(options.input, written, ec)) {
        error = "refusing to overwrite the input file '" + options.input + "' with '" + written + "'";
        return std::nullopt;
      }
    }
  }
  return options;
}

int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  std::string usage_error;
  std::optional<CliOptions> options = parse_options(args, usage_error);
  if (!options) {
    err << "openplx2mjcf: error: " << usage_error << "\nTry 'openplx2mjcf --help'.\n";
    return kExitUsageError;
  }
  if (options->help) {
    out << usage();
    return kExitOk;
  }
  if (options->version) {
    out << "openplx2mjcf " << OPENPLX_VERSION << '\n';
    return kExitOk;
  }

  fe::SourceManager sources;
  fe::DiagnosticSink sink(options->strict);
  std::ostringstream text;
  Converted converted;
  if (options->dump == DumpKind::Tokens || options->dump == DumpKind::Ast) {
    std::string io_error;
    std::optional<fe::FileId> file_id = sources.load(options->input, io_error);
    if (!file_id) {
      err << options->input << ": error: " << io_error << " [" << fe::code_name(fe::DiagCode::IoError)
          << "]\n";
      return kExitInputError;
    }
    const fe::SourceFile& file = sources.file(*file_id);
    if (options->dump == DumpKind::Tokens) {
      fe::dump_tokens(text, file, fe::lex(file, *file_id, sink));
    } else {
      fe::dump_ast(text, file, fe::parse_file(sources, *file_id, sink));
    }
  } else if (!convert(*options, sources, sink, text, converted, err)) {
    return kExitInputError;
  }

  fe::print_diagnostics(err, sources, sink.diagnostics());
  const bool failed = sink.has_errors();
  const bool to_stdout = !options->output || *options->output == "-";
  if (to_stdout) {
    out << text.str() << converted.xml;  // a dump of a broken file still helps; its diagnostics are on stderr
  } else if (!failed && !write_outputs(*options, sources, converted, text.str(), err)) {
    return kExitInputError;
  }
  leave_to_exit(std::move(converted));
  return failed ? kExitInputError : kExitOk;
}

}  // namespace openplx::cli
