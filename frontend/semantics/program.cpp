// The program, loading: bundles, namespaces and documents read as they are first named, and imports.
// Name lookup is in program_lookup.cpp; resolving models (bases, traits, members) in program_resolve.cpp.
#include "frontend/semantics/program.h"

#include <dirent.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "frontend/bundles/bundle_index.h"
#include "frontend/bundles/embedded_bundles.h"
#include "frontend/bundles/import_plugins.h"
#include "frontend/semantics/deprecations.h"
#include "frontend/syntax/parser.h"
#include "frontend/urdf/urdf_importer.h"

namespace openplx::frontend {
namespace fs = std::filesystem;

namespace {

// The names of a folder's sub-folders and of its other entries, each sorted. readdir, not
// std::filesystem::directory_iterator, which builds and parses a path per entry: for the bundles that cost
// as much as scanning their files.
void list_folder(const std::string& dir, std::vector<std::string>& dirs, std::vector<std::string>& others) {
  DIR* folder = opendir(dir.c_str());
  if (!folder) return;
  while (const dirent* entry = readdir(folder)) {
    const std::string_view name = entry->d_name;
    if (name == "." || name == "..") continue;
    bool is_dir = entry->d_type == DT_DIR;
    if (entry->d_type == DT_UNKNOWN ||
        entry->d_type == DT_LNK) {  // links are followed, as is_directory() does
      struct stat st;
      is_dir = stat((dir + '/').append(name).c_str(), &st) == 0 && S_ISDIR(st.st_mode);
    }
    (is_dir ? dirs : others).emplace_back(name);
  }
  closedir(folder);
  std::sort(dirs.begin(), dirs.end());
  std::sort(others.begin(), others.end());
}

}  // namespace

// spec §15.1: the schema of a bundle's config.openplx.
constexpr const char* kBuiltins =
    "BundleConfig:\n"
    "    name is String\n"
    "    version is String: \"\"\n"
    "    dependencies is String[]: []\n";

Program::Program(SourceManager& sources, DiagnosticSink& sink) : sources_(sources), sink_(sink) {
  builtins_ = new_namespace("", nullptr, "", nullptr);
  load_document(sources_.add("<builtin>", kBuiltins), builtins_, nullptr);
}
Program::~Program() = default;

Namespace* Program::new_namespace(std::string name, Namespace* parent, std::string dir,
                                  const BundleConfig* bundle) {
  Namespace& ns = namespaces_.emplace_back();
  ns.qualified = parent && !parent->qualified.empty() ? parent->qualified + "." + name : name;
  ns.name = std::move(name);
  ns.parent = parent;
  ns.dir = std::move(dir);
  ns.bundle = bundle;
  ns.loaded = ns.dir.empty();
  return &ns;
}

void Program::set_bundles(std::vector<BundleConfig> bundles) {
  for (BundleConfig& bundle : bundles) add_bundle(std::move(bundle));
}

const BundleConfig* Program::add_bundle(BundleConfig bundle) {
  if (Namespace* existing = bundle_root(bundle.name)) return existing->bundle;
  const BundleConfig& stored = bundles_.emplace_back(std::move(bundle));
  Namespace* root = new_namespace(stored.name, nullptr, stored.dir, &stored);
  root->embedded = stored.embedded;
  bundle_roots_[stored.name] = root;
  // The 0.17.8 `Charges` namespaces live on as aliases of the models' current homes.
  for (std::string_view old : renamed_namespaces()) {
    const size_t dot = old.find('.');
    if (old.substr(0, dot) != stored.name) continue;
    const std::string child(old.substr(dot + 1));
    Namespace* legacy = new_namespace(child, root, "", &stored);
    legacy->legacy = true;
    root->children[child] = legacy;
  }
  return &stored;
}

Namespace* Program::bundle_root(std::string_view name) {
  auto it = bundle_roots_.find(name);
  return it == bundle_roots_.end() ? nullptr : it->second;
}

void Program::load_namespace(Namespace* ns, bool eager) {
  if (ns->loaded) {
    if (eager) load_all(ns);
    return;
  }
  ns->loaded = true;
  // Entries by name: they share the folder, so sorting names sorts their paths, and the folder's normal form
  // followed by a name is the entry's normal form (one lexically_normal per folder, not per file).
  std::string folder = fs::path(ns->dir).lexically_normal().generic_string();
  if (folder == ".") folder.clear();
  if (!folder.empty() && folder.back() != '/') folder += '/';
  std::vector<std::string> dirs;
  std::vector<std::string> files;
  if (ns->embedded) {
    for (const embedded::Dir& dir : embedded::subdirs(*ns->embedded)) dirs.emplace_back(dir.name);
    for (const embedded::File& file : embedded::files(*ns->embedded)) files.emplace_back(file.name);
  } else {
    list_folder(ns->dir, dirs, files);
  }
  for (size_t i = 0; i < dirs.size(); ++i) {
    const std::string& name = dirs[i];
    if (ns->children.count(name)) continue;
    Namespace* child = ns->children[name] = new_namespace(name, ns, folder + name, ns->bundle);
    if (ns->embedded) child->embedded = &embedded::subdirs(*ns->embedded)[i];
  }
  // Every file is read and scanned before any is parsed. Unless each was scanned completely and no name is
  // declared twice, the folder is parsed as a whole, so that a DuplicateDeclaration comes as it always did.
  struct Found {
    std::string path;
    std::optional<FileId> id;
    std::string error;
    FileDeclarations declares;
  };
  std::vector<Found> found;
  found.reserve(files.size());
  std::vector<std::string_view> names;
  bool whole = eager;
  for (const std::string& name : files) {
    if (name.size() <= 8 || !name.ends_with(".openplx")) continue;  // as path::extension(): not ".openplx"
    // config.openplx describes the bundle and adds nothing to its namespace.
    if (!ns->parent && name == "config.openplx") continue;
    std::string path = folder + name;
    if (loaded_files_.count(path) || lazy_by_path_.count(path)) continue;
    Found& f = found.emplace_back();
    const embedded::File* copy = ns->embedded ? embedded::find_file(*ns->embedded, name) : nullptr;
    f.id = copy ? sources_.add_static(path, copy->text) : sources_.load(path, f.error);
    f.path = std::move(path);
    if (!f.id || whole) continue;
    if (copy) {
      f.declares = embedded::declarations(*copy);  // scanned when the copy was made
    } else {
      const SourceFile& source = sources_.file(*f.id);
      f.declares = scan_declarations(source.text(), source.content_begin());
    }
    whole = !f.declares.complete;
    names.insert(names.end(), f.declares.names.begin(), f.declares.names.end());
  }
  std::sort(names.begin(), names.end());
  whole = whole || std::adjacent_find(names.begin(), names.end()) != names.end();
  // In path order, as before: files that must be parsed now (imports, operators) come in the order they
  // always did, so operators_ and the diagnostics keep theirs.
  for (Found& f : found) {
    if (loaded_files_.count(f.path)) continue;  // imported by a file before it
    if (!f.id) {
      sink_.report(DiagCode::IoError, {}, f.path + ": " + f.error);
      continue;
    }
    if (whole || !f.declares.lazy) {
      load_document(*f.id, ns, ns->bundle);
      continue;
    }
    LazyFile* lazy = &lazy_files_.emplace_back(LazyFile{*f.id, ns});
    ns->lazy_files.push_back(lazy);
    lazy_by_path_.emplace(std::move(f.path), lazy);
    for (std::string& name : f.declares.names) ns->lazy_names.emplace(std::move(name), lazy);
  }
}

void Program::load_all(Namespace* ns) {
  load_namespace(ns);
  for (LazyFile* file : ns->lazy_files) parse_lazy(file);
}

DocumentInfo* Program::parse_lazy(LazyFile* file) {
  if (!file->doc) file->doc = load_document(file->file, file->ns, file->ns->bundle);
  return file->doc;
}

DocumentInfo* Program::find_loaded(const std::string& path) {
  if (auto it = loaded_files_.find(path); it != loaded_files_.end()) return it->second;
  if (auto it = lazy_by_path_.find(path); it != lazy_by_path_.end()) return parse_lazy(it->second);
  return nullptr;
}

DocumentInfo* Program::load_document(FileId file, Namespace* ns, const BundleConfig* bundle) {
  DocumentInfo& info = documents_.emplace_back();
  loaded_files_[sources_.file(file).path()] = &info;
  info.doc = parse_file(sources_, file, sink_);
  info.ns = ns;
  info.bundle = bundle;
  declare(&info, ns);
  process_imports(&info);
  return &info;
}

void Program::declare(DocumentInfo* doc, Namespace* ns) {
  for (const Decl& decl : doc->doc.decls) {
    if (decl.kind == DeclKind::Operator) {
      operators_.push_back({&decl, doc});
      continue;
    }
    if (decl.kind != DeclKind::Model && decl.kind != DeclKind::Trait &&
        decl.kind != DeclKind::GlobalAttribute) {
      continue;
    }
    const std::string name(decl.name.text);
    const std::string qualified = ns->qualified.empty() ? name : ns->qualified + "." + name;
    if (ns->symbols.count(name)) {
      sink_.report(DiagCode::DuplicateDeclaration, decl.name.range, "Duplicate declaration " + qualified);
      continue;
    }
    if (decl.kind == DeclKind::GlobalAttribute) {
      GlobalInfo& global = globals_.emplace_back();
      global.decl = &decl;
      global.doc = doc;
      global.qualified = qualified;
      ns->symbols[name].global = &global;
      continue;
    }
    ModelInfo& model = models_.emplace_back();
    model.name = name;
    model.qualified = qualified;
    model.decl = &decl;
    model.doc = doc;
    model.is_trait = decl.kind == DeclKind::Trait;
    model.is_const = decl.is_const;
    ns->symbols[name].model = &model;
  }
}

void Program::process_imports(DocumentInfo* doc) {
  std::error_code ec;
  const fs::path base_dir = fs::absolute(fs::path(sources_.file(doc->doc.file).path()), ec).parent_path();
  for (const Decl& decl : doc->doc.decls) {
    if (decl.kind != DeclKind::Import) continue;
    const Expr& path_expr = doc->doc.expr(*decl.value);
    fs::path target = fs::path(path_expr.string_value);
    if (target.is_relative()) target = base_dir / target;
    const std::string path = target.lexically_normal().generic_string();
    if (!fs::is_regular_file(path, ec)) {
      sink_.report(DiagCode::ImportNotFound, decl.range, "Could not find imported file " + path);
      continue;
    }
    const std::string extension = lowercase_extension(path);  // `robot.URDF` is a URDF too
    const std::string alias = decl.alias ? to_string(*decl.alias) : fs::path(path).stem().string();
    if (extension == ".openplx") {
      DocumentInfo* imported = find_loaded(path);
      if (!imported) {
        std::string error;
        std::optional<FileId> id = sources_.load(path, error);
        if (!id) {
          sink_.report(DiagCode::ImportNotFound, decl.range,
                       "Could not read imported file " + path + ": " + error);
          continue;
        }
        Namespace* ns = new_namespace(alias, nullptr, "", nullptr);
        ns->qualified = "";
        imported = load_document(*id, ns, nullptr);
      }
      if (decl.alias) {
        doc->import_namespaces[alias] = imported->ns;
      } else {
        doc->imported_files.push_back(imported->ns);
      }
      continue;
    }
    std::optional<std::string> source;
    std::vector<std::string> names{alias};
    std::optional<UrdfSource> urdf;
    if (is_urdf_extension(extension)) {
      urdf = read_urdf(path, alias, decl.range);
      if (!urdf) continue;
      source = std::move(urdf->text);
      // `import @"robot.urdf"` also names the robot after <robot name>, as OpenPLX documents it.
      if (!decl.alias && !urdf->robot_name.empty()) names.push_back(urdf->robot_name);
    } else {
      std::string error;
      source = import_plugin_source(path, alias, error);
      if (!source) {
        sink_.report(DiagCode::UnsupportedImport, decl.range, error);
        continue;
      }
    }
    // The plugin describes the imported asset as OpenPLX text; it is read like any other document, in a
    // scope of its own, and its one model becomes visible under the alias.
    FileId id = sources_.add("<import " + path + ">", *source);
    if (urdf) sources_.set_origin(id, urdf->file, std::move(urdf->line_origins));
    Namespace* ns = new_namespace("", nullptr, "", nullptr);
    load_document(id, ns, nullptr);
    if (auto it = ns->symbols.find(alias); it != ns->symbols.end() && it->second.model) {
      for (const std::string& name : names) doc->import_models.try_emplace(name, it->second.model);
    }
  }
}

// Reads and converts an imported URDF; its findings are reported in the URDF itself. nullopt when it was
// rejected (an error was reported).
std::optional<Program::UrdfSource> Program::read_urdf(const std::string& path, const std::string& model,
                                                      SourceRange import_range) {
  std::string error;
  std::optional<FileId> file = sources_.load(path, error);
  if (!file) {
    sink_.report(DiagCode::ImportNotFound, import_range,
                 "Could not read imported file " + path + ": " + error);
    return std::nullopt;
  }
  UrdfImport urdf =
      import_urdf(path, std::string(sources_.file(*file).text()), model, {urdf_given_directly_});
  for (const UrdfFinding& f : urdf.findings) {
    Diagnostic& d = sink_.report(f.error ? DiagCode::UrdfInvalid : DiagCode::UrdfWarning,
                                 SourceRange{*file, f.offset, f.offset + 1}, f.message);
    d.notes.insert(d.notes.end(), f.notes.begin(), f.notes.end());
  }
  if (!urdf.text) return std::nullopt;
  return UrdfSource{*file, std::move(*urdf.text), std::move(urdf.line_origins), std::move(urdf.robot_name)};
}

DocumentInfo* Program::load_main(const std::string& path) {
  const std::string normal = fs::absolute(path).lexically_normal().generic_string();
  if (DocumentInfo* loaded = find_loaded(normal)) return loaded;
  // A file inside a bundle folder is read as part of that bundle, so its neighbours are in scope.
  if (std::optional<std::string> bundle_dir = enclosing_bundle_dir(normal)) {
    const BundleConfig* bundle = nullptr;
    for (const BundleConfig& b : bundles_) {
      if (b.dir == *bundle_dir) bundle = &b;
    }
    if (!bundle) {
      std::optional<BundleConfig> config = read_bundle_config(*bundle_dir, sources_, sink_);
      if (config) bundle = add_bundle(std::move(*config));
    }
    if (bundle) {
      // Eagerly, as the folders of a bundle being edited: every file's findings are reported.
      Namespace* ns = bundle_root(bundle->name);
      fs::path rel = fs::path(normal).parent_path().lexically_relative(bundle->dir);
      for (const fs::path& part : rel) {
        if (part == ".") continue;
        load_namespace(ns, true);
        auto child = ns->children.find(part.string());
        if (child == ns->children.end()) break;
        ns = child->second;
      }
      load_namespace(ns, true);
      if (DocumentInfo* loaded = find_loaded(normal)) return loaded;
    }
  }
  std::string error;
  std::optional<FileId> id = sources_.load(path, error);
  if (!id) {
    sink_.report(DiagCode::IoError, {}, path + ": " + error);
    return nullptr;
  }
  Namespace* ns = new_namespace("", nullptr, "", nullptr);
  return load_document(*id, ns, nullptr);
}

DocumentInfo* Program::load_text(const std::string& path, std::string text) {
  FileId id = sources_.add(path, std::move(text));
  return load_document(id, new_namespace("", nullptr, "", nullptr), nullptr);
}

bool Program::bundle_visible(DocumentInfo* from, const BundleConfig* target) const {
  if (!from || !from->bundle || from->bundle == target) return true;
  // Dependencies are visible transitively.
  std::vector<const BundleConfig*> todo{from->bundle};
  std::set<std::string> seen{from->bundle->name};
  while (!todo.empty()) {
    const BundleConfig* current = todo.back();
    todo.pop_back();
    for (const BundleDependency& dep : current->dependencies) {
      if (dep.name == target->name) return true;
      if (!seen.insert(dep.name).second) continue;
      for (const BundleConfig& b : bundles_) {
        if (b.name == dep.name) todo.push_back(&b);
      }
    }
  }
  return false;
}

}  // namespace openplx::frontend
