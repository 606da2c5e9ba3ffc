// What native functions see (NativeCall) and the registry they are found in.
#include "frontend/evaluation/evaluator.h"

#include <cmath>

namespace openplx::frontend {

NativeRegistry& NativeRegistry::global() {
  static NativeRegistry registry;
  return registry;
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

}  // namespace openplx::frontend
