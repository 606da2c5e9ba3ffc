// The evaluator, part 2: computing attribute values (defaults, globals, layouts) and checking them
// against their declared types. Part 1 (evaluator.cpp) builds the objects; part 3 (evaluator_expressions.cpp)
// evaluates expressions.
#include "frontend/evaluation/evaluator.h"

#include <cmath>

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

}  // namespace
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

}  // namespace openplx::frontend
