// The evaluator, part 1: types, and building objects and their slots (which binding reaches which attribute).
// Part 2 (evaluator_values.cpp) computes attribute values; part 3 (evaluator_expressions.cpp) evaluates
// expressions.
#include "frontend/evaluation/evaluator.h"

#include <cstring>

#include "frontend/natives/builtin_natives.h"
#include "frontend/semantics/deprecations.h"

namespace openplx::frontend {
namespace {

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
