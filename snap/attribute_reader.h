// Typed reads of evaluated attributes for the resolved-system builder: a missing attribute or one of another
// kind gives the fallback, never an error (the evaluator has already reported bad values).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "frontend/evaluator.h"
#include "snap/resolved_system.h"

namespace openplx::snap {

class AttributeReader {
 public:
  explicit AttributeReader(frontend::Evaluator& evaluator) : ev_(evaluator) {}

  frontend::Evaluator& evaluator() { return ev_; }
  const frontend::ObjectGraph& graph() const { return ev_.graph(); }

  std::optional<double> number(frontend::ObjectId id, std::string_view name) {
    const frontend::Value* v = ev_.value(id, name);
    return v && v->is_number() ? std::optional<double>(v->as_real()) : std::nullopt;
  }
  double real(frontend::ObjectId id, std::string_view name, double fallback = 0.0) {
    return number(id, name).value_or(fallback);
  }
  std::optional<bool> boolean(frontend::ObjectId id, std::string_view name) {
    const frontend::Value* v = ev_.value(id, name);
    return v && v->kind == frontend::Value::Kind::Bool ? std::optional<bool>(v->bool_value) : std::nullopt;
  }
  std::optional<std::string> string(frontend::ObjectId id, std::string_view name) {
    const frontend::Value* v = ev_.value(id, name);
    return v && v->kind == frontend::Value::Kind::String ? std::optional<std::string>(v->string_value())
                                                         : std::nullopt;
  }
  frontend::ObjectId object(frontend::ObjectId id, std::string_view name) {
    const frontend::Value* v = ev_.value(id, name);
    return v && v->kind == frontend::Value::Kind::Object ? v->object : frontend::kNoObject;
  }
  // The objects of an array attribute, in order (items that are not objects are skipped).
  std::vector<frontend::ObjectId> objects(frontend::ObjectId id, std::string_view name) {
    std::vector<frontend::ObjectId> out;
    const frontend::Value* v = ev_.value(id, name);
    if (v && v->kind == frontend::Value::Kind::Array) {
      for (const frontend::Value& item : v->array())
        if (item.kind == frontend::Value::Kind::Object) out.push_back(item.object);
    }
    return out;
  }
  const std::string& type_name(frontend::ObjectId id) const { return graph().at(id).type->qualified; }
  // A Math.Vec3 attribute (zero when absent; a component that is not a number is 0).
  Eigen::Vector3d vec3(frontend::ObjectId id, std::string_view name) {
    const frontend::ObjectId v = object(id, name);
    if (v == frontend::kNoObject) return Eigen::Vector3d::Zero();
    return {real(v, "x"), real(v, "y"), real(v, "z")};
  }

 private:
  frontend::Evaluator& ev_;
};

}  // namespace openplx::snap
