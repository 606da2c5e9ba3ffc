// Where each object is declared, as the user sees it, and its path in the tree: what every diagnostic and
// every resolved element of the system is named by.
#include <optional>
#include <string>
#include <tuple>

#include "snap/resolve_system.h"
#include "snap/system_builder.h"

namespace openplx::snap {
namespace {

namespace fe = openplx::frontend;

bool in_bundle(const fe::ModelInfo* m) {
  return m && m->doc && m->doc->bundle;
}

// Where source_of finds an object declared, from the object's owner `at` up: the nearest attribute declared
// outside the bundles, or the root model's declaration; nullopt where it falls back on the object's own
// attribute. The same for every object of one owner; `settled` is false when the climb ended at a free
// object, which the evaluator may yet adopt.
std::optional<fe::SourceRange> declared_above(const fe::ObjectGraph& graph, fe::ObjectId at, bool& settled) {
  settled = true;
  for (;;) {
    const fe::Object& obj = graph.at(at);
    if (obj.owner == fe::kNoObject) {
      settled = at == graph.root;
      if (in_bundle(obj.type)) return std::nullopt;
      return obj.type->decl ? obj.type->decl->range : fe::SourceRange{};
    }
    const fe::Slot* slot = graph.at(obj.owner).find(obj.name);
    if (!slot) return std::nullopt;
    if (!in_bundle(slot->declared_in())) return slot->declaration()->member->range;
    at = obj.owner;
  }
}

// Where an object is declared, as the user sees it: an attribute a bundle model declares (a suspension's
// `mate`, a wheel's `rim_alignment_mate`) is reported at the user's declaration of the instance holding it,
// the nearest enclosing attribute declared outside the bundles. `above` is declared_above, or a memo of it.
template <typename Above>
fe::SourceRange source_with(const fe::ObjectGraph& graph, fe::ObjectId id, Above&& above) {
  const fe::Object& obj = graph.at(id);
  if (obj.owner == fe::kNoObject) return obj.type->decl ? obj.type->decl->range : fe::SourceRange{};
  const fe::Slot* slot = graph.at(obj.owner).find(obj.name);
  if (!slot) return {};
  const fe::SourceRange own = slot->declaration()->member->range;
  if (!in_bundle(slot->declared_in())) return own;
  return above(obj.owner).value_or(own);
}

}  // namespace

namespace detail {

// source_of, with what lies above an owner found once (a body's signals and connectors share it).
fe::SourceRange SystemBuilder::where_of(fe::ObjectId id) {
  return source_with(ev_.graph(), id, [&](fe::ObjectId owner) {
    if (auto it = declared_above_.find(owner); it != declared_above_.end()) return it->second;
    bool settled;
    const std::optional<fe::SourceRange> above = declared_above(ev_.graph(), owner, settled);
    if (settled) declared_above_.emplace(owner, above);
    return above;
  });
}

// ObjectGraph::path, built on the owner's path when that is kept (a body's signals and connectors share
// it).
std::string SystemBuilder::path_of(fe::ObjectId id) {
  const fe::Object& obj = ev_.graph().at(id);
  const std::string* owner = obj.owner == fe::kNoObject ? nullptr : owner_path(obj.owner);
  return owner ? joined_path(*owner, obj.name) : ev_.graph().path(id);
}

// rooted_path, the last owner's remembered: siblings (a body's signals) are visited in a row.
const std::string* SystemBuilder::owner_path(fe::ObjectId owner) {
  if (owner == last_owner_ && last_owner_path_) return last_owner_path_;
  const std::string* path = rooted_path(owner);
  if (path) std::tie(last_owner_, last_owner_path_) = std::pair(owner, path);  // kept paths never move
  return path;
}

// The path of the root or of an object below it, kept: an owned object keeps its owner and name, so its
// path never changes. Null under a free object (a value the evaluator may yet adopt).
const std::string* SystemBuilder::rooted_path(fe::ObjectId id) {
  if (auto it = rooted_paths_.find(id); it != rooted_paths_.end()) return &it->second;
  const fe::Object& obj = ev_.graph().at(id);
  if (obj.owner == fe::kNoObject) {
    if (id != ev_.graph().root) return nullptr;
    return &rooted_paths_.emplace(id, ev_.graph().path(id)).first->second;
  }
  const std::string* owner = rooted_path(obj.owner);
  if (!owner) return nullptr;
  return &rooted_paths_.emplace(id, joined_path(*owner, obj.name)).first->second;
}

// ObjectGraph::path's rule: the owner's path, a dot and the name; no dot after an empty path (the root's).
std::string SystemBuilder::joined_path(const std::string& owner, const std::string& name) {
  std::string path;
  path.reserve(owner.size() + 1 + name.size());
  if (!owner.empty()) (path += owner) += '.';
  path += name;
  return path;
}

}  // namespace detail

frontend::SourceRange source_of(const frontend::ObjectGraph& graph, frontend::ObjectId id) {
  bool settled;
  return source_with(graph, id, [&](fe::ObjectId owner) { return declared_above(graph, owner, settled); });
}

}  // namespace openplx::snap
