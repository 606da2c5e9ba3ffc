#include "frontend/bundles/bundles.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "frontend/bundles/embedded_bundles.h"
#include "frontend/syntax/parser.h"

#ifndef OPENPLX_SOURCE_BUNDLES_DIR
#define OPENPLX_SOURCE_BUNDLES_DIR ""
#endif

namespace openplx::frontend {
namespace fs = std::filesystem;

namespace {

std::string normalised(const fs::path& path) {
  std::error_code ec;
  fs::path absolute = fs::absolute(path, ec);
  return (ec ? path : absolute).lexically_normal().generic_string();
}

bool is_bundle_dir(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / "config.openplx", ec);
}

// The literal string (or array of strings) assigned to `name` in the config body.
const Member* find_assignment(const Decl& decl, std::string_view name) {
  for (const Member& m : decl.body) {
    if ((m.kind == MemberKind::Assignment || m.kind == MemberKind::Attribute) && m.path.parts.size() == 1 &&
        m.path.parts[0].text == name && m.value) {
      return &m;
    }
  }
  return nullptr;
}

// Reads `dir/config.openplx`, from the embedded folder `from` when given (it is `dir` as this build saw it).
std::optional<BundleConfig> read_config(const std::string& dir, const embedded::Dir* from,
                                        SourceManager& sources, DiagnosticSink& sink) {
  const std::string path = (fs::path(dir) / "config.openplx").generic_string();
  std::optional<FileId> id;
  if (from) {
    if (const embedded::File* file = embedded::find_file(*from, "config.openplx")) {
      id = sources.add_static(path, file->text);
    }
  } else {
    std::string error;
    id = sources.load(path, error);
    if (!id) {
      sink.report(DiagCode::IoError, {}, path + ": " + error);
      return std::nullopt;
    }
  }
  if (!id) return std::nullopt;  // not reached: only folders with a config are read
  Document doc = parse_file(sources, *id, sink);
  const SourceFile& file = sources.file(*id);
  const Decl* config = nullptr;
  for (const Decl& decl : doc.decls) {
    if (decl.kind == DeclKind::Model && decl.name.text == "config") config = &decl;
  }
  const SourceRange file_start{*id, file.content_begin(), file.content_begin()};
  if (!config) {
    sink.report(DiagCode::InvalidBundleConfig, file_start,
                "bundle config must declare `config is BundleConfig:`");
    return std::nullopt;
  }
  BundleConfig result;
  result.dir = normalised(dir);
  result.embedded = from;
  const Member* name = find_assignment(*config, "name");
  if (!name || doc.expr(*name->value).kind != ExprKind::String) {
    sink.report(DiagCode::InvalidBundleConfig, config->range, "bundle config needs `name: \"BundleName\"`");
    return std::nullopt;
  }
  result.name = doc.expr(*name->value).string_value;
  if (const Member* version = find_assignment(*config, "version")) {
    const Expr& e = doc.expr(*version->value);
    if (e.kind == ExprKind::String) {
      result.version = e.string_value;
    } else {
      sink.report(DiagCode::InvalidBundleConfig, e.range, "bundle `version` must be a string");
    }
  }
  if (const Member* deps = find_assignment(*config, "dependencies")) {
    const Expr& e = doc.expr(*deps->value);
    if (e.kind != ExprKind::Array) {
      sink.report(DiagCode::InvalidBundleConfig, e.range,
                  "bundle `dependencies` must be an array of strings");
    } else {
      for (ExprId item : e.operands) {
        const Expr& dep = doc.expr(item);
        if (dep.kind != ExprKind::String) {
          sink.report(DiagCode::InvalidBundleConfig, dep.range, "a dependency is a string such as \"Math\"");
          continue;
        }
        result.dependencies.push_back(parse_dependency(dep.string_value));
      }
    }
  }
  return result;
}

}  // namespace

std::string executable_dir() {
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : exe.parent_path().string();
}

// "Math", "Math@0.20.2", "Math==0.20.2" (the releases' pin); a range ("Math>=0.19") names the bundle and
// is not checked.
BundleDependency parse_dependency(const std::string& text) {
  const size_t op = text.find_first_of("@=<>~!");
  if (op == std::string::npos) return {text, ""};
  std::string name = text.substr(0, op);
  while (!name.empty() && name.back() == ' ') name.pop_back();
  std::string rest = text.substr(op);
  const bool exact = rest.starts_with("@") || rest.starts_with("==");
  const size_t start = rest.find_first_not_of("@=<>~! ");
  return {std::move(name), exact && start != std::string::npos ? rest.substr(start) : ""};
}

std::optional<BundleConfig> read_bundle_config(const std::string& dir, SourceManager& sources,
                                               DiagnosticSink& sink) {
  return read_config(dir, nullptr, sources, sink);
}

// The project's bundles, installed or in the source tree, are the ones this build embedded: the installed
// copy is made from the same tree by `cmake --install`. The folder must still exist, as it did before the
// copy was embedded, and gives the paths that diagnostics, dumps and manifests show.
std::vector<BundleRoot> bundle_search_path(const std::vector<std::string>& extra_dirs, bool default_bundles) {
  std::vector<BundleRoot> path;
  std::error_code ec;
  const fs::path installed = fs::path(executable_dir()) / "../share/openplx2mjcf/bundles";
  if (!default_bundles) {
    // only the user's: OPENPLX_BUNDLE_PATH and -B (an AGX/OpenPLX installation's bundles)
  } else if (fs::is_directory(installed, ec)) {
    path.push_back({normalised(installed), true});
  } else if (std::string source = OPENPLX_SOURCE_BUNDLES_DIR;
             !source.empty() && fs::is_directory(source, ec)) {
    path.push_back({normalised(source), true});
  }
  if (const char* env = std::getenv("OPENPLX_BUNDLE_PATH")) {
    std::string list = env;
    size_t start = 0;
    while (start <= list.size()) {
      size_t end = list.find(':', start);
      if (end == std::string::npos) end = list.size();
      if (end > start) path.push_back({normalised(list.substr(start, end - start))});
      start = end + 1;
    }
  }
  for (const std::string& dir : extra_dirs) path.push_back({normalised(dir)});
  return path;
}

std::vector<BundleConfig> discover_bundles(const std::vector<BundleRoot>& search_path, SourceManager& sources,
                                           DiagnosticSink& sink) {
  std::vector<BundleConfig> bundles;
  std::set<std::string> names;
  auto add = [&](const fs::path& dir, const embedded::Dir* from = nullptr) {
    std::optional<BundleConfig> config = read_config(dir.string(), from, sources, sink);
    if (config && names.insert(config->name).second) bundles.push_back(std::move(*config));
  };
  auto is_bundle = [](const embedded::Dir& dir) { return embedded::find_file(dir, "config.openplx"); };
  for (const auto& [root, from_build] : search_path) {
    if (from_build) {  // as below, from the copy: sub-folders are in name order already
      if (is_bundle(embedded::root())) {
        add(root, &embedded::root());
        continue;
      }
      for (const embedded::Dir& child : embedded::subdirs(embedded::root())) {
        if (is_bundle(child)) add(fs::path(root) / child.name, &child);
      }
      continue;
    }
    std::error_code ec;
    if (is_bundle_dir(root)) {
      add(root);
      continue;
    }
    std::vector<fs::path> children;
    for (const auto& entry : fs::directory_iterator(root, ec)) {
      if (entry.is_directory(ec) && is_bundle_dir(entry.path())) children.push_back(entry.path());
    }
    std::sort(children.begin(), children.end());  // directory order is not deterministic
    for (const fs::path& child : children) add(child);
  }
  return bundles;
}

std::optional<std::string> enclosing_bundle_dir(const std::string& file) {
  fs::path dir = fs::path(normalised(file)).parent_path();
  while (!dir.empty()) {
    if (is_bundle_dir(dir)) return dir.generic_string();
    if (dir == dir.root_path()) break;
    dir = dir.parent_path();
  }
  return std::nullopt;
}

}  // namespace openplx::frontend
