// The declarations of a run: every parsed document, the namespace tree (bundles and their folders), and one
// ModelInfo per model or trait with its base, traits and flattened members. Bundles are read lazily, so a
// model pays only for the files it uses: a folder is listed and its files scanned for the names they declare
// (bundle_index.h) the first time a name inside it is looked up, and a file is parsed when one of its names
// is. Whatever lists all names of a namespace (a "did you mean") first parses the rest with load_all().
//
// Name lookup follows ../shared/spec/openplx-language.md §11: members first (done by the evaluator), then the
// namespace of the file (its folder, or the file itself outside bundles, plus its imports), then the
// enclosing bundle's root, then bundle names.
#pragma once

#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "frontend/bundles/bundles.h"
#include "frontend/diagnostics/diagnostics.h"
#include "frontend/diagnostics/source.h"
#include "frontend/syntax/ast.h"

namespace openplx::frontend {

struct ModelInfo;
struct Namespace;
struct DocumentInfo;
class Program;

// A bundle file known only by the names it declares (bundle_index.h), parsed on the first lookup of one.
struct LazyFile {
  FileId file;
  Namespace* ns;
  DocumentInfo* doc = nullptr;  // once parsed
};

// A loaded document and where its names resolve.
struct DocumentInfo {
  Document doc;
  Namespace* ns = nullptr;                                           // namespace its declarations belong to
  const BundleConfig* bundle = nullptr;                              // enclosing bundle, if any
  std::map<std::string, Namespace*, std::less<>> import_namespaces;  // `import @"x.openplx" as X`
  std::map<std::string, ModelInfo*, std::less<>> import_models;      // asset imports
  std::vector<Namespace*> imported_files;  // `import @"x.openplx"` without `as`: looked up like locals
  // The names of the plain files among imported_files (outside bundles: what they declare never changes)
  // -> the first of them declaring it, and where the others (bundle folders) sit: a name is found without
  // asking 10,000 imports one by one. Built on the first lookup, again if imports were added since.
  std::unordered_map<std::string_view, size_t> imported_names;
  std::vector<size_t> imported_folders;
  size_t imports_indexed = 0;
  // Type names this document's text resolved to a model without a word, by their parts joined with '\0': a
  // thousand `lN is Link` lines look the name up once (a name found never changes its meaning).
  std::unordered_map<std::string, ModelInfo*> model_names;
};

struct GlobalInfo {
  const Decl* decl = nullptr;
  DocumentInfo* doc = nullptr;
  std::string qualified;
};

struct Symbol {
  ModelInfo* model = nullptr;
  GlobalInfo* global = nullptr;
  Namespace* ns = nullptr;
  explicit operator bool() const { return model || global || ns; }
};

struct Namespace {
  std::string name;
  std::string qualified;  // "Physics3D.Bodies"; empty for a file's own scope outside bundles
  Namespace* parent = nullptr;
  std::string dir;  // folder on disk whose .openplx files fill it; empty when filled otherwise
  const embedded::Dir* embedded = nullptr;  // that folder as this build carries it, read instead
  const BundleConfig* bundle = nullptr;
  bool loaded = false;  // its folder was listed: children known, each file parsed or in lazy_files
  std::map<std::string, Namespace*, std::less<>> children;
  std::map<std::string, Symbol, std::less<>> symbols;        // of the files parsed so far
  std::vector<LazyFile*> lazy_files;                         // in path order; parsed or not
  std::map<std::string, LazyFile*, std::less<>> lazy_names;  // what each of them declares
  bool legacy = false;  // a 0.17.8 namespace whose models moved (see deprecations.h)
};

// One member of a model body, flattened: nested blocks become entries whose path starts with the
// attribute they configure (`inner is In:` + `v: 1` gives a Declare at [inner] and a Value at [inner, v]).
struct Entry {
  enum class Kind : uint8_t { Declare, Value, Becomes, Annotation, WithTrait };
  Kind kind;
  std::vector<std::string_view> path;  // for Annotation: the annotated attribute's path ([] = the model)
  std::string parent_key;              // path minus its last segment, joined with '.'
  const Member* member = nullptr;      // nullptr only for synthetic entries
  std::optional<ExprId> value;
  bool from_declaration = false;  // a Value that is a declaration's default, not an assignment
  uint32_t index = 0;             // position in the owning ModelInfo's entries
};

struct MethodInfo {
  const Member* member;
  ModelInfo* owner;
};

struct ModelInfo {
  std::string name;
  std::string qualified;
  const Decl* decl = nullptr;  // nullptr for synthetic models (asset imports, `T with X` types)
  DocumentInfo* doc = nullptr;
  bool is_trait = false;
  bool is_const = false;

  // Filled by Program::resolve().
  enum class State : uint8_t { Unresolved, Resolving, Resolved, Failed } state = State::Unresolved;
  ModelInfo* base = nullptr;
  std::vector<ModelInfo*> traits;  // direct `with` traits
  // The base linearization() takes (a resolved one), its depth and a jump further up (skew-binary jump
  // pointers, Myers 1983): whether a model extends another is found in O(log depth) steps, not by listing
  // a chain 40,000 deep. Traits extend only traits, so every model (not trait) it extends is on this chain.
  const ModelInfo* chain_base = nullptr;
  const ModelInfo* chain_jump = nullptr;  // nullptr: itself
  uint32_t chain_depth = 0;
  // Self, own traits (with their parents), then the base's, deduplicated. Built on first use and kept: a
  // chain of 10,000 models each extending the previous holds the list of the models used, not one per
  // model (quadratic time and memory).
  const std::vector<ModelInfo*>& linearization() const;
  // Which traits and base linearization() takes: none (resolve stopped before), those that resolved, or
  // all (a `T with X` type).
  enum class Linearize : uint8_t { No, Resolved, All } linearize = Linearize::No;
  std::vector<Entry> entries;
  std::unordered_map<std::string, std::vector<uint32_t>> by_parent;  // parent_key -> entries
  std::unordered_map<std::string, uint32_t> prefixes;  // every strict prefix of an entry path -> an entry
  // parent path -> the attributes under it with entries on their parts (true: some of them assign).
  std::unordered_map<std::string, std::vector<std::pair<std::string_view, bool>>> children_below;
  // parent path -> Annotation entries on the attributes directly under it.
  std::unordered_map<std::string, std::vector<uint32_t>> annotations_below;
  std::vector<MethodInfo> methods;                         // own methods
  std::map<std::string, ExprId, std::less<>> annotations;  // own model annotations

  bool is_subtype_of(const ModelInfo* other) const;  // reflexive; through bases and traits

 private:
  mutable std::vector<ModelInfo*> linearization_;
  mutable bool linearized_ = false;
};

struct OperatorInfo {
  const Decl* decl;
  DocumentInfo* doc;
};

class Program {
 public:
  Program(SourceManager& sources, DiagnosticSink& sink);
  ~Program();

  // Finds the bundles on `search_path` (see bundles.h). Call once before loading files.
  void set_bundles(std::vector<BundleConfig> bundles);
  // Registers one bundle (no-op when one of that name exists); returns the registered one.
  const BundleConfig* add_bundle(BundleConfig bundle);
  const std::deque<BundleConfig>& bundles() const { return bundles_; }
  // Whether names a user's bundle release leaves to its host are declared (natives/host_declarations.h); on
  // by default. Off, they are unknown names: how a test lists what a release expects from its host.
  void set_host_declarations(bool on) { host_declarations_ = on; }

  // Loads the user's file (and its imports). Returns nullptr when it cannot be read.
  DocumentInfo* load_main(const std::string& path);
  // Loads text held in memory as a stand-alone file named `path` (fuzzing, tests).
  DocumentInfo* load_text(const std::string& path, std::string text);
  // A URDF given directly (pipeline.cpp): no Urdf.PackagePath can name its mesh packages, so the import
  // reports a `package://` package it finds nowhere (UrdfImportOptions::packages_final).
  void set_urdf_given_directly() { urdf_given_directly_ = true; }
  bool urdf_given_directly() const { return urdf_given_directly_; }

  // Resolves base, traits and entries of a model; false (and diagnostics) on errors such as cycles.
  bool resolve(ModelInfo* model);

  // Name lookup for a name written in `doc`: its scope, the bundle root, then bundle names.
  // `extra` adds candidates (the scope's attribute names) to the "did you mean" of an unknown name.
  // `extra` lists more names for the "did you mean" of an unknown name; it runs only then.
  Symbol lookup(DocumentInfo* doc, std::string_view name, SourceRange where, bool report = true,
                const std::function<std::vector<std::string>()>& extra = {});
  // A member of a namespace (loads it on first use). With `where`, a 0.17.8 name is reported there as
  // deprecated.
  Symbol lookup_in(Namespace* ns, std::string_view name, const SourceRange* where = nullptr);
  // Resolves a qualified name (type names: no members).
  Symbol lookup_qualified(DocumentInfo* doc, const QualifiedName& name, bool report = true);
  ModelInfo* resolve_model_name(DocumentInfo* doc, const QualifiedName& name, bool report = true);

  const std::vector<OperatorInfo>& operators() const { return operators_; }
  ModelInfo* builtin_model(std::string_view qualified);  // e.g. "Math.Vec3"; loads its namespace
  // The model if its file is already parsed, without loading anything: a model nothing loaded cannot be the
  // base of anything evaluated (cheap role checks on models a document may not use).
  ModelInfo* loaded_model(std::string_view qualified) const;
  ModelInfo* make_trait_extension(ModelInfo* base, std::vector<ModelInfo*> traits);
  // Loads the namespace and parses every file of it still waiting for a lookup, so that `symbols` lists all
  // of its names (for "did you mean" suggestions).
  void load_all(Namespace* ns);
  // Documents parsed so far: the builtins, the user's file, its imports and the bundle files in use.
  size_t document_count() const { return documents_.size(); }
  // Steps spent on names so far: namespaces asked for one, models compared for an inherited attribute and
  // names offered to a "did you mean". tests/frontend/declaration_scaling_test.cpp holds it linear in the
  // number of declarations, a count a quadratic walk cannot fake and no timer can flake.
  size_t name_steps() const { return name_steps_; }

  SourceManager& sources() { return sources_; }
  DiagnosticSink& sink() { return sink_; }
  // Closest names to `name` among `candidates` (for "did you mean").
  static std::string suggestion(std::string_view name, const std::vector<std::string>& candidates);
  std::vector<std::string> names_visible_from(DocumentInfo* doc);
  // Lists the AGX annotations (`.agx_*`) the user wrote in the models `held` says the converted root holds
  // (its own, its parts' and the models they extend); those of models it does not use are not its concern.
  void report_agx_annotations(const std::function<bool(const ModelInfo*)>& held);

 private:
  // Lists the folder and parses its files, or indexes those that can wait; `eager` parses every one.
  void load_namespace(Namespace* ns, bool eager = false);
  DocumentInfo* parse_lazy(LazyFile* file);
  // The document of a file already loaded, or of one waiting in a namespace (parsed now); else nullptr.
  DocumentInfo* find_loaded(const std::string& path);
  DocumentInfo* load_document(FileId file, Namespace* ns, const BundleConfig* bundle);
  void declare(DocumentInfo* doc, Namespace* ns);
  void process_imports(DocumentInfo* doc);
  struct UrdfSource {
    FileId file;  // the URDF itself
    std::string text;
    std::vector<uint32_t> line_origins;
    std::string robot_name;
  };
  std::optional<UrdfSource> read_urdf(const std::string& path, const std::string& model,
                                      SourceRange import_range);
  bool urdf_given_directly_ = false;
  Namespace* new_namespace(std::string name, Namespace* parent, std::string dir, const BundleConfig* bundle);
  void flatten(ModelInfo* model, const std::vector<Member>& members, std::vector<std::string_view>& prefix);
  void resolve_bases_first(ModelInfo* model);
  bool bundle_visible(DocumentInfo* from, const BundleConfig* target) const;
  // `name` in `ns` when `release`, a user's bundle, leaves it to its host (natives/host_declarations.h):
  // declared in `ns` on its first lookup.
  Symbol host_declared(Namespace* ns, std::string_view name, const BundleConfig* release);
  // `name` (two parts or more) from the folders enclosing `doc`'s, innermost first, skipping the namespace
  // its first part already named (`tried`); quiet.
  Symbol lookup_in_enclosing(DocumentInfo* doc, const QualifiedName& name, Namespace* tried);
  // `name` in the files `doc` imports without `as`, the first that has it, as lookup_in on each would.
  Symbol lookup_imported(DocumentInfo* doc, std::string_view name);
  Namespace* bundle_root(std::string_view name);

  SourceManager& sources_;
  DiagnosticSink& sink_;
  Namespace* builtins_ = nullptr;  // models every file sees without a bundle (BundleConfig)
  bool host_declarations_ = true;
  std::deque<BundleConfig> bundles_;  // stable addresses: namespaces and documents point at them
  std::map<std::string, Namespace*, std::less<>> bundle_roots_;
  std::deque<Namespace> namespaces_;
  std::deque<DocumentInfo> documents_;
  std::deque<ModelInfo> models_;
  std::unordered_map<std::string, ModelInfo*> trait_extensions_;  // make_trait_extension's, by name
  // Models by the attributes they declare at their top level: an attribute declared again below an
  // ancestor is found without a walk over every ancestor of every model. A set, so that a name 40,000
  // unrelated models declare is checked against a model's few ancestors, not against all of them.
  std::unordered_map<std::string_view, std::unordered_set<const ModelInfo*>> declarers_;
  std::deque<GlobalInfo> globals_;
  std::vector<OperatorInfo> operators_;
  // builtin_model's answers by name (natives make a Math.Vec3 for every vector they return).
  struct NameHash {
    using is_transparent = void;
    size_t operator()(std::string_view name) const { return std::hash<std::string_view>()(name); }
  };
  std::unordered_map<std::string, ModelInfo*, NameHash, std::equal_to<>> builtin_models_;
  ModelInfo* find_builtin_model(std::string_view qualified);  // builtin_model without its memo
  std::map<std::string, DocumentInfo*> loaded_files_;         // absolute path -> document
  std::deque<LazyFile> lazy_files_;
  std::unordered_map<std::string, LazyFile*> lazy_by_path_;  // absolute path -> file waiting for a lookup
  struct AgxAnnotation {
    const ModelInfo* model;
    const Member* member;
  };
  std::vector<AgxAnnotation> agx_annotations_;  // in the user's files, for report_agx_annotations
  size_t name_steps_ = 0;
};

}  // namespace openplx::frontend
