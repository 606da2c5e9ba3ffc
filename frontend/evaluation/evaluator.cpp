#include "frontend/evaluation/evaluator.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <unordered_set>

#include "frontend/semantics/deprecations.h"
#include "frontend/natives/builtin_natives.h"
#include "frontend/semantics/unknown_name_notes.h"
#include "frontend/evaluation/value_format.h"

namespace openplx::frontend {
namespace {

// Deep enough for any real model (MuJoCo stops near 100 levels); a recursive model hits it quickly.
constexpr uint32_t kMaxInstanceDepth = 1000;
// How often owned default instances of one model may nest inside each other along an ownership chain.
constexpr uint32_t kMaxTypeRepeats = 3;
// Instances in one evaluation: far above any real model, low enough to stop a runaway before memory does.
constexpr size_t kMaxObjects = 20'000'000;
// Attributes whose values depend on each other in a chain this long would overflow the stack.
constexpr int kMaxEvalDepth = 1000;

std::string join_key(const std::string& rel, std::string_view slot) {
  return rel.empty() ? std::string(slot) : rel + "." + std::string(slot);
}

bool is_primitive_name(std::string_view name, TypeKind& kind) {
  if (name == "Real")
    kind = TypeKind::Real;
  else if (name == "Int")
    kind = TypeKind::Int;
  else if (name == "Bool")
    kind = TypeKind::Bool;
  else if (name == "String")
    kind = TypeKind::String;
  else
    return false;
  return true;
}

}  // namespace

// ---------------------------------------------------------------------------------------------- types

std::string Type::describe() const {
  std::string out;
  switch (kind) {
    case TypeKind::Error:
      out = "<error>";
      break;
    case TypeKind::Int:
      out = "Int";
      break;
    case TypeKind::Real:
      out = "Real";
      break;
    case TypeKind::Bool:
      out = "Bool";
      break;
    case TypeKind::String:
      out = "String";
      break;
    case TypeKind::Model:
      out = model->qualified;
      break;
    case TypeKind::Union:
      for (size_t i = 0; i < alternatives.size(); ++i) out += (i ? " or " : "") + alternatives[i].describe();
      break;
  }
  return is_array ? out + "[]" : out;
}

std::string ObjectGraph::path(ObjectId id) const {
  // Called for every signal and diagnostic: measured first, then written back to front in one allocation.
  ObjectId top = id;
  size_t length = 0;
  for (ObjectId cur = id; cur != kNoObject; cur = objects[cur].owner) {
    top = cur;
    length += objects[cur].name.size() + 1;
  }
  const bool named_top = objects[top].is_const_singleton || (root != kNoObject && top != root);
  if (!named_top) length -= objects[top].name.size() + 1;
  if (length == 0) return {};
  std::string out(length - 1, '.');
  size_t end = out.size();
  for (ObjectId cur = id;; cur = objects[cur].owner) {
    if (cur == top && !named_top) break;
    const std::string& name = objects[cur].name;
    end -= name.size();
    out.replace(end, name.size(), name);
    if (cur == top) break;
    --end;  // the '.' before it
  }
  return out;
}

NativeRegistry& NativeRegistry::global() {
  static NativeRegistry registry;
  return registry;
}

// -------------------------------------------------------------------------------------- construction

Evaluator::Evaluator(Program& program, DiagnosticSink& sink) : program_(program), sink_(sink) {
  natives::register_builtin_natives();
}

std::string Evaluator::root_name() const {
  return graph_.root == kNoObject ? std::string() : graph_.at(graph_.root).name;
}

Type Evaluator::resolve_type_ref(DocumentInfo* doc, const TypeRef& ref) {
  Type t;
  TypeKind kind;
  if (ref.name.parts.size() == 1 && is_primitive_name(ref.name.parts[0].text, kind)) {
    t.kind = kind;
  } else if (ModelInfo* model = program_.resolve_model_name(doc, ref.name)) {
    if (program_.resolve(model)) t = Type::of_model(model);
  }
  t.is_array = ref.is_array && t.kind != TypeKind::Error;
  return t;
}

Type Evaluator::resolve_type(DocumentInfo* doc, const TypeExpr& type) {
  if (type.alternatives.empty()) return {};
  Type result;
  if (type.alternatives.size() == 1) {
    result = resolve_type_ref(doc, type.alternatives[0]);
  } else {
    result.kind = TypeKind::Union;
    for (const TypeRef& ref : type.alternatives) {
      Type alt = resolve_type_ref(doc, ref);
      if (alt.kind == TypeKind::Error) return {};
      result.alternatives.push_back(std::move(alt));
    }
  }
  if (!type.traits.empty() && result.kind == TypeKind::Model) {
    std::vector<ModelInfo*> traits;
    for (const QualifiedName& name : type.traits) {
      ModelInfo* trait = program_.resolve_model_name(doc, name);
      if (!trait || !program_.resolve(trait)) return {};
      if (!trait->is_trait) {
        sink_.report(DiagCode::TraitRestriction, name.range,
                     "`" + trait->qualified + "` is a model, not a trait; only traits go after `with`");
        return {};
      }
      traits.push_back(trait);
    }
    result.model = program_.make_trait_extension(result.model, std::move(traits));
  }
  return result;
}

std::vector<Evaluator::Level> Evaluator::levels_of(ObjectId id) const {
  std::vector<Level> levels;
  std::string rel;
  for (ObjectId cur = id; cur != kNoObject; cur = graph_.at(cur).owner) {
    levels.push_back({cur, rel});
    rel = rel.empty() ? graph_.at(cur).name : graph_.at(cur).name + "." + rel;
  }
  std::reverse(levels.begin(), levels.end());
  return levels;
}

Evaluator::Targeting Evaluator::collect_targeting(const std::vector<Level>& levels) const {
  // Every entry aimed at the instance's own attributes, in priority order: the level nearest the root
  // first, then the most derived model of that level's type. Built once per instance, so each attribute is
  // a hash lookup instead of a walk over all levels.
  Targeting t;
  for (uint32_t i = 0; i < levels.size(); ++i) {
    if (levels[i].left_out) continue;
    for (ModelInfo* model : graph_.at(levels[i].object).type->linearization()) {
      if (auto it = model->by_parent.find(levels[i].rel); it != model->by_parent.end()) {
        for (uint32_t index : it->second) {
          const Entry& e = model->entries[index];
          t.by_name[e.path.back()].push_back(static_cast<uint32_t>(t.ordered.size()));
          t.ordered.push_back({&e, model, levels[i].object, i});
        }
      }
      if (auto it = model->children_below.find(levels[i].rel); it != model->children_below.end()) {
        for (const auto& [name, assigned] : it->second) t.below[name] = t.below[name] || assigned;
      }
      if (auto it = model->annotations_below.find(levels[i].rel); it != model->annotations_below.end()) {
        for (uint32_t index : it->second) t.annotations.emplace_back(&model->entries[index], model);
      }
    }
  }
  return t;
}

std::vector<uint32_t> Evaluator::candidates(const Targeting& t, const Object& object, std::string_view slot) {
  // The entries that may bind this attribute: its own name's, and those written with its 0.17.8 name.
  std::vector<uint32_t> mine;
  if (auto it = t.by_name.find(slot); it != t.by_name.end()) mine = it->second;
  if (std::optional<std::string_view> legacy = legacy_attribute(slot)) {
    auto it = t.by_name.find(*legacy);
    if (it != t.by_name.end() && is_renamed_to(object, *legacy, slot)) {
      mine.insert(mine.end(), it->second.begin(), it->second.end());
      std::sort(mine.begin(), mine.end());  // back in priority order
    }
  }
  return mine;
}

Binding Evaluator::pick_value(const Targeting& t, const std::vector<uint32_t>& candidates,
                              bool include_declarations) {
  // Assignments anywhere beat declaration defaults.
  for (uint32_t k : candidates) {
    if (t.ordered[k].entry->kind == Entry::Kind::Value) return t.ordered[k];
  }
  if (include_declarations) {
    for (uint32_t k : candidates) {
      const Entry& e = *t.ordered[k].entry;
      if (e.kind == Entry::Kind::Declare && e.value.has_value()) return t.ordered[k];
    }
  }
  return {};
}

Type Evaluator::merged_becomes_type(const std::vector<Binding>& all) {
  Type merged = resolve_type(all.front().model->doc, all.front().entry->member->type);
  for (size_t k = 1; k < all.size() && merged.kind == TypeKind::Model; ++k) {
    Type other = resolve_type(all[k].model->doc, all[k].entry->member->type);
    if (other.kind != TypeKind::Model || other.is_array != merged.is_array) continue;
    if (merged.model->is_subtype_of(other.model)) continue;
    if (other.model->is_subtype_of(merged.model)) {
      merged = other;
      continue;
    }
    // `X with A` and `X with B` meet in `X with A, B` (the more derived base, all the traits).
    auto split = [](ModelInfo* m, std::vector<ModelInfo*>& traits) {
      if (m->decl || !m->base) return m;
      traits.insert(traits.end(), m->traits.begin(), m->traits.end());
      return m->base;
    };
    std::vector<ModelInfo*> traits;
    ModelInfo* a = split(merged.model, traits);
    ModelInfo* b = split(other.model, traits);
    ModelInfo* base = a->is_subtype_of(b) ? a : (b->is_subtype_of(a) ? b : nullptr);
    if (!base) {
      sink_.report(DiagCode::IncompatibleBecomes, all[k].entry->member->type.range,
                   "Type " + other.describe() + " is not compatible with " + merged.describe() +
                       ", which another `becomes` of the same attribute chose");
      return {};
    }
    std::vector<ModelInfo*> unique;
    for (ModelInfo* t : traits) {
      if (std::find(unique.begin(), unique.end(), t) == unique.end()) unique.push_back(t);
    }
    merged.model = program_.make_trait_extension(base, std::move(unique));
  }
  return merged;
}

bool Evaluator::is_renamed_to(const Object& object, std::string_view written, std::string_view slot) {
  std::optional<std::string_view> current = renamed_attribute(written);
  return current && *current == slot && !object.has(written);
}

const Entry* Evaluator::entry_below(ObjectId id, std::string_view slot) const {
  // Only on the error path: the first entry (not an annotation) on a part of `slot`, at any level.
  for (const Level& level : levels_of(id)) {
    const std::string key = join_key(level.rel, slot);
    for (ModelInfo* model : graph_.at(level.object).type->linearization()) {
      auto it = model->prefixes.find(key);
      if (it != model->prefixes.end() && model->entries[it->second].kind != Entry::Kind::Annotation) {
        return &model->entries[it->second];
      }
    }
  }
  return nullptr;
}

ObjectId Evaluator::new_object(ModelInfo* type, ObjectId owner, std::string name) {
  const ObjectId id = static_cast<ObjectId>(graph_.objects.size());
  Object& obj = graph_.objects.emplace_back();
  obj.type = type;
  obj.owner = owner;
  obj.name = std::move(name);
  obj.depth = owner == kNoObject ? 0 : graph_.at(owner).depth + 1;
  build_slots(id);
  return id;
}

template <typename Visit>
void Evaluator::for_each_reaching(const std::vector<ObjectId>& chain, Visit&& visit) const {
  const uint32_t own_level = static_cast<uint32_t>(chain.size() - 1);
  for (uint32_t i = 0; i < own_level; ++i) {
    const EntryReach::Node* node = entry_reach_.root(graph_.at(chain[i]).type);
    for (uint32_t k = i + 1; node && k <= own_level; ++k)
      node = EntryReach::step(node, graph_.at(chain[k]).name);
    if (node && node->targeted && visit(i, *node)) return;
  }
}

bool Evaluator::assigns_only(const ModelInfo* type, const EntryReach::Node& node) const {
  if (node.assigns_only < 0) node.assigns_only = assigns_only(type, node.rel);
  return node.assigns_only;
}

bool Evaluator::assigns_only(const ModelInfo* type, const std::string& rel) const {
  for (const ModelInfo* model : type->linearization()) {
    if (model->children_below.count(rel) || model->annotations_below.count(rel)) return false;
    auto it = model->by_parent.find(rel);
    if (it == model->by_parent.end()) continue;
    for (uint32_t index : it->second) {
      if (model->entries[index].kind != Entry::Kind::Value) return false;
    }
  }
  return true;
}

void Evaluator::owner_chain(ObjectId id, std::vector<ObjectId>& chain) const {
  chain.clear();
  for (ObjectId cur = id; cur != kNoObject; cur = graph_.at(cur).owner) chain.push_back(cur);
  std::reverse(chain.begin(), chain.end());
}

uint32_t Evaluator::reach_state(const std::vector<ObjectId>& chain) {
  ReachState state;
  const uint32_t own_level = static_cast<uint32_t>(chain.size() - 1);
  for (uint32_t i = 0; i <= own_level; ++i) {
    const EntryReach::Node* node = entry_reach_.root(graph_.at(chain[i]).type);
    for (uint32_t k = i + 1; node && k <= own_level; ++k)
      node = EntryReach::step(node, graph_.at(chain[k]).name);
    // A node with nothing below it cannot reach a part: left out, so that instances differing only there
    // (each hinge assigned its own connectors) share their parts' layouts.
    if (node && !node->below.empty()) state.emplace_back(own_level - i, node);
  }
  return reach_ids_.try_emplace(std::move(state), static_cast<uint32_t>(reach_ids_.size() + 1)).first->second;
}

void Evaluator::build_slots(ObjectId id) {
  std::vector<ObjectId>& chain = chain_;  // reused, building slots creates no objects
  owner_chain(id, chain);
  const uint32_t own_level = static_cast<uint32_t>(chain.size() - 1);
  // A part of an owner whose reach state is known: its layout was worked out for the first such part.
  PartKey part{0, 0, nullptr, graph_.at(id).type};
  if (const ObjectId owner = graph_.at(id).owner; owner != kNoObject && graph_.at(owner).reach) {
    const Object& o = graph_.at(owner);
    if (auto slot = o.index->find(graph_.at(id).name); slot != o.index->end()) {
      part = {o.reach, slot->second, o.index.get(), graph_.at(id).type};
      if (auto it = part_layouts_.find(part); it != part_layouts_.end()) {
        copy_layout(id, *it->second.layout, chain, own_level);
        graph_.at(id).reach = it->second.reach;
        return;
      }
    }
  }
  build_slots_by_key(id, chain, own_level);
  graph_.at(id).reach = reach_state(chain);
  if (part.owner_reach) {
    if (auto it = layouts_.find(full_layout_key_); it != layouts_.end())
      part_layouts_.emplace(part, PartLayout{&it->second, graph_.at(id).reach});
  }
}

void Evaluator::build_slots_by_key(ObjectId id, const std::vector<ObjectId>& chain, uint32_t own_level) {
  // An instance's layout (its slots, their types and the entries that bind them) is decided by its type and
  // by the enclosing models whose entries reach it, each at its distance and relative path. Instances
  // that agree on all of that (the inertia of every Link, the outputs of every body) share one layout:
  // the first is built in full, the others copy it and rebind `this` to their own ancestors.
  // An enclosing model that only assigns values to the instance's attributes (`hinge: connectors: [...]`,
  // one per instance) leaves the layout alone: its entries are laid over a copy (overlay_assignments).
  // Keys are bytes: each reaching ancestor's type, distance and node (a node stands for one path below one
  // type). Built in reused buffers: most instances only look their layout up.
  std::string& key = layout_key_;
  std::string& full_key = full_layout_key_;
  std::vector<Overlay>& overlays = overlays_;
  key.assign(reinterpret_cast<const char*>(&graph_.at(id).type), sizeof(ModelInfo*));
  full_key = key;
  overlays.clear();
  for_each_reaching(chain, [&](uint32_t i, const EntryReach::Node& node) {
    const ModelInfo* type = graph_.at(chain[i]).type;
    const uint32_t distance = own_level - i;
    const EntryReach::Node* at = &node;
    char part[sizeof(type) + sizeof(distance) + sizeof(at)];
    std::memcpy(part, &type, sizeof(type));
    std::memcpy(part + sizeof(type), &distance, sizeof(distance));
    std::memcpy(part + sizeof(type) + sizeof(distance), &at, sizeof(at));
    full_key.append(part, sizeof(part));
    if (assigns_only(type, node)) {
      overlays.emplace_back(i, at);
    } else {
      key.append(part, sizeof(part));
    }
    return false;
  });
  if (auto found = layouts_.find(full_key); found != layouts_.end()) {
    copy_layout(id, found->second, chain, own_level);
    return;
  }
  ModelInfo* const type = graph_.at(id).type;
  if (overlays.empty() || !use_layout(id, key, chain, own_level, overlays) ||
      !overlay_assignments(id, chain, overlays)) {
    graph_.at(id).type = type;
    use_layout(id, full_key, chain, own_level, {});
    return;
  }
  // The others with the same entries copy the result.
  const Object& built = graph_.at(id);
  Layout& layout = layouts_[full_key];
  layout = {built.type, own_level, built.slots, built.index, built.infos, next_layout_++};
  graph_.at(id).layout = layout.id;
}

void Evaluator::copy_layout(ObjectId id, const Layout& l, const std::vector<ObjectId>& chain,
                            uint32_t own_level) {
  Object& obj = graph_.at(id);
  obj.type = l.type;
  obj.slots = l.slots;
  for (Slot& slot : obj.slots) {  // rebind the entries to this instance's own ancestors
    Binding& b = slot.binding;
    if (!b.entry) continue;
    b.level = own_level - (l.own_level - b.level);
    b.self = chain[b.level];
  }
  obj.index = l.index;
  obj.infos = l.infos;
  obj.layout = l.id;
}

bool Evaluator::use_layout(ObjectId id, const std::string& key, const std::vector<ObjectId>& chain,
                           uint32_t own_level, const std::vector<Overlay>& left_out) {
  auto [layout, fresh] = layouts_.try_emplace(key);
  if (!fresh) {
    copy_layout(id, layout->second, chain, own_level);
    return true;
  }
  graph_.at(id).slots.clear();
  std::vector<Level> levels = levels_of(id);
  for (const auto& [level, node] : left_out) levels[level].left_out = true;
  build_slots_from(id, levels);
  Object& built = graph_.at(id);
  layout->second = {built.type, own_level, built.slots, built.index, built.infos, next_layout_++};
  built.layout = layout->second.id;
  return true;
}

bool Evaluator::overlay_assignments(ObjectId id, const std::vector<ObjectId>& chain,
                                    const std::vector<Overlay>& overlays) {
  // Entries aimed at attributes the layout lacks (unknown or 0.17.8 names) take the full path, which
  // reports them.
  Object& obj = graph_.at(id);
  for (const auto& [level, node] : overlays) {
    for (const ModelInfo* model : graph_.at(chain[level]).type->linearization()) {
      auto it = model->by_parent.find(node->rel);
      if (it == model->by_parent.end()) continue;
      for (uint32_t index : it->second) {
        if (!obj.has(model->entries[index].path.back())) return false;
      }
    }
  }
  // Priority as in collect_targeting and pick_value: the level nearest the root, then the most derived
  // model; an assignment beats a declaration's default.
  std::vector<bool> overlaid(obj.slots.size(), false);
  for (const auto& [level, node] : overlays) {
    for (ModelInfo* model : graph_.at(chain[level]).type->linearization()) {
      auto it = model->by_parent.find(node->rel);
      if (it == model->by_parent.end()) continue;
      for (uint32_t index : it->second) {
        const Entry& e = model->entries[index];
        const uint32_t k = obj.index->at(e.path.back());
        Slot& slot = obj.slots[k];
        if (overlaid[k]) continue;
        const Binding& b = slot.binding;
        if (b.entry && b.entry->kind == Entry::Kind::Value && b.level < level) continue;
        slot.binding = {&e, model, chain[level], level};
        slot.explicit_value = true;
        overlaid[k] = true;
      }
    }
  }
  return true;
}

void Evaluator::build_slots_from(ObjectId id, const std::vector<Level>& levels) {
  const uint32_t own_level = static_cast<uint32_t>(levels.size() - 1);
  Targeting targeting = collect_targeting(levels);
  const std::vector<Binding>& ordered = targeting.ordered;

  // `with` lines in a nested block add traits to this one instance.
  std::vector<ModelInfo*> extra_traits;
  for (const Binding& b : ordered) {
    if (b.entry->kind != Entry::Kind::WithTrait || b.level == own_level) continue;
    ModelInfo* trait = program_.resolve_model_name(b.model->doc, b.entry->member->path);
    if (trait && program_.resolve(trait) && trait->is_trait) extra_traits.push_back(trait);
  }
  if (!extra_traits.empty()) {
    graph_.at(id).type = program_.make_trait_extension(graph_.at(id).type, std::move(extra_traits));
    // The traits bring entries of their own (`visible becomes ... with ...` in a surface feature).
    targeting = collect_targeting(levels);
  }
  Object& obj = graph_.at(id);
  auto index = std::make_shared<SlotIndex>();
  obj.index = index;
  std::vector<SlotInfo> infos;  // beside obj.slots, index for index; shared by the layout once built
  auto add_slot = [&](const Entry& e, ModelInfo* model) {
    const std::string_view name = e.path.back();
    if (index->count(name)) {
      sink_.report(DiagCode::DuplicateAttribute, e.member->path.range,
                   "Duplicate attribute name " + std::string(name) + " in " + obj.type->qualified);
      return;
    }
    SlotInfo info;
    info.name = name;
    info.declaration = &e;
    info.declared_in = model;
    info.optional = e.member->is_optional || e.member->is_reference;  // a reference nobody set stays unset
    index->emplace(name, static_cast<uint32_t>(obj.slots.size()));
    infos.push_back(std::move(info));
    obj.slots.emplace_back();
  };
  // Declaration order: the root-most base first, then traits, then the model itself...
  const auto& lin = obj.type->linearization();
  for (auto it = lin.rbegin(); it != lin.rend(); ++it) {
    auto found = (*it)->by_parent.find("");
    if (found == (*it)->by_parent.end()) continue;
    for (uint32_t index : found->second) {
      const Entry& e = (*it)->entries[index];
      if (e.kind == Entry::Kind::Declare) add_slot(e, *it);
    }
  }
  // ...then attributes added by the nested blocks of owners.
  for (const Binding& b : ordered) {
    if (b.entry->kind == Entry::Kind::Declare && b.level != own_level) add_slot(*b.entry, b.model);
  }
  // Entries aimed at attributes this instance does not have.
  for (const Binding& b : ordered) {
    const Entry& e = *b.entry;
    if (e.kind == Entry::Kind::Annotation || e.kind == Entry::Kind::WithTrait) continue;
    if (obj.has(e.path.back()) || !reported_unknown_.insert(&e).second) continue;
    if (std::optional<std::string_view> current = renamed_attribute(e.path.back());
        current && obj.has(*current)) {
      sink_.report(
          DiagCode::DeprecatedName, e.member->path.range,
          "`" + std::string(e.path.back()) + "` is the 0.17.8 name; use `" + std::string(*current) + "`");
      continue;
    }
    std::vector<std::string> names;
    for (const SlotInfo& s : infos) names.emplace_back(s.name);
    std::string message = "Unknown attribute " + std::string(e.path.back()) + " in " + obj.type->qualified;
    std::string near = Program::suggestion(e.path.back(), names);
    if (!near.empty()) message += "; did you mean `" + near + "`?";
    const QualifiedName& path = e.member->path;
    sink_.report(DiagCode::UnknownAttribute, path.parts.empty() ? e.member->range : path.parts.back().range,
                 message);
  }
  // Types, `becomes`, bindings and annotations.
  for (size_t k = 0; k < obj.slots.size(); ++k) {
    Slot& slot = obj.slots[k];
    SlotInfo& info = infos[k];
    // The entries that may bind this attribute: its own name's, and those written with its 0.17.8 name.
    const std::vector<uint32_t> mine = candidates(targeting, obj, info.name);

    const Type& declared = declared_type(*info.declaration, info.declared_in);
    info.type = &declared;
    std::vector<Binding> all_becomes;
    for (uint32_t k : mine) {
      const Binding& b = ordered[k];
      if (b.entry->kind != Entry::Kind::Becomes) continue;
      if (!all_becomes.empty() && all_becomes.front().level != b.level) break;  // only the winning level
      all_becomes.push_back(b);
    }
    if (!all_becomes.empty()) {
      const Binding& becomes = all_becomes.front();
      Type narrowed = merged_becomes_type(all_becomes);
      const Type& old = declared;
      bool compatible = false;
      if (old.is_primitive() && old.kind != TypeKind::Error) {
        sink_.report(DiagCode::IncompatibleBecomes, becomes.entry->member->path.range,
                     "Cannot specialise primitive attribute " + std::string(info.name));
        narrowed = {};
      } else if (narrowed.kind == TypeKind::Model && old.kind == TypeKind::Model) {
        compatible = narrowed.is_array == old.is_array && narrowed.model->is_subtype_of(old.model);
      } else if (narrowed.kind == TypeKind::Model && old.kind == TypeKind::Union) {
        for (const Type& alt : old.alternatives) {
          compatible =
              compatible || (alt.kind == TypeKind::Model && narrowed.model->is_subtype_of(alt.model));
        }
      }
      if (!compatible && narrowed.kind != TypeKind::Error && old.kind != TypeKind::Error) {
        sink_.report(DiagCode::IncompatibleBecomes, becomes.entry->member->type.range,
                     "Type " + narrowed.describe() + " is not compatible with " + old.describe());
        narrowed = {};
      }
      info.type = &narrowed_types_.emplace_back(std::move(narrowed));
    }
    slot.binding = pick_value(targeting, mine, true);
    auto part = targeting.below.find(info.name);
    slot.entries_below = part != targeting.below.end();
    slot.explicit_value = (slot.binding.entry && slot.binding.entry->kind == Entry::Kind::Value) ||
                          (slot.entries_below && part->second);
  }
  // Annotations: the entry nearest the root (then the most derived) wins, so apply in reverse.
  for (auto it = targeting.annotations.rbegin(); it != targeting.annotations.rend(); ++it) {
    const Entry& e = *it->first;
    auto slot = obj.index->find(e.path[e.path.size() - 2]);
    if (slot != obj.index->end()) {
      auto& annotations = infos[slot->second].annotations;
      if (!annotations) annotations = std::make_shared<std::map<std::string, AnnotationValue, std::less<>>>();
      (*annotations)[std::string(e.path.back())] = {*e.value, &it->second->doc->doc};
    }
  }
  auto shared = std::make_shared<const std::vector<SlotInfo>>(std::move(infos));
  for (size_t k = 0; k < obj.slots.size(); ++k) obj.slots[k].info = &(*shared)[k];
  obj.infos = std::move(shared);
}

const Type& Evaluator::declared_type(const Entry& declaration, ModelInfo* model) {
  auto it = declared_types_.find(&declaration);
  if (it != declared_types_.end()) return it->second;
  Type type = resolve_type(model->doc, declaration.member->type);
  return declared_types_.emplace(&declaration, std::move(type)).first->second;  // nodes never move
}

ObjectId Evaluator::instantiate_root(ModelInfo* model) {
  if (!program_.resolve(model)) return kNoObject;
  if (model->is_trait) {
    sink_.report(DiagCode::CannotInstantiateTrait, model->decl->name.range,
                 "Cannot instantiate trait " + model->name);
    return kNoObject;
  }
  graph_.root = new_object(model, kNoObject, model->name);
  return graph_.root;
}

ObjectId Evaluator::make_free_object(ModelInfo* model) {
  return new_object(model, kNoObject, model->name);
}

void Evaluator::preset(ObjectId object, std::string_view name, Value value) {
  Object& obj = graph_.at(object);
  auto it = obj.index->find(name);
  if (it == obj.index->end()) return;
  Slot& slot = obj.slots[it->second];
  slot.value = std::move(value);
  slot.state = Slot::State::Done;
  slot.preset = true;
  slot.explicit_value = true;
  slot.binding = {};
  slot.owns = slot.value.kind == Value::Kind::Object && graph_.at(slot.value.object).owner == kNoObject;
  if (slot.owns) {
    Object& child = graph_.at(slot.value.object);
    child.owner = object;
    child.name = std::string(name);
    child.depth = obj.depth + 1;
    forget_reach(slot.value.object);  // worked out where it was made, free
  }
}

bool Evaluator::reached_by_entries(ObjectId id) const {
  std::vector<ObjectId>& chain = reach_chain_;  // reused: asked once per adopted value
  owner_chain(id, chain);
  bool reached = false;
  for_each_reaching(chain, [&](uint32_t, const EntryReach::Node&) { return reached = true; });
  return reached;
}

void Evaluator::forget_reach(ObjectId id) {
  Object& obj = graph_.at(id);
  obj.reach = 0;
  for (const Slot& slot : obj.slots) {
    if (slot.owns && slot.value.kind == Value::Kind::Object) forget_reach(slot.value.object);
  }
}

void Evaluator::move_free_subtree(ObjectId id, uint32_t levels) {
  Object& obj = graph_.at(id);
  obj.depth += levels;
  for (Slot& slot : obj.slots) {
    if (slot.binding.entry) slot.binding.level += levels;
    if (slot.preset && slot.owns) move_free_subtree(slot.value.object, levels);
  }
}

void Evaluator::adopt(ObjectId child, ObjectId owner, const std::string& name, uint32_t level) {
  {
    Object& obj = graph_.at(child);
    obj.owner = owner;
    obj.name = name;
    obj.depth = graph_.at(owner).depth + 1;
  }
  forget_reach(child);  // worked out where it was made, free; its parts' layouts are found afresh
  // Most values (`main_axis: Math.Vec3.Y_AXIS()`) have no entries aimed at their parts: their bindings
  // stay, a level deeper for every level above them.
  if (!reached_by_entries(child)) {
    const uint32_t depth = graph_.at(child).depth;
    graph_.at(child).depth = 0;  // where it was made, free
    move_free_subtree(child, depth);
    return;
  }
  // The value came with its fields set at `level`; assignments to its parts from that level or nearer the
  // root still win (`position: {0, 0, 1}` in a body, `body.position.z: 2` in its owner).
  const Targeting targeting = collect_targeting(levels_of(child));
  Object& obj = graph_.at(child);
  for (uint32_t i = 0; i < obj.slots.size(); ++i) {
    Slot& slot = obj.slots[i];
    const std::vector<uint32_t> mine = candidates(targeting, obj, slot.name());
    Binding assigned = pick_value(targeting, mine, false);
    if (slot.preset) {
      if (assigned.entry && assigned.level <= level) {
        slot.binding = assigned;
        slot.state = Slot::State::Pending;
        slot.preset = false;
        slot.owns = false;
      } else if (slot.owns) {
        adopt(slot.value.object, child, std::string(slot.name()), level);
      }
    } else if (slot.state == Slot::State::Pending) {
      slot.binding = pick_value(targeting, mine, true);
    }
    slot.explicit_value = slot.explicit_value || assigned.entry != nullptr;
  }
}

ObjectId Evaluator::singleton(ModelInfo* model) {
  if (auto it = singletons_.find(model); it != singletons_.end()) return it->second;
  ObjectId id = new_object(model, kNoObject, model->qualified);
  graph_.at(id).is_const_singleton = true;
  singletons_[model] = id;
  return id;
}

std::string Evaluator::slot_path(ObjectId id, std::string_view slot) const {
  std::string base = graph_.path(id);
  const Object& top = [&]() -> const Object& {
    ObjectId cur = id;
    while (graph_.at(cur).owner != kNoObject) cur = graph_.at(cur).owner;
    return graph_.at(cur);
  }();
  std::string prefix = &top == &graph_.at(graph_.root) ? root_name() : "";
  std::string out = prefix;
  if (!base.empty()) out += (out.empty() ? "" : ".") + base;
  out += (out.empty() ? "" : ".") + std::string(slot);
  return out;
}

// ---------------------------------------------------------------------------------------- evaluation

const Value& Evaluator::value(ObjectId object, uint32_t slot) {
  if (tracking_) graph_.at(object).slots[slot].used = true;
  if (graph_.at(object).slots[slot].state != Slot::State::Done) evaluate_slot(object, slot);
  return graph_.at(object).slots[slot].value;
}

const Value* Evaluator::value(ObjectId object, std::string_view slot) {
  const SlotIndex& index = *graph_.at(object).index;
  auto it = index.find(slot);
  if (it == index.end()) return nullptr;
  graph_.at(object).slots[it->second].used = true;  // natives and the pipeline read by name
  return &value(object, it->second);
}

void Evaluator::evaluate_slot(ObjectId id, uint32_t slot_index) {
  Slot* slot = &graph_.at(id).slots[slot_index];
  if (slot->state == Slot::State::Done) return;
  const SourceRange where =
      slot->binding.entry ? slot->binding.entry->member->range : slot->declaration()->member->range;
  if (slot->state == Slot::State::Evaluating) {
    sink_.report(DiagCode::CyclicDependency, where,
                 "Cyclic dependency detected at " + slot_path(id, slot->name()));
    slot->value = Value::error();
    slot->state = Slot::State::Done;
    return;
  }
  if (eval_depth_ >= kMaxEvalDepth) {
    sink_.report(DiagCode::EvaluationTooDeep, where,
                 "evaluating " + slot_path(id, slot->name()) + " needs a chain of more than " +
                     std::to_string(kMaxEvalDepth) + " dependent attributes");
    slot->value = Value::error();
    slot->state = Slot::State::Done;
    return;
  }
  slot->state = Slot::State::Evaluating;
  ++eval_depth_;
  Value result;
  bool owns = false;
  const Type& type = *slot->type();
  if (type.kind == TypeKind::Error) {
    result = Value::error();
  } else if (!slot->binding.entry) {
    if (slot->optional()) {
      // stays unset, whatever its type (spec §5.1)
    } else if (type.is_array) {
      result = Value::of_array({});  // an array nobody assigned is empty
    } else if (type.kind == TypeKind::Model) {
      result = owned_default(id, *slot);
      slot = &graph_.at(id).slots[slot_index];
      owns = result.kind == Value::Kind::Object && graph_.at(result.object).owner == id;
    } else {
      sink_.report(DiagCode::MissingAssignment, slot->declaration()->member->range,
                   "Missing assignment " + slot_path(id, slot->name()) + ", owning model is not complete");
      result = Value::error();
    }
  } else {
    const Binding binding = slot->binding;
    Scope scope{binding.model->doc, binding.model, binding.self};
    const ExprId expr = *binding.entry->value;
    const bool path = is_path_expression(binding.model->doc->doc, expr);
    const bool outer_reads_instance = std::exchange(reads_instance_, false);
    Value v = eval(expr, scope, &type);
    slot = &graph_.at(id).slots[slot_index];
    if (v.kind == Value::Kind::Object && graph_.at(v.object).owner == kNoObject &&
        !graph_.at(v.object).is_const_singleton && !path) {
      adopt(v.object, id, std::string(slot->name()), binding.level);
      slot = &graph_.at(id).slots[slot_index];
      owns = true;
      auto [it, first] = instance_free_.try_emplace(binding.entry, !reads_instance_);
      if (!first) it->second = it->second && !reads_instance_;
    }
    reads_instance_ = outer_reads_instance;
    result = convert(std::move(v), type, binding.model->doc->doc.expr(expr).range,
                     [&] { return slot_path(id, graph_.at(id).slots[slot_index].name()); });
  }
  slot = &graph_.at(id).slots[slot_index];
  // Assignments to parts of a reference or of a primitive have nowhere to go.
  if (!owns && !result.is_error() && slot->entries_below) {
    const Entry* e = entry_below(id, slot->name());
    if (e && result.kind == Value::Kind::Object && graph_.at(result.object).is_const_singleton) {
      sink_.report(DiagCode::ConstAssignment, e->member->range,
                   "Cannot assign to attribute of const model " + graph_.at(result.object).type->qualified);
      result = Value::error();
    } else if (e && result.kind == Value::Kind::Object) {
      sink_.report(DiagCode::AssignThroughReference, e->member->range,
                   "Cannot assign through reference " + std::string(slot->name()));
      result = Value::error();
    } else if (e) {
      sink_.report(DiagCode::UnknownAttribute, e->member->range,
                   "`" + std::string(slot->name()) + "` is " + type.describe() + " and has no attributes");
      result = Value::error();
    }
  }
  slot->value = std::move(result);
  slot->owns = owns;
  slot->state = Slot::State::Done;
  --eval_depth_;
}

Value Evaluator::owned_default(ObjectId id, Slot& slot) {
  ModelInfo* model = slot.type()->model;
  if (model->is_trait) {
    sink_.report(DiagCode::CannotInstantiateTrait, slot.declaration()->member->range,
                 "Cannot instantiate trait " + model->qualified + " for " + slot_path(id, slot.name()) +
                     "; assign a reference to an instance that includes it");
    return Value::error();
  }
  if (model->is_const) return Value::of_object(singleton(model));  // an alias of the singleton
  // A model that owns an instance of itself by default never ends. Owners may stop the recursion by
  // assigning a reference a few levels down, so allow a handful of repeats of one declaration.
  // Count by model, not by declaration: several attributes of a model's own type would otherwise nest
  // exponentially before any one declaration repeats.
  uint32_t repeats = 0;
  for (ObjectId cur = id; cur != kNoObject; cur = graph_.at(cur).owner) {
    repeats += graph_.at(cur).created_by && graph_.at(cur).type == model;
  }
  if (repeats >= kMaxTypeRepeats || graph_.at(id).depth + 1 > kMaxInstanceDepth ||
      graph_.objects.size() >= kMaxObjects) {
    sink_.report(DiagCode::EvaluationTooDeep, slot.declaration()->member->range,
                 graph_.objects.size() >= kMaxObjects
                     ? "the model needs more than " + std::to_string(kMaxObjects) + " instances at " +
                           slot_path(id, slot.name())
                     : "the instance tree does not end at " + slot_path(id, slot.name()) + ": " +
                           model->qualified + " contains itself (" + std::to_string(repeats) +
                           " nested owned instances)");
    return Value::error();
  }
  const std::string name(slot.name());
  const bool pure = !slot.entries_below;
  const ObjectId child = new_object(model, id, name);
  graph_.at(child).created_by = slot.declaration();
  graph_.at(child).pure_default = pure;
  return Value::of_object(child);
}

Value Evaluator::global_value(GlobalInfo* global) {
  auto& [state, value] = globals_[global];
  if (state == 2) return value;
  if (state == 1) {
    sink_.report(DiagCode::CyclicDependency, global->decl->range,
                 "Cyclic dependency detected at " + global->qualified);
    state = 2;
    value = Value::error();
    return value;
  }
  state = 1;
  const Type type = resolve_type(global->doc, global->decl->type);
  Scope scope{global->doc, nullptr, kNoObject};
  Value v = eval(*global->decl->value, scope, &type);
  Value converted = convert(std::move(v), type, global->doc->doc.expr(*global->decl->value).range,
                            [&] { return global->qualified; });
  auto& entry = globals_[global];
  entry.first = 2;
  entry.second = std::move(converted);
  return entry.second;
}

void Evaluator::evaluate_all(ObjectId root) {
  std::vector<ObjectId> todo{root};
  while (!todo.empty()) {
    ObjectId id = todo.back();
    todo.pop_back();
    for (uint32_t i = 0; i < graph_.at(id).slots.size(); ++i) {
      const Value& v = value(id, i);
      const Slot& slot = graph_.at(id).slots[i];
      if (slot.owns && v.kind == Value::Kind::Object) todo.push_back(v.object);
    }
  }
}

void Evaluator::evaluate_layouts(ObjectId root) {
  // An item is an object to check, or (through) the end of the first pure default of its type's subtree.
  struct Item {
    ObjectId id;
    bool through = false;
  };
  std::vector<Item> todo{{root}};
  while (!todo.empty()) {
    const auto [id, through] = todo.back();
    todo.pop_back();
    const uint32_t layout = graph_.at(id).layout;
    if (through) {  // everything below it has been checked: the type's defaults are quiet or not
      checked_defaults_[graph_.at(id).type] = noisy_.count(layout) ? kNoObject : id;
      continue;
    }
    // Depth first: the first instance's whole subtree is checked before any other instance is reached,
    // except the instances inside it (a model owning its own kind), which are checked like it.
    auto [checked, first] = checked_.try_emplace(layout, id);
    if (!first && !noisy_.count(layout) && !owns_transitively(checked->second, id)) continue;
    if (graph_.at(id).pure_default && checked_defaults_.try_emplace(graph_.at(id).type, kNoObject).second)
      todo.push_back({id, true});  // popped after its subtree
    const size_t reported = sink_.diagnostics().size();
    for (uint32_t i = 0; i < graph_.at(id).slots.size(); ++i) {
      if (may_skip(id, i)) continue;  // the same as a pure default checked already
      const Value& v = value(id, i);
      const Slot& slot = graph_.at(id).slots[i];
      if (slot.owns && v.kind == Value::Kind::Object) todo.push_back({v.object});
    }
    if (sink_.diagnostics().size() == reported) continue;
    for (ObjectId cur = id; cur != kNoObject; cur = graph_.at(cur).owner)
      noisy_.insert(graph_.at(cur).layout);
  }
}

bool Evaluator::owns_transitively(ObjectId owner, ObjectId id) const {
  for (ObjectId cur = graph_.at(id).owner; cur != kNoObject; cur = graph_.at(cur).owner) {
    if (cur == owner) return true;
  }
  return false;
}

const ModelInfo* Evaluator::pending_default(ObjectId object, uint32_t slot_index) const {
  const Slot& slot = graph_.at(object).slots[slot_index];
  if (slot.state != Slot::State::Pending || slot.binding.entry || slot.entries_below || slot.preset ||
      slot.optional())
    return nullptr;
  const Type& type = *slot.type();
  if (type.kind != TypeKind::Model || type.is_array || type.model->is_trait || type.model->is_const)
    return nullptr;
  return type.model;
}

ObjectId Evaluator::checked_default(const ModelInfo* type) const {
  auto it = checked_defaults_.find(type);
  return it == checked_defaults_.end() ? kNoObject : it->second;
}

bool Evaluator::may_skip(ObjectId holder, uint32_t slot) const {
  const ModelInfo* type = pending_default(holder, slot);
  const ObjectId checked = type ? checked_default(type) : kNoObject;
  // No deeper than the checked one: the instance-depth limit then stops neither of them.
  return checked != kNoObject && graph_.at(holder).depth + 1 <= graph_.at(checked).depth;
}

ObjectId Evaluator::checked_instance(const Object& object) const {
  auto it = checked_.find(object.layout);
  return it == checked_.end() ? kNoObject : it->second;
}

bool Evaluator::is_path_expression(const Document& doc, ExprId expr) {
  const Expr* e = &doc.expr(expr);
  while (e->kind == ExprKind::Member || e->kind == ExprKind::Index) e = &doc.expr(e->operands[0]);
  return e->kind == ExprKind::Name || e->kind == ExprKind::This;
}

Type Evaluator::type_of(const Value& v) const {
  switch (v.kind) {
    case Value::Kind::Int:
      return Type::primitive(TypeKind::Int);
    case Value::Kind::Real:
      return Type::primitive(TypeKind::Real);
    case Value::Kind::Bool:
      return Type::primitive(TypeKind::Bool);
    case Value::Kind::String:
      return Type::primitive(TypeKind::String);
    case Value::Kind::Object:
      return Type::of_model(graph_.at(v.object).type);
    default:
      return {};
  }
}

bool Evaluator::assignable(const Value& v, const Type& target) const {
  if (v.is_error() || target.kind == TypeKind::Error) return true;
  if (target.is_array) {
    if (v.kind != Value::Kind::Array) return false;
    const Type element = target.element();
    for (const Value& item : v.array()) {
      if (!assignable(item, element)) return false;
    }
    return true;
  }
  switch (target.kind) {
    case TypeKind::Real:
      return v.is_number();
    case TypeKind::Int:
      return v.kind == Value::Kind::Int ||
             (v.kind == Value::Kind::Real && std::trunc(v.real_value) == v.real_value);
    case TypeKind::Bool:
      return v.kind == Value::Kind::Bool;
    case TypeKind::String:
      return v.kind == Value::Kind::String;
    case TypeKind::Model:
      return v.kind == Value::Kind::Object && graph_.at(v.object).type->is_subtype_of(target.model);
    case TypeKind::Union:
      for (const Type& alt : target.alternatives) {
        if (assignable(v, alt)) return true;
      }
      return false;
    case TypeKind::Error:
      return true;
  }
  return false;
}

// `what` names the value in error messages; it is only built when there is an error (building paths for every
// converted value cost 8 % of evaluating a large model).
Value Evaluator::convert(Value v, const Type& target, SourceRange where, const Describe& what) {
  if (v.is_error() || target.kind == TypeKind::Error) return v;
  if (v.kind == Value::Kind::Unset) return v;
  if (target.is_array && v.kind == Value::Kind::Array) {
    const Type element = target.element();
    for (Value& item : v.array()) {
      item = convert(std::move(item), element, where, what);
      if (item.is_error()) return Value::error();
    }
    return v;
  }
  if (!target.is_array && target.kind == TypeKind::Int && v.kind == Value::Kind::Real) {
    if (std::trunc(v.real_value) != v.real_value || std::abs(v.real_value) > 9.2e18) {
      sink_.report(DiagCode::TypeMismatch, where,
                   "Cannot convert Real value " + format_real(v.real_value) + " to Int for " + what());
      return Value::error();
    }
    return Value::of_int(static_cast<int64_t>(v.real_value));
  }
  if (!assignable(v, target)) {
    sink_.report(DiagCode::TypeMismatch, where,
                 "Type mismatch: expected " + target.describe() + ", got " + describe_value_type(v, graph_) +
                     " for " + what());
    return Value::error();
  }
  if (!target.is_array && target.kind == TypeKind::Real && v.kind == Value::Kind::Int) {
    return Value::of_real(static_cast<double>(v.int_value));
  }
  return v;
}

Evaluator::Entity Evaluator::eval_entity(ExprId id, const Scope& scope) {
  const Document& doc = scope.doc->doc;
  const Expr& e = doc.expr(id);
  Entity entity;
  if (e.kind == ExprKind::Name) {
    if (scope.self != kNoObject) {
      const SlotIndex& index = *graph_.at(scope.self).index;
      auto it = index.find(e.text);
      if (it != index.end()) {
        reads_instance_ = true;
        graph_.at(scope.self).slots[it->second].used = true;  // an expression depends on it
        entity.value = value(scope.self, it->second);
        if (entity.value.kind == Value::Kind::Unset) {
          sink_.report(DiagCode::UnsetAttribute, e.range,
                       "Attribute " + slot_path(scope.self, e.text) + " is not set");
          entity.value = Value::error();
        }
        return entity;
      }
    }
    // The instance's attribute names are suggestions only for a name nothing knows.
    auto members = [&] {
      std::vector<std::string> names;
      if (scope.self != kNoObject) {
        for (const Slot& s : graph_.at(scope.self).slots) names.emplace_back(s.name());
      }
      return names;
    };
    Symbol symbol = program_.lookup(scope.doc, e.text, e.range, true, members);
    if (!symbol) {
      entity.value = Value::error();
      return entity;
    }
    if (symbol.model) {
      entity.kind = Entity::Kind::Model;
      entity.model = symbol.model;
    } else if (symbol.global) {
      entity.value = global_value(symbol.global);
    } else {
      entity.kind = Entity::Kind::Namespace;
      entity.ns = symbol.ns;
    }
    return entity;
  }
  if (e.kind == ExprKind::This) {
    if (scope.self == kNoObject) {
      sink_.report(DiagCode::NotAValue, e.range, "`this` has no meaning in a global attribute");
      entity.value = Value::error();
    } else {
      reads_instance_ = true;
      entity.value = Value::of_object(scope.self);
    }
    return entity;
  }
  if (e.kind == ExprKind::Member) {
    // A dotted name of a model or namespace (`Math.Vec3` in `Math.Vec3.Y_AXIS()`) means the same wherever
    // its text is, unless its first name is an attribute of the instance: resolved once per expression.
    std::string& key = static_name_key_;  // the document, then the names from the last
    key.assign(reinterpret_cast<const char*>(&scope.doc), sizeof(scope.doc));
    const Expr* head = &e;
    for (; head->kind == ExprKind::Member; head = &doc.expr(head->operands[0])) (key += head->text) += '.';
    const bool static_name = head->kind == ExprKind::Name &&
                             (scope.self == kNoObject || !graph_.at(scope.self).index->count(head->text));
    if (static_name) {
      key += head->text;
      if (auto it = static_names_.find(key); it != static_names_.end()) return it->second;
    }
    std::string found = static_name ? key : std::string();  // the buffer is reused by nested lookups
    const size_t reported = sink_.diagnostics().size();
    entity = eval_member_entity(e, scope);
    if (static_name && entity.kind != Entity::Kind::Value && sink_.diagnostics().size() == reported)
      static_names_.emplace(std::move(found), entity);
    return entity;
  }
  entity.value = eval(id, scope, nullptr);
  return entity;
}

Evaluator::Entity Evaluator::eval_member_entity(const Expr& e, const Scope& scope) {
  Entity entity;
  {
    Entity target = eval_entity(e.operands[0], scope);
    switch (target.kind) {
      case Entity::Kind::Value:
        entity.value = member_of(target.value, e.text, e.range);
        return entity;
      case Entity::Kind::Model:
        if (!program_.resolve(target.model)) {
          entity.value = Value::error();
        } else if (target.model->is_const) {
          entity.value = member_of(Value::of_object(singleton(target.model)), e.text, e.range);
        } else {
          sink_.report(
              DiagCode::NotAValue, e.range,
              "`" + target.model->qualified + "." + std::string(e.text) + "`: " + target.model->qualified +
                  " is a model; without an instance only its static methods and, for const models, its "
                  "attributes can be used");
          entity.value = Value::error();
        }
        return entity;
      case Entity::Kind::Namespace: {
        Symbol symbol = program_.lookup_in(target.ns, e.text, &e.range);
        if (!symbol) {
          program_.load_all(target.ns);
          std::vector<std::string> candidates;
          for (const auto& [n, s] : target.ns->symbols) candidates.push_back(n);
          for (const auto& [n, c] : target.ns->children) candidates.push_back(n);
          std::string message = "Unknown name " + target.ns->qualified + "." + std::string(e.text);
          std::string near = Program::suggestion(e.text, candidates);
          if (!near.empty()) message += "; did you mean `" + near + "`?";
          add_note(sink_.report(DiagCode::UnknownName, e.range, message),
                   missing_member_note(target.ns->bundle, target.ns->qualified, e.text));
          entity.value = Value::error();
        } else if (symbol.model) {
          entity.kind = Entity::Kind::Model;
          entity.model = symbol.model;
        } else if (symbol.global) {
          entity.value = global_value(symbol.global);
        } else {
          entity.kind = Entity::Kind::Namespace;
          entity.ns = symbol.ns;
        }
        return entity;
      }
    }
  }
  return entity;
}

Value Evaluator::member_of(const Value& object, std::string_view name, SourceRange where) {
  if (object.is_error()) return object;
  if (object.kind != Value::Kind::Object) {
    sink_.report(
        DiagCode::UnknownAttribute, where,
        "a " + describe_value_type(object, graph_) + " value has no attribute `" + std::string(name) + "`");
    return Value::error();
  }
  const Object& obj = graph_.at(object.object);
  auto it = obj.index->find(name);
  if (std::optional<std::string_view> current = renamed_attribute(name);
      it == obj.index->end() && current && obj.has(*current)) {
    sink_.report(DiagCode::DeprecatedName, where,
                 "`" + std::string(name) + "` is the 0.17.8 name; use `" + std::string(*current) + "`");
    it = obj.index->find(*current);
  }
  if (it == obj.index->end()) {
    std::vector<std::string> names;
    for (const Slot& s : obj.slots) names.emplace_back(s.name());
    std::string message = "Unknown attribute " + std::string(name) + " in " + obj.type->qualified;
    std::string near = Program::suggestion(name, names);
    if (!near.empty()) message += "; did you mean `" + near + "`?";
    sink_.report(DiagCode::UnknownAttribute, where, message);
    return Value::error();
  }
  const uint32_t index = it->second;
  graph_.at(object.object).slots[index].used = true;  // an expression depends on it
  Value v = value(object.object, index);
  if (v.kind == Value::Kind::Unset) {
    sink_.report(DiagCode::UnsetAttribute, where,
                 "Attribute " + slot_path(object.object, name) + " is not set");
    return Value::error();
  }
  return v;
}

Value Evaluator::eval(ExprId id, const Scope& scope, const Type* expected) {
  const Document& doc = scope.doc->doc;
  const Expr& e = doc.expr(id);
  switch (e.kind) {
    case ExprKind::Error:
      return Value::error();
    case ExprKind::Int:
      if (e.int_value) return Value::of_int(*e.int_value);
      if (expected && expected->kind == TypeKind::Real && !expected->is_array)
        return Value::of_real(e.real_value);
      sink_.report(DiagCode::TypeMismatch, e.range,
                   "integer `" + std::string(e.text.substr(0, 24)) +
                       "` does not fit in Int (64 bits); write it as a Real");
      return Value::error();
    case ExprKind::Real:
      return Value::of_real(e.real_value);
    case ExprKind::Bool:
      return Value::of_bool(e.bool_value);
    case ExprKind::String:
      return Value::of_string(e.string_value);
    case ExprKind::PathString: {
      namespace fs = std::filesystem;
      fs::path p(e.string_value);
      if (p.is_relative()) p = fs::path(program_.sources().file(doc.file).path()).parent_path() / p;
      std::error_code ec;
      const fs::path absolute = fs::absolute(p, ec);  // a path string is absolute (spec §2.8)
      return Value::of_string((ec ? p : absolute).lexically_normal().generic_string());
    }
    case ExprKind::Name:
    case ExprKind::This:
    case ExprKind::Member: {
      Entity entity = eval_entity(id, scope);
      if (entity.kind == Entity::Kind::Value) return entity.value;
      if (entity.kind == Entity::Kind::Model && entity.model->is_const && program_.resolve(entity.model)) {
        return Value::of_object(singleton(entity.model));
      }
      sink_.report(
          DiagCode::NotAValue, e.range,
          entity.kind == Entity::Kind::Model
              ? "`" + entity.model->qualified + "` is a model, not a value (only const models are values)"
              : "`" + entity.ns->qualified + "` is a namespace, not a value");
      return Value::error();
    }
    case ExprKind::Index: {
      // `links[0]`: an element of an array attribute (an object element is the object itself).
      const Value array = eval(e.operands[0], scope, nullptr);
      const Value index = eval(e.operands[1], scope, nullptr);
      if (array.is_error() || index.is_error()) return Value::error();
      if (array.kind != Value::Kind::Array) {
        sink_.report(DiagCode::TypeMismatch, doc.expr(e.operands[0]).range,
                     "only arrays can be indexed, not a " + describe_value_type(array, graph_));
        return Value::error();
      }
      if (index.kind != Value::Kind::Int) {
        sink_.report(DiagCode::TypeMismatch, doc.expr(e.operands[1]).range,
                     "an index must be an Int, not a " + describe_value_type(index, graph_));
        return Value::error();
      }
      if (index.int_value < 0 || static_cast<size_t>(index.int_value) >= array.array().size()) {
        sink_.report(DiagCode::IndexOutOfRange, doc.expr(e.operands[1]).range,
                     "index " + std::to_string(index.int_value) + " is outside the array's " +
                         std::to_string(array.array().size()) + " elements");
        return Value::error();
      }
      return array.array()[static_cast<size_t>(index.int_value)];
    }
    case ExprKind::Call:
      return eval_call(e, scope);
    case ExprKind::Unary:
      return eval_unary(e, scope, expected);
    case ExprKind::Binary:
      return eval_binary(e, scope, expected);
    case ExprKind::Array: {
      Type element;
      const bool typed = expected && expected->is_array;
      if (typed) element = expected->element();
      std::vector<Value> items;
      for (ExprId item : e.operands) {
        Value v = eval(item, scope, typed ? &element : nullptr);
        // Checked here so a wrong element is reported where it is written.
        if (typed)
          v = convert(std::move(v), element, doc.expr(item).range,
                      [&] { return "an element of " + expected->describe(); });
        if (v.is_error()) return v;
        items.push_back(std::move(v));
      }
      return Value::of_array(std::move(items));
    }
    case ExprKind::Initializer:
      return eval_initializer(e, scope, expected);
  }
  return Value::error();
}

Value Evaluator::eval_initializer(const Expr& e, const Scope& scope, const Type* expected) {
  // `{}`: nothing given, so an empty array, or an instance with its defaults.
  if (e.operands.empty() && expected && expected->is_array) return Value::of_array({});
  if (!expected || expected->kind != TypeKind::Model || expected->is_array) {
    sink_.report(DiagCode::InitializerType, e.range,
                 expected && expected->kind != TypeKind::Error
                     ? "an initializer `{...}` cannot make a " + expected->describe()
                     : "Cannot infer type of initializer");
    return Value::error();
  }
  ModelInfo* model = expected->model;
  if (model->is_trait || model->is_const) {
    sink_.report(DiagCode::InitializerType, e.range, "an initializer cannot make a " + model->qualified);
    return Value::error();
  }
  ObjectId object = make_free_object(model);
  if (e.operands.empty()) return Value::of_object(object);
  std::vector<uint32_t> fields;
  // Fields in declaration order: primitive values, and references to instances made elsewhere
  // (`{Sensors.Signals.TriaxialOutputField.X_F64, logic.accelerometer_logic}`).
  for (uint32_t i = 0; i < graph_.at(object).slots.size(); ++i) {
    const Slot& slot = graph_.at(object).slots[i];
    const bool reference = slot.declaration() && slot.declaration()->member->is_reference;
    if ((slot.type()->is_primitive() || reference) && !slot.type()->is_array &&
        slot.type()->kind != TypeKind::Error)
      fields.push_back(i);
  }
  if (e.operands.size() != fields.size()) {
    sink_.report(DiagCode::InitializerArity, e.range,
                 "Initializer has " + std::to_string(e.operands.size()) + " values but " + model->qualified +
                     " has " + std::to_string(fields.size()) + " fields");
    return Value::error();
  }
  for (size_t i = 0; i < fields.size(); ++i) {
    const Type field_type = *graph_.at(object).slots[fields[i]].type();
    Value v = eval(e.operands[i], scope, &field_type);
    const std::string field_name(graph_.at(object).slots[fields[i]].name());
    v = convert(std::move(v), field_type, scope.doc->doc.expr(e.operands[i]).range,
                [&] { return model->qualified + "." + field_name; });
    if (v.is_error()) return v;
    preset(object, field_name, std::move(v));
  }
  return Value::of_object(object);
}

Value Evaluator::eval_unary(const Expr& e, const Scope& scope, const Type* expected) {
  Value v = eval(e.operands[0], scope, expected);
  if (v.is_error()) return v;
  if (v.kind == Value::Kind::Int) {
    if (v.int_value == INT64_MIN) {
      sink_.report(DiagCode::TypeMismatch, e.range, "Int overflow in negation");
      return Value::error();
    }
    return Value::of_int(-v.int_value);
  }
  if (v.kind == Value::Kind::Real) return Value::of_real(-v.real_value);
  return apply_operator('-', {v}, e.range, true);
}

Value Evaluator::eval_binary(const Expr& e, const Scope& scope, const Type* expected) {
  const Document& doc = scope.doc->doc;
  const bool lhs_init = doc.expr(e.operands[0]).kind == ExprKind::Initializer;
  const bool rhs_init = doc.expr(e.operands[1]).kind == ExprKind::Initializer;
  Value lhs, rhs;
  if (lhs_init != rhs_init) {
    // An initializer operand takes its type from the whole expression, when an operator exists for that type
    // and the other operand (spec §10.8); else from the other operand.
    const ExprId other_id = lhs_init ? e.operands[1] : e.operands[0];
    Value other = eval(other_id, scope, nullptr);
    if (other.is_error()) return other;
    Type other_type = type_of(other);
    Type init_type;
    auto fits = [&](const Type& t) {
      if (t.kind != TypeKind::Model || t.is_array) return false;
      std::vector<Type> types =
          lhs_init ? std::vector<Type>{t, other_type} : std::vector<Type>{other_type, t};
      return find_operator(e.op, types, nullptr) != nullptr;
    };
    if (expected && fits(*expected)) {
      init_type = *expected;
    } else if (fits(other_type)) {
      init_type = other_type;
    }
    Value init = eval(lhs_init ? e.operands[0] : e.operands[1], scope, &init_type);
    if (init.is_error()) return init;
    lhs = lhs_init ? init : other;
    rhs = lhs_init ? other : init;
  } else {
    lhs = eval(e.operands[0], scope, expected);
    if (lhs.is_error()) return lhs;
    rhs = eval(e.operands[1], scope, expected);
    if (rhs.is_error()) return rhs;
  }
  if (lhs.is_number() && rhs.is_number()) {
    if (lhs.kind == Value::Kind::Int && rhs.kind == Value::Kind::Int && e.op != '/') {
      int64_t out = 0;
      bool overflow = e.op == '+'   ? __builtin_add_overflow(lhs.int_value, rhs.int_value, &out)
                      : e.op == '-' ? __builtin_sub_overflow(lhs.int_value, rhs.int_value, &out)
                                    : __builtin_mul_overflow(lhs.int_value, rhs.int_value, &out);
      if (overflow) {
        sink_.report(DiagCode::TypeMismatch, e.range, "Int overflow; write the operands as Reals");
        return Value::error();
      }
      return Value::of_int(out);
    }
    // Int / Int is Real (spec §10.5 proposal): 7 / 2 is 3.5.
    const double a = lhs.as_real(), b = rhs.as_real();
    const double out = e.op == '+' ? a + b : e.op == '-' ? a - b : e.op == '*' ? a * b : a / b;
    // Infinity is a value (Math.INF); one made from finite numbers, or NaN, is a mistake to report here,
    // where it was written, before it reaches a mass or a position.
    if (std::isnan(out) || (std::isinf(out) && std::isfinite(a) && std::isfinite(b))) {
      sink_.report(DiagCode::InvalidValue, e.range,
                   e.op == '/' && b == 0 ? std::string("division by zero")
                   : std::isnan(out) ? std::string("this gives no number (NaN): ") + format_real(a) + ' ' +
                                           e.op + ' ' + format_real(b)
                                     : std::string("the result overflows a Real (beyond 1.8e308)"));
      return Value::error();
    }
    return Value::of_real(out);
  }
  return apply_operator(e.op, {lhs, rhs}, e.range, true);
}

const OperatorInfo* Evaluator::find_operator(char op, const std::vector<Type>& operand_types,
                                             std::vector<Type>* params_out) {
  const OperatorInfo* loose = nullptr;
  std::vector<Type> loose_params;
  for (const OperatorInfo& info : program_.operators()) {
    if (info.decl->op != op || info.decl->params.size() != operand_types.size()) continue;
    std::vector<Type> params;
    bool exact = true, compatible = true;
    for (size_t i = 0; i < operand_types.size(); ++i) {
      Type p = resolve_type_ref(info.doc, info.decl->params[i].type);
      const Type& a = operand_types[i];
      const bool same = p.kind == a.kind && p.is_array == a.is_array && p.model == a.model;
      const bool fits = same || (p.kind == TypeKind::Real && a.kind == TypeKind::Int && !a.is_array) ||
                        (p.kind == TypeKind::Model && a.kind == TypeKind::Model && !p.is_array &&
                         !a.is_array && a.model->is_subtype_of(p.model));
      exact = exact && same;
      compatible = compatible && fits;
      params.push_back(std::move(p));
    }
    if (exact) {
      if (params_out) *params_out = params;
      return &info;
    }
    if (compatible && !loose) {
      loose = &info;
      loose_params = params;
    }
  }
  if (loose && params_out) *params_out = loose_params;
  return loose;
}

Value Evaluator::apply_operator(char op, const std::vector<Value>& operands, SourceRange where, bool report) {
  std::vector<Type> types;
  for (const Value& v : operands) types.push_back(type_of(v));
  std::vector<Type> params;
  const OperatorInfo* info = find_operator(op, types, &params);
  std::string signature;
  for (size_t i = 0; i < types.size(); ++i)
    signature += (i ? " and " : "") + describe_value_type(operands[i], graph_);
  if (!info) {
    if (report) {
      sink_.report(DiagCode::NoOperator, where, std::string("No operator ") + op + " for " + signature);
    }
    return Value::error();
  }
  std::string key = std::string("operator") + op + "(";
  for (size_t i = 0; i < params.size(); ++i) key += (i ? "," : "") + params[i].describe();
  key += ")";
  const NativeFunction* fn = NativeRegistry::global().find(key);
  if (!fn) {
    sink_.report(DiagCode::NoImplementation, where, "No implementation for operator " + key.substr(8));
    return Value::error();
  }
  std::vector<Value> args;
  for (size_t i = 0; i < operands.size(); ++i) {
    args.push_back(convert(operands[i], params[i], where, [&] { return std::string("operand of ") + op; }));
  }
  NativeCall call(*this, where);
  Value result = (*fn)(call, args);
  return call.poisoned() ? Value::error() : result;
}

const MethodInfo* Evaluator::find_method(ModelInfo* model, std::string_view name, ModelInfo** owner) {
  for (ModelInfo* m : model->linearization()) {
    for (const MethodInfo& method : m->methods) {
      if (method.member->path.parts[0].text == name) {
        *owner = m;
        return &method;
      }
    }
  }
  return nullptr;
}

Value Evaluator::eval_call(const Expr& call, const Scope& scope) {
  const Document& doc = scope.doc->doc;
  const Expr& callee = doc.expr(call.operands[0]);
  std::vector<ExprId> args(call.operands.begin() + 1, call.operands.end());
  std::string_view name = callee.text;
  ModelInfo* type = nullptr;
  std::optional<Value> self;
  bool on_instance = false;  // `value.f()`, as opposed to `Model.f()` or an unqualified `f()`
  if (callee.kind == ExprKind::Name) {
    if (scope.self == kNoObject) {
      sink_.report(DiagCode::UnknownMethod, callee.range, "Unknown method " + std::string(name));
      return Value::error();
    }
    reads_instance_ = true;
    self = Value::of_object(scope.self);
    type = graph_.at(scope.self).type;
  } else {
    Entity target = eval_entity(callee.operands[0], scope);
    if (target.kind == Entity::Kind::Model) {
      if (!program_.resolve(target.model)) return Value::error();
      type = target.model;
      // A const model's name is also its one instance: `Steel.is_default_material()`.
      if (target.model->is_const) self = Value::of_object(singleton(target.model));
    } else if (target.kind == Entity::Kind::Namespace) {
      sink_.report(DiagCode::UnknownMethod, callee.range,
                   "`" + target.ns->qualified + "." + std::string(name) + "` is not a method");
      return Value::error();
    } else {
      if (target.value.is_error()) return target.value;
      if (target.value.kind != Value::Kind::Object) {
        sink_.report(DiagCode::UnknownMethod, callee.range,
                     "a " + describe_value_type(target.value, graph_) + " value has no methods");
        return Value::error();
      }
      self = target.value;
      on_instance = true;
      type = graph_.at(target.value.object).type;
    }
  }
  ModelInfo* owner = nullptr;
  const MethodInfo* method = find_method(type, name, &owner);
  if (!method) {
    std::vector<std::string> names;
    for (ModelInfo* m : type->linearization()) {
      for (const MethodInfo& mi : m->methods) names.emplace_back(mi.member->path.parts[0].text);
    }
    std::string message = "Unknown method " + std::string(name) + " in " + type->qualified;
    std::string near = Program::suggestion(name, names);
    if (!near.empty()) message += "; did you mean `" + near + "`?";
    sink_.report(DiagCode::UnknownMethod, callee.range, message);
    return Value::error();
  }
  if (method->member->is_static && on_instance) {
    sink_.report(DiagCode::StaticMismatch, call.range,
                 "Static method " + std::string(name) + " called on instance");
    return Value::error();
  }
  return call_method(owner, *method, method->member->is_static ? std::nullopt : self, std::move(args), scope,
                     call.range);
}

const Evaluator::PreparedMethod& Evaluator::prepare(ModelInfo* owner, const MethodInfo& method) {
  auto [it, fresh] = prepared_methods_.try_emplace(&method);
  PreparedMethod& p = it->second;
  if (!fresh) return p;
  const Member& m = *method.member;
  p.qualified = owner->qualified + "." + std::string(m.path.parts[0].text);
  for (const Param& param : m.params) p.params.push_back(resolve_type_ref(owner->doc, param.type));
  if (m.return_type) p.result = resolve_type_ref(owner->doc, *m.return_type);
  p.native = NativeRegistry::global().find(p.qualified);
  p.renamed = renamed_method(p.qualified);
  return p;
}

Value Evaluator::call_method(ModelInfo* owner, const MethodInfo& method, std::optional<Value> self,
                             std::vector<ExprId> args, const Scope& scope, SourceRange where) {
  const Member& m = *method.member;
  const std::string_view name = m.path.parts[0].text;
  if (!m.is_static && !self) {
    sink_.report(DiagCode::StaticMismatch, where,
                 "Non-static method " + std::string(name) + " called on type " + owner->qualified);
    return Value::error();
  }
  if (!m.return_type) {
    sink_.report(DiagCode::VoidMethodCall, where,
                 "Method " + std::string(name) + " has no return value and cannot be called");
    return Value::error();
  }
  if (args.size() != m.params.size()) {
    sink_.report(DiagCode::WrongArgumentCount, where,
                 "Wrong number of arguments to " + std::string(name) + ": expected " +
                     std::to_string(m.params.size()) + ", got " + std::to_string(args.size()));
    return Value::error();
  }
  // Names, types and the native of a method are the same at every call: worked out once.
  const PreparedMethod& prepared = prepare(owner, method);
  std::vector<Value> values;
  values.reserve(args.size() + 1);
  if (!m.is_static) values.push_back(*self);
  for (size_t i = 0; i < args.size(); ++i) {
    const Type& param = prepared.params[i];
    Value v = eval(args[i], scope, &param);
    v = convert(std::move(v), param, scope.doc->doc.expr(args[i]).range, [&] {
      return "argument `" + std::string(m.params[i].name.text) + "` of " + std::string(name);
    });
    if (v.is_error()) return v;
    values.push_back(std::move(v));
  }
  if (prepared.renamed) {
    sink_.report(
        DiagCode::DeprecatedName, where,
        "`" + prepared.qualified + "` is the pre-0.10 name; use `" + std::string(*prepared.renamed) + "`");
  }
  if (!prepared.native) {
    sink_.report(DiagCode::NoImplementation, where, "No implementation for method " + prepared.qualified);
    return Value::error();
  }
  NativeCall call(*this, where);
  Value result = (*prepared.native)(call, values);
  if (call.poisoned()) return Value::error();
  if (result.kind == Value::Kind::Real && !std::isfinite(result.real_value)) {
    // Math.Functions.inf() is infinite by design; NaN, or infinity from finite arguments, is not.
    bool finite_arguments = !values.empty();
    for (const Value& v : values)
      finite_arguments = finite_arguments && !(v.is_number() && !std::isfinite(v.as_real()));
    if (std::isnan(result.real_value) || finite_arguments) {
      sink_.report(DiagCode::InvalidValue, where,
                   "`" + prepared.qualified + "` gives " +
                       (std::isnan(result.real_value) ? "no number (NaN)" : "an infinite number") +
                       " for these arguments");
      return Value::error();
    }
  }
  return convert(std::move(result), prepared.result, where,
                 [&] { return "the result of " + prepared.qualified; });
}

// ------------------------------------------------------------------------------------------- natives

double NativeCall::real(const Value& v) {
  return v.as_real();
}

std::vector<double> NativeCall::reals(const Value& array) {
  std::vector<double> out;
  if (array.kind != Value::Kind::Array) poisoned_ = true;
  for (const Value& v : array.array()) out.push_back(v.as_real());
  return out;
}

bool NativeCall::is_object(const Value& v) {
  if (v.kind == Value::Kind::Object) return true;
  poisoned_ = true;
  return false;
}

Value NativeCall::object(const Value& of, std::string_view attribute) {
  const Value* v = is_object(of) ? evaluator_.value(of.object, attribute) : nullptr;
  if (!v || v->is_error()) poisoned_ = true;
  return v ? *v : Value::error();
}

std::vector<double> NativeCall::fields(const Value& object, std::initializer_list<std::string_view> names) {
  std::vector<double> out;
  for (std::string_view name : names) {
    const Value* v = is_object(object) ? evaluator_.value(object.object, name) : nullptr;
    if (!v || !v->is_number()) poisoned_ = true;
    out.push_back(v && v->is_number() ? v->as_real() : std::nan(""));
  }
  return out;
}

Value NativeCall::make(std::string_view model,
                       std::initializer_list<std::pair<std::string_view, double>> fields) {
  ModelInfo* info = evaluator_.program().builtin_model(model);
  if (!info || !evaluator_.program().resolve(info))
    return fail("the bundle model " + std::string(model) + " is missing");
  ObjectId id = evaluator_.make_free_object(info);
  for (const auto& [name, v] : fields) evaluator_.preset(id, name, Value::of_real(v));
  return Value::of_object(id);
}

Value NativeCall::make_with(std::string_view model,
                            std::initializer_list<std::pair<std::string_view, Value>> fields) {
  ModelInfo* info = evaluator_.program().builtin_model(model);
  if (!info || !evaluator_.program().resolve(info))
    return fail("the bundle model " + std::string(model) + " is missing");
  ObjectId id = evaluator_.make_free_object(info);
  for (const auto& [name, v] : fields) evaluator_.preset(id, name, v);
  return Value::of_object(id);
}

Value NativeCall::fail(const std::string& message) {
  evaluator_.sink().report(DiagCode::NativeError, where_, message);
  return Value::error();
}

// ----------------------------------------------------------------------------------------------- root

ModelInfo* select_root_model(Program& program, DocumentInfo* doc, const std::string* name) {
  const SourceFile& file = program.sources().file(doc->doc.file);
  const SourceRange file_start{doc->doc.file, file.content_begin(), file.content_begin()};
  if (name) {
    auto it = doc->ns->symbols.find(*name);
    const Decl* decl = nullptr;
    for (const Decl& d : doc->doc.decls) {
      if ((d.kind == DeclKind::Model || d.kind == DeclKind::Trait) && d.name.text == *name) decl = &d;
    }
    if (!decl || it == doc->ns->symbols.end() || !it->second.model) {
      std::string models;
      for (const Decl& d : doc->doc.decls) {
        if (d.kind == DeclKind::Model) models += (models.empty() ? "" : ", ") + std::string(d.name.text);
      }
      program.sink().report(DiagCode::UnknownModel, file_start,
                            "no model named `" + *name + "` in this file" +
                                (models.empty() ? std::string() : "; its models are " + models));
      return nullptr;
    }
    return it->second.model;
  }
  const Decl* last = doc->doc.last_model();
  if (!last) {
    program.sink().report(DiagCode::NoModel, file_start, "No model could be found");
    return nullptr;
  }
  auto it = doc->ns->symbols.find(last->name.text);
  return it == doc->ns->symbols.end() ? nullptr : it->second.model;
}

}  // namespace openplx::frontend
