// The program, resolving models: linearization, trait extensions, bases first, then each model's members.
#include "frontend/semantics/program.h"

#include <algorithm>
#include <set>
#include <unordered_set>

namespace openplx::frontend {
namespace {

std::string join(const std::vector<std::string_view>& parts, size_t count) {
  std::string out;
  for (size_t i = 0; i < count; ++i) {
    if (i) out += '.';
    out += parts[i];
  }
  return out;
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

const ModelInfo* jump_of(const ModelInfo* m) {
  return m->chain_jump ? m->chain_jump : m;
}

// Links `model` below the base linearize_model() would take now.
void link_chain(ModelInfo* model) {
  const ModelInfo* base = model->base;
  if (!base || base->state != ModelInfo::State::Resolved) return;
  const ModelInfo* jump = jump_of(base);
  model->chain_base = base;
  model->chain_depth = base->chain_depth + 1;
  const bool even = base->chain_depth - jump->chain_depth == jump->chain_depth - jump_of(jump)->chain_depth;
  model->chain_jump = even ? jump_of(jump) : base;
}

// Whether `ancestor` is on the base chain above `model`.
bool on_chain_above(const ModelInfo* model, const ModelInfo* ancestor) {
  const uint32_t depth = ancestor->chain_depth;
  if (depth >= model->chain_depth) return false;
  while (model->chain_depth > depth)
    model = jump_of(model)->chain_depth >= depth ? jump_of(model) : model->chain_base;
  return model == ancestor;
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
  link_chain(model);

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
  auto list_ancestors = [&] {
    if (!ancestors.empty()) return;
    ancestors = linearize_model(model);
    name_steps_ += ancestors.size();
  };
  auto inherited = [&](std::string_view name) {
    auto found = declarers_.find(name);
    if (found == declarers_.end()) return false;
    const std::unordered_set<const ModelInfo*>& declarers = found->second;
    // Fewer declarers than bases: each is looked for on the base chain, unless one is a trait.
    if (declarers.size() <= model->chain_depth) {
      bool trait = false;
      for (const ModelInfo* m : declarers) {
        ++name_steps_;
        trait = trait || m->is_trait;
        if (!m->is_trait && on_chain_above(model, m)) {
          list_ancestors();  // for the report, which names the declarer
          return true;
        }
      }
      if (!trait) return false;
    }
    list_ancestors();
    // Whichever side is smaller is walked: a name every model declares meets few ancestors, and a deep
    // chain meets few declarers.
    if (declarers.size() >= ancestors.size() - 1) {
      return std::any_of(ancestors.begin() + 1, ancestors.end(), [&](const ModelInfo* m) {
        ++name_steps_;
        return declarers.count(m) > 0;
      });
    }
    if (ancestor_set.empty()) ancestor_set.insert(ancestors.begin() + 1, ancestors.end());
    return std::any_of(declarers.begin(), declarers.end(), [&](const ModelInfo* m) {
      ++name_steps_;
      return ancestor_set.count(m) > 0;
    });
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
    declarers_[e.path[0]].insert(model);
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

}  // namespace openplx::frontend
