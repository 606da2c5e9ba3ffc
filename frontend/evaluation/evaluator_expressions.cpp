// The evaluator, part 3: expressions (names, members, operators, initializers, calls and methods).
// Part 1 (evaluator.cpp) builds the objects; part 2 (evaluator_values.cpp) computes attribute values.
#include "frontend/evaluation/evaluator.h"

#include <cmath>
#include <filesystem>

#include "frontend/evaluation/value_format.h"
#include "frontend/semantics/deprecations.h"
#include "frontend/semantics/unknown_name_notes.h"

namespace openplx::frontend {

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
          std::string message = "Unknown name " + target.ns->qualified + "." + std::string(e.text);
          if (sink_.error_count() < kMaxPrintedErrors) {  // a namespace can hold 40,000 names
            std::vector<std::string> candidates;
            for (const auto& [n, s] : target.ns->symbols) candidates.push_back(n);
            for (const auto& [n, c] : target.ns->children) candidates.push_back(n);
            std::string near = Program::suggestion(e.text, candidates);
            if (!near.empty()) message += "; did you mean `" + near + "`?";
          }
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

}  // namespace openplx::frontend
