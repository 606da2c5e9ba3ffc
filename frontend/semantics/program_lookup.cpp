// The program, name lookup: a name in a namespace, its enclosing namespaces, bundles and host declarations,
// with a suggestion and a note when it is not found.
#include "frontend/semantics/program.h"

#include <algorithm>

#include "contract/edit_distance.h"
#include "frontend/bundles/embedded_bundles.h"
#include "frontend/natives/host_declarations.h"
#include "frontend/semantics/deprecations.h"
#include "frontend/semantics/unknown_name_notes.h"

namespace openplx::frontend {

Symbol Program::lookup_in(Namespace* ns, std::string_view name, const SourceRange* where) {
  ++name_steps_;
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
  if (Symbol s = lookup_imported(doc, name)) return s;
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
    const bool shown = sink_.error_count() < kMaxPrintedErrors;  // else its suggestion and notes go unread
    if (shown) {
      std::vector<std::string> candidates = names_visible_from(doc);
      if (extra) {
        std::vector<std::string> more = extra();
        candidates.insert(candidates.end(), more.begin(), more.end());
      }
      name_steps_ += candidates.size();
      std::string near = suggestion(name, candidates);
      if (!near.empty()) message += "; did you mean `" + near + "`?";
    } else {
      load_all(doc->ns);  // as names_visible_from would: the same files parsed either way
    }
    Diagnostic& d = sink_.report(DiagCode::UnknownName, where, message);
    if (shown) add_note(d, newer_bundle_note(name, bundles_));
    if (shown && !doc->bundle && doc->ns && doc->ns->qualified.empty())
      add_note(d, sibling_bundle_note(sources_.file(doc->doc.file).path(), name));  // lists a folder
  }
  return {};
}

Symbol Program::lookup_imported(DocumentInfo* doc, std::string_view name) {
  std::vector<Namespace*>& files = doc->imported_files;
  if (doc->imports_indexed != files.size()) {
    doc->imported_names.clear();
    doc->imported_folders.clear();
    for (size_t i = 0; i < files.size(); ++i) {
      const Namespace* ns = files[i];
      // lookup_in on such a file reads only its symbols (no folder, children, host names or renames).
      const bool plain = ns->loaded && ns->dir.empty() && !ns->bundle && !ns->legacy &&
                         ns->qualified.empty() && ns->children.empty() && ns->lazy_names.empty();
      if (!plain) {
        doc->imported_folders.push_back(i);
        continue;
      }
      for (const auto& [declared, symbol] : ns->symbols) doc->imported_names.emplace(declared, i);
    }
    doc->imports_indexed = files.size();
  }
  auto found = doc->imported_names.find(name);
  const size_t first = found == doc->imported_names.end() ? files.size() : found->second;
  for (size_t i : doc->imported_folders) {
    if (i > first) break;
    if (Symbol s = lookup_in(files[i], name)) return s;
  }
  if (first == files.size()) return {};
  return files[first]->symbols.find(name)->second;
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
      std::string message = "Unknown name " + to_string(name) + ": no `" + std::string(name.parts[i].text) +
                            "` in " + (ns->qualified.empty() ? ns->name : ns->qualified);
      if (sink_.error_count() < kMaxPrintedErrors) {
        std::vector<std::string> candidates;
        for (const auto& [n, sym] : ns->symbols) candidates.push_back(n);
        for (const auto& [n, child] : ns->children) candidates.push_back(n);
        name_steps_ += candidates.size();
        std::string near = suggestion(name.parts[i].text, candidates);
        if (!near.empty()) message += "; did you mean `" + near + "`?";
      }
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
