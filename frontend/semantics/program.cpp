#include "frontend/semantics/program.h"

#include <dirent.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <unordered_set>

#include "frontend/bundles/bundle_index.h"
#include "frontend/semantics/deprecations.h"
#include "frontend/semantics/edit_distance.h"
#include "frontend/bundles/embedded_bundles.h"
#include "frontend/bundles/import_plugins.h"
#include "frontend/natives/host_declarations.h"
#include "frontend/syntax/parser.h"
#include "frontend/semantics/unknown_name_notes.h"
#include "frontend/urdf/urdf_importer.h"

namespace openplx::frontend {
namespace fs = std::filesystem;

namespace {

std::string join(const std::vector<std::string_view>& parts, size_t count) {
  std::string out;
  for (size_t i = 0; i < count; ++i) {
    if (i) out += '.';
    out += parts[i];
  }
  return out;
}

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

// The linearization of `model`: each model the first time it is met, depth first (a model, its traits in
// order, then its base). This is the model followed by each trait's and then the base's own linearization
// with what came before left out, without building theirs: each model's parents are looked at once.
std::vector<ModelInfo*> linearize_model(const ModelInfo* model) {
  std::vector<ModelInfo*> out;
  if (model->linearize == ModelInfo::Linearize::No) return out;
  std::unordered_set<const ModelInfo*> met;
  std::vector<const ModelInfo*> stack{model};  // iterative: an inheritance chain can be 10,000 deep
  std::vector<const ModelInfo*> parents;
  while (!stack.empty()) {
    const ModelInfo* m = stack.back();
    stack.pop_back();
    if (!met.insert(m).second) continue;  // met before: so were all of its parents
    out.push_back(const_cast<ModelInfo*>(m));
    const bool all = m->linearize == ModelInfo::Linearize::All;
    auto taken = [&](const ModelInfo* p) {
      return p && (all ? p->linearize != ModelInfo::Linearize::No : p->state == ModelInfo::State::Resolved);
    };
    parents.clear();
    for (const ModelInfo* trait : m->traits) {
      if (taken(trait)) parents.push_back(trait);
    }
    if (taken(m->base)) parents.push_back(m->base);
    stack.insert(stack.end(), parents.rbegin(), parents.rend());
  }
  return out;
}

}  // namespace

const std::vector<ModelInfo*>& ModelInfo::linearization() const {
  if (!linearized_ && linearize != Linearize::No) {  // before resolve() gets that far: empty, for now
    linearization_ = linearize_model(this);
    linearized_ = true;
  }
  return linearization_;
}

bool ModelInfo::is_subtype_of(const ModelInfo* other) const {
  if (this == other) return true;
  const std::vector<ModelInfo*>& linearization = this->linearization();
  if (std::find(linearization.begin(), linearization.end(), other) != linearization.end()) return true;
  // `Base with T1, T2` names no model of its own: any subtype of Base that includes T1 and T2 fits.
  if (!other->decl && other->base) {
    if (!is_subtype_of(other->base)) return false;
    for (const ModelInfo* trait : other->traits) {
      if (!is_subtype_of(trait)) return false;
    }
    return true;
  }
  return false;
}

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

Symbol Program::lookup_in(Namespace* ns, std::string_view name, const SourceRange* where) {
  if (!ns->legacy) {
    load_namespace(ns);
    auto it = ns->symbols.find(name);
    if (it == ns->symbols.end()) {
      if (auto lazy = ns->lazy_names.find(name); lazy != ns->lazy_names.end()) {
        parse_lazy(lazy->second);
        it = ns->symbols.find(name);
      }
    }
    if (it != ns->symbols.end()) return it->second;
    if (auto it = ns->children.find(name); it != ns->children.end())
      return Symbol{nullptr, nullptr, it->second};
    if (Symbol s = host_declared(ns, name, ns->bundle)) return s;
  }
  // A model of the 0.17.8 API that moved: found at its current home, with a warning naming it.
  std::optional<std::string> current = renamed_model(ns->qualified, name);
  ModelInfo* model = current ? builtin_model(*current) : nullptr;
  if (model && where) {
    sink_.report(
        DiagCode::DeprecatedName, *where,
        "`" + ns->qualified + "." + std::string(name) + "` is the 0.17.8 name; use `" + *current + "`");
  }
  return model ? Symbol{model} : Symbol{};
}

Symbol Program::lookup(DocumentInfo* doc, std::string_view name, SourceRange where, bool report,
                       const std::function<std::vector<std::string>()>& extra) {
  if (Symbol s = lookup_in(doc->ns, name)) return s;
  if (auto it = doc->import_models.find(name); it != doc->import_models.end()) return Symbol{it->second};
  if (auto it = doc->import_namespaces.find(name); it != doc->import_namespaces.end()) {
    return Symbol{nullptr, nullptr, it->second};
  }
  for (Namespace* imported : doc->imported_files) {
    if (Symbol s = lookup_in(imported, name)) return s;
  }
  // The folders enclosing the file's, innermost first: bundle releases name a model of a parent folder
  // without a word (Sensors/Optics/Traits/RayEmitter.openplx: `RaySource` of Sensors/Optics).
  for (Namespace* outer = doc->ns->parent; outer && outer->parent; outer = outer->parent) {
    if (Symbol s = lookup_in(outer, name)) return s;
  }
  if (doc->bundle) {
    if (Namespace* root = bundle_root(doc->bundle->name)) {
      if (Symbol s = lookup_in(root, name)) return s;
    }
  }
  if (Symbol s = lookup_in(builtins_, name)) return s;
  if (Symbol s = host_declared(builtins_, name, doc->bundle)) return s;
  if (Namespace* root = bundle_root(name)) {
    if (bundle_visible(doc, root->bundle)) {
      for (const BundleDependency& dep :
           doc->bundle ? doc->bundle->dependencies : std::vector<BundleDependency>{}) {
        if (dep.name == name && !dep.version.empty() && dep.version != root->bundle->version && report) {
          sink_.report(DiagCode::BundleVersionMismatch, where,
                       "Bundle " + doc->bundle->name + " requires " + dep.name + "@" + dep.version +
                           " but found " + dep.name + "@" + root->bundle->version);
        }
      }
      return Symbol{nullptr, nullptr, root};
    }
    if (report) {
      sink_.report(DiagCode::UnknownName, where,
                   "Unknown name " + std::string(name) + " (bundle not declared as dependency of " +
                       doc->bundle->name + ")");
    }
    return {};
  }
  if (report) {
    std::string message = "Unknown name " + std::string(name);
    std::vector<std::string> candidates = names_visible_from(doc);
    if (extra) {
      std::vector<std::string> more = extra();
      candidates.insert(candidates.end(), more.begin(), more.end());
    }
    std::string near = suggestion(name, candidates);
    if (!near.empty()) message += "; did you mean `" + near + "`?";
    Diagnostic& d = sink_.report(DiagCode::UnknownName, where, message);
    add_note(d, newer_bundle_note(name, bundles_));
    if (!doc->bundle && doc->ns && doc->ns->qualified.empty())
      add_note(d, sibling_bundle_note(sources_.file(doc->doc.file).path(), name));
  }
  return {};
}

Symbol Program::host_declared(Namespace* ns, std::string_view name, const BundleConfig* release) {
  if (!host_declarations_ || !release || release->embedded) return {};
  const natives::HostDeclaration* host =
      natives::find_host_declaration(release->version, ns->qualified, name);
  if (!host) return {};
  std::string path = "<host declarations " +
                     std::string(natives::host_generation(release->version).first_version) + ">/" +
                     std::string(host->ns) + (host->ns.empty() ? "" : ".") + std::string(name) + ".openplx";
  if (!loaded_files_.count(path)) load_document(sources_.add_static(path, host->text), ns, ns->bundle);
  auto it = ns->symbols.find(name);
  return it == ns->symbols.end() ? Symbol{} : it->second;
}

// The 0.20.2 release writes `Traits.RefractiveIndex` in Physics/Optics/Surfaces/Traits for the model of
// Physics/Optics/Traits: the first `Traits` found from there (the file's own folder) lacks it, so the name is
// the first enclosing folder's whose `Traits` holds the whole rest. Quiet: the caller reports a failure.
Symbol Program::lookup_in_enclosing(DocumentInfo* doc, const QualifiedName& name, Namespace* tried) {
  for (Namespace* outer = doc->ns ? doc->ns->parent : nullptr; outer; outer = outer->parent) {
    Symbol s = lookup_in(outer, name.parts[0].text);
    if (!s.ns || s.ns == tried) continue;
    for (size_t i = 1; s && i < name.parts.size(); ++i)
      s = s.ns ? lookup_in(s.ns, name.parts[i].text) : Symbol{};
    if (s) return s;
  }
  return {};
}

Symbol Program::lookup_qualified(DocumentInfo* doc, const QualifiedName& name, bool report) {
  // `import $"robot.urdf" as robots.arm` names the imported model with a dotted alias.
  if (name.parts.size() > 1 && !doc->import_models.empty()) {
    if (auto it = doc->import_models.find(to_string(name)); it != doc->import_models.end())
      return Symbol{it->second};
  }
  Symbol s = lookup(doc, name.parts[0].text, name.parts[0].range, report);
  Namespace* const first = s.ns;
  for (size_t i = 1; s && i < name.parts.size(); ++i) {
    if (!s.ns) {
      if (report) {
        sink_.report(DiagCode::UnknownName, name.parts[i].range,
                     "Unknown name " + to_string(name) + ": `" + std::string(name.parts[i - 1].text) +
                         "` is not a namespace");
      }
      return {};
    }
    Namespace* ns = s.ns;
    s = lookup_in(ns, name.parts[i].text, report ? &name.range : nullptr);
    if (!s) {
      if (Symbol found = lookup_in_enclosing(doc, name, first)) return found;
    }
    if (!s && report) {
      load_all(ns);
      std::vector<std::string> candidates;
      for (const auto& [n, sym] : ns->symbols) candidates.push_back(n);
      for (const auto& [n, child] : ns->children) candidates.push_back(n);
      std::string message = "Unknown name " + to_string(name) + ": no `" + std::string(name.parts[i].text) +
                            "` in " + (ns->qualified.empty() ? ns->name : ns->qualified);
      std::string near = suggestion(name.parts[i].text, candidates);
      if (!near.empty()) message += "; did you mean `" + near + "`?";
      Diagnostic& d = sink_.report(DiagCode::UnknownName, name.parts[i].range, message);
      add_note(d, missing_member_note(ns->bundle, ns->qualified, name.parts[i].text));
    }
  }
  return s;
}

ModelInfo* Program::resolve_model_name(DocumentInfo* doc, const QualifiedName& name, bool report) {
  std::string key;
  for (size_t i = 0; i < name.parts.size(); ++i) {
    if (i) key += '\0';
    key += name.parts[i].text;
  }
  if (auto it = doc->model_names.find(key); it != doc->model_names.end()) return it->second;
  const size_t reported = sink_.diagnostics().size();
  Symbol s = lookup_qualified(doc, name, report);
  // Only a quiet lookup is remembered: a 0.17.8 name is warned about wherever it is written.
  if (s.model && report && sink_.diagnostics().size() == reported)
    doc->model_names.emplace(std::move(key), s.model);
  if (!s) return nullptr;
  if (!s.model) {
    if (report) {
      sink_.report(DiagCode::NotAType, name.range,
                   "`" + to_string(name) + "` is " + (s.global ? "a global attribute" : "a namespace") +
                       ", not a model or trait");
    }
    return nullptr;
  }
  return s.model;
}

ModelInfo* Program::builtin_model(std::string_view qualified) {
  if (auto it = builtin_models_.find(qualified); it != builtin_models_.end()) return it->second;
  ModelInfo* model = find_builtin_model(qualified);
  if (model) builtin_models_.emplace(qualified, model);  // a name found never changes its meaning
  return model;
}

ModelInfo* Program::find_builtin_model(std::string_view qualified) {
  Namespace* ns = nullptr;
  Symbol s;
  size_t start = 0;
  while (start <= qualified.size()) {
    size_t end = qualified.find('.', start);
    if (end == std::string_view::npos) end = qualified.size();
    std::string_view part = qualified.substr(start, end - start);
    s = ns ? lookup_in(ns, part) : Symbol{nullptr, nullptr, bundle_root(part)};
    if (!s) return nullptr;
    ns = s.ns;
    start = end + 1;
  }
  return s.model;
}

ModelInfo* Program::loaded_model(std::string_view qualified) const {
  const Namespace* ns = nullptr;
  size_t start = 0;
  while (start <= qualified.size()) {
    size_t end = qualified.find('.', start);
    if (end == std::string_view::npos) end = qualified.size();
    const std::string_view part = qualified.substr(start, end - start);
    if (!ns) {
      auto root = bundle_roots_.find(part);
      if (root == bundle_roots_.end()) return nullptr;
      ns = root->second;
    } else {
      if (!ns->loaded) return nullptr;
      if (end == qualified.size()) {
        auto it = ns->symbols.find(part);
        return it == ns->symbols.end() ? nullptr : it->second.model;
      }
      auto child = ns->children.find(part);
      if (child == ns->children.end()) return nullptr;
      ns = child->second;
    }
    start = end + 1;
  }
  return nullptr;
}

ModelInfo* Program::make_trait_extension(ModelInfo* base, std::vector<ModelInfo*> traits) {
  std::string name = base->qualified + " with ";
  for (size_t i = 0; i < traits.size(); ++i) name += (i ? ", " : "") + traits[i]->qualified;
  if (auto it = trait_extensions_.find(name); it != trait_extensions_.end()) return it->second;
  ModelInfo& model = models_.emplace_back();
  trait_extensions_.emplace(name, &model);
  model.name = name;
  model.qualified = name;
  model.doc = base->doc;
  model.is_const = false;
  model.base = base;
  model.traits = std::move(traits);
  model.state = ModelInfo::State::Resolved;
  model.linearize = ModelInfo::Linearize::All;
  return &model;
}

void Program::report_agx_annotations(const std::function<bool(const ModelInfo*)>& held) {
  for (const AgxAnnotation& a : agx_annotations_) {
    if (!held(a.model)) continue;
    sink_.report(DiagCode::AgxAnnotation, a.member->range,
                 "AGX annotation `." + std::string(a.member->path.parts[0].text) +
                     "` has no MuJoCo counterpart; it was ignored");
  }
}

void Program::flatten(ModelInfo* model, const std::vector<Member>& members,
                      std::vector<std::string_view>& prefix) {
  auto add = [&](Entry::Kind kind, const Member& m, std::vector<std::string_view> path) {
    Entry e;
    e.kind = kind;
    e.parent_key = join(path, path.size() - 1);
    e.path = std::move(path);
    e.member = &m;
    e.value = m.value;
    e.index = static_cast<uint32_t>(model->entries.size());
    model->entries.push_back(std::move(e));
  };
  auto extended = [&](const QualifiedName& name) {
    std::vector<std::string_view> path = prefix;
    for (const Ident& part : name.parts) path.push_back(part.text);
    return path;
  };
  for (const Member& m : members) {
    switch (m.kind) {
      case MemberKind::Method:
        if (prefix.empty()) model->methods.push_back({&m, model});
        break;
      case MemberKind::TraitUse:
        if (prefix.empty()) {
          if (model->is_trait) {
            sink_.report(DiagCode::TraitRestriction, m.range, "Trait " + model->name + " cannot use with");
            break;
          }
          if (ModelInfo* trait = resolve_model_name(model->doc, m.path)) {
            if (!trait->is_trait) {
              sink_.report(DiagCode::TraitRestriction, m.path.range,
                           "`" + trait->qualified + "` is a model, not a trait; only traits go after `with`");
            } else {
              model->traits.push_back(trait);
            }
          }
        } else {
          Entry e;
          e.kind = Entry::Kind::WithTrait;
          e.path = prefix;
          e.path.push_back("with");
          e.parent_key = join(prefix, prefix.size());
          e.member = &m;
          e.index = static_cast<uint32_t>(model->entries.size());
          model->entries.push_back(std::move(e));
        }
        break;
      case MemberKind::Annotation: {
        // AGX's own settings (`.agx_*`) mean nothing to MuJoCo: accepted, and listed where a user wrote them
        // once the converted root is known (report_agx_annotations).
        if (m.path.parts[0].text.starts_with("agx_") && !model->doc->bundle)
          agx_annotations_.push_back({model, &m});
        std::vector<std::string_view> path = extended(m.path);
        if (prefix.empty()) {
          model->annotations[std::string(m.path.parts[0].text)] = *m.value;
        } else {
          add(Entry::Kind::Annotation, m, std::move(path));
        }
        break;
      }
      case MemberKind::Attribute: {
        std::vector<std::string_view> path = extended(m.path);
        add(Entry::Kind::Declare, m, path);
        model->entries.back().from_declaration = true;
        if (m.has_block) {
          prefix.push_back(m.path.parts[0].text);
          flatten(model, m.block, prefix);
          prefix.pop_back();
        }
        break;
      }
      case MemberKind::Becomes:
      case MemberKind::Assignment: {
        std::vector<std::string_view> path = extended(m.path);
        if (m.kind == MemberKind::Becomes) add(Entry::Kind::Becomes, m, path);
        if (m.value) add(Entry::Kind::Value, m, path);
        if (m.has_block) {
          const size_t size = prefix.size();
          for (const Ident& part : m.path.parts) prefix.push_back(part.text);
          flatten(model, m.block, prefix);
          prefix.resize(size);
        }
        break;
      }
    }
  }
}

// The unresolved models up a base chain are resolved farthest first, so that resolving a chain 100,000
// deep (the last model written first) recurses one level, not 100,000 (a stack overflow). Only a chain that
// ends (in a resolved model, an unknown name or no base): a cycle is left to resolve(), which reports it.
void Program::resolve_bases_first(ModelInfo* model) {
  std::vector<ModelInfo*> bases;
  std::unordered_set<const ModelInfo*> seen{model};
  for (const ModelInfo* m = model; m->decl && m->decl->base;) {
    ModelInfo* base = resolve_model_name(m->doc, *m->decl->base, /*report=*/false);
    if (!base || base->state != ModelInfo::State::Unresolved) break;
    if (!seen.insert(base).second) return;  // a cycle
    bases.push_back(base);
    m = base;
  }
  for (auto it = bases.rbegin(); it != bases.rend(); ++it) resolve(*it);
}

bool Program::resolve(ModelInfo* model) {
  switch (model->state) {
    case ModelInfo::State::Resolved:
      return true;
    case ModelInfo::State::Failed:
      return false;
    case ModelInfo::State::Resolving:
      sink_.report(DiagCode::CyclicInheritance, model->decl ? model->decl->name.range : SourceRange{},
                   "Cyclic inheritance involving " + model->qualified);
      model->state = ModelInfo::State::Failed;
      return false;
    case ModelInfo::State::Unresolved:
      break;
  }
  resolve_bases_first(model);
  model->state = ModelInfo::State::Resolving;
  const Decl& decl = *model->decl;
  bool ok = true;
  if (decl.base) {
    model->base = resolve_model_name(model->doc, *decl.base);
    if (!model->base) {
      ok = false;
    } else if (!resolve(model->base)) {
      if (model->state == ModelInfo::State::Failed) return false;  // the cycle was reported at this model
      ok = false;
    } else if (model->base->is_trait && !model->is_trait) {
      sink_.report(DiagCode::TraitRestriction, decl.base->range,
                   "Model " + model->name + " cannot extend trait " + model->base->qualified + "; use with");
      ok = false;
    } else if (!model->base->is_trait && model->is_trait) {
      sink_.report(DiagCode::TraitRestriction, decl.base->range,
                   "Trait " + model->name + " cannot extend model " + model->base->qualified);
      ok = false;
    }
  }
  for (const QualifiedName& name : decl.traits) {
    if (ModelInfo* trait = resolve_model_name(model->doc, name)) {
      if (!trait->is_trait) {
        sink_.report(DiagCode::TraitRestriction, name.range,
                     "`" + trait->qualified + "` is a model, not a trait; only traits go after `with`");
      } else {
        model->traits.push_back(trait);
      }
    }
  }
  std::vector<std::string_view> prefix;
  flatten(model, decl.body, prefix);
  for (ModelInfo* trait : model->traits) ok = resolve(trait) && ok;

  // Linearization: the model, its traits (each with its parent traits), then the base chain; built when
  // first asked for, from the traits and base resolved by now.
  model->linearize = ModelInfo::Linearize::Resolved;

  // Trait restrictions (spec §8): no shared ancestor between two traits of a model.
  for (size_t i = 0; i < model->traits.size(); ++i) {
    for (size_t j = i + 1; j < model->traits.size(); ++j) {
      for (ModelInfo* a : model->traits[i]->linearization()) {
        const auto& other = model->traits[j]->linearization();
        if (std::find(other.begin(), other.end(), a) != other.end()) {
          sink_.report(DiagCode::TraitRestriction, decl.name.range,
                       "Traits " + model->traits[i]->qualified + " and " + model->traits[j]->qualified +
                           " share common ancestor " + a->qualified);
          ok = false;
          break;
        }
      }
    }
  }

  // Index the entries; report duplicates within this one body.
  std::unordered_set<std::string> declared, assigned;
  for (const Entry& e : model->entries) {
    model->by_parent[e.parent_key].push_back(e.index);
    const bool assigns = e.kind == Entry::Kind::Value || e.kind == Entry::Kind::Becomes;
    for (size_t n = 1; n < e.path.size(); ++n) {
      model->prefixes.emplace(join(e.path, n), e.index);
      if (e.kind == Entry::Kind::Annotation && n == e.path.size() - 1) {
        model->annotations_below[join(e.path, n - 1)].push_back(e.index);
      } else if (e.kind != Entry::Kind::Annotation) {
        model->children_below[join(e.path, n - 1)].emplace_back(e.path[n - 1], assigns);
      }
    }
    if (e.kind != Entry::Kind::Declare && e.kind != Entry::Kind::Value) continue;
    const bool declares = e.kind == Entry::Kind::Declare;
    auto [key, fresh] = (declares ? declared : assigned).insert(join(e.path, e.path.size()));
    if (!fresh) {
      sink_.report(declares ? DiagCode::DuplicateAttribute : DiagCode::DuplicateAssignment,
                   e.member->path.range,
                   (declares ? "Duplicate attribute name " : "Duplicate assignment to ") + *key);
      ok = false;
    }
  }
  // Attribute names are unique across the base chain and traits. Only a name some other model declares
  // can clash, and only then are the ancestors listed (never kept: see linearization()).
  std::vector<ModelInfo*> ancestors;
  std::unordered_set<const ModelInfo*> ancestor_set;
  auto inherited = [&](std::string_view name) {
    auto found = declarers_.find(name);
    if (found == declarers_.end()) return false;
    if (ancestors.empty()) {
      ancestors = linearize_model(model);
      ancestor_set.insert(ancestors.begin() + 1, ancestors.end());
    }
    return std::any_of(found->second.begin(), found->second.end(),
                       [&](const ModelInfo* m) { return ancestor_set.count(m) > 0; });
  };
  for (const Entry& e : model->entries) {
    if (e.kind != Entry::Kind::Declare || e.path.size() != 1 || !inherited(e.path[0])) continue;
    for (size_t k = 1; k < ancestors.size(); ++k) {
      ModelInfo* other = ancestors[k];
      auto it = other->by_parent.find("");
      if (it == other->by_parent.end()) continue;
      for (uint32_t index : it->second) {
        const Entry& o = other->entries[index];
        if (o.kind != Entry::Kind::Declare || o.path[0] != e.path[0]) continue;
        const bool from_trait = other->is_trait && !model->is_trait;
        sink_.report(from_trait ? DiagCode::TraitRestriction : DiagCode::DuplicateAttribute,
                     e.member->path.range,
                     from_trait ? "Trait " + other->qualified + " injects attribute " +
                                      std::string(e.path[0]) + " which already exists in " + model->qualified
                                : "Duplicate attribute name " + std::string(e.path[0]) +
                                      " (already declared in " + other->qualified + ")");
        ok = false;
      }
    }
  }
  for (const Entry& e : model->entries) {
    if (e.kind != Entry::Kind::Declare || e.path.size() != 1) continue;
    std::vector<ModelInfo*>& declarers = declarers_[e.path[0]];
    if (declarers.empty() || declarers.back() != model) declarers.push_back(model);
  }
  std::set<std::string_view> methods;
  for (const MethodInfo& method : model->methods) {
    if (!methods.insert(method.member->path.parts[0].text).second) {
      sink_.report(DiagCode::DuplicateMethod, method.member->path.range,
                   "Duplicate method " + std::string(method.member->path.parts[0].text));
    }
  }
  model->state = ok ? ModelInfo::State::Resolved : ModelInfo::State::Failed;
  return ok;
}

std::string Program::suggestion(std::string_view name, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_distance = std::max<size_t>(1, name.size() / 3) + 1;
  for (const std::string& candidate : candidates) {
    if (candidate == name) continue;
    size_t d = edit_distance(name, candidate);
    if (d < best_distance) {
      best_distance = d;
      best = candidate;
    }
  }
  return best;
}

std::vector<std::string> Program::names_visible_from(DocumentInfo* doc) {
  load_all(doc->ns);
  std::vector<std::string> names;
  for (const auto& [name, sym] : doc->ns->symbols) names.push_back(name);
  for (const auto& [name, child] : doc->ns->children) names.push_back(name);
  for (const auto& [name, model] : doc->import_models) names.push_back(name);
  for (const auto& [name, ns] : doc->import_namespaces) names.push_back(name);
  for (const auto& [name, root] : bundle_roots_) names.push_back(name);
  return names;
}

}  // namespace openplx::frontend
