#include "tests/support/json_schema_subset.h"

#include <cmath>
#include <set>
#include <stdexcept>

namespace openplx::testing {

namespace {

bool annotation(const std::string& key) {
  static const std::set<std::string> kAnnotations = {"$schema", "$id",         "$defs",   "$comment",
                                                     "title",   "description", "default", "examples"};
  return kAnnotations.count(key) || key.rfind("x-", 0) == 0;
}

bool has_type(const nlohmann::json& v, const std::string& type) {
  if (type == "object") return v.is_object();
  if (type == "array") return v.is_array();
  if (type == "string") return v.is_string();
  if (type == "boolean") return v.is_boolean();
  if (type == "null") return v.is_null();
  if (type == "number") return v.is_number();
  if (type == "integer") return v.is_number() && std::floor(v.get<double>()) == v.get<double>();
  throw std::invalid_argument("schema: unknown type " + type);
}

}  // namespace

std::vector<std::string> SchemaSubset::validate(const nlohmann::json& value) const {
  std::vector<std::string> errors;
  check(root_, value, "", errors);
  return errors;
}

const nlohmann::json& SchemaSubset::resolve(const std::string& ref) const {
  if (ref.rfind("#/", 0) != 0) throw std::invalid_argument("schema: only local $ref: " + ref);
  return root_.at(nlohmann::json::json_pointer(ref.substr(1)));
}

void SchemaSubset::check(const nlohmann::json& schema, const nlohmann::json& v, const std::string& at,
                         std::vector<std::string>& errors) const {
  if (schema.is_boolean()) {
    if (!schema.get<bool>()) errors.push_back(at + ": not allowed here");
    return;
  }
  const std::string where = at.empty() ? "/" : at;
  for (const auto& [key, rule] : schema.items()) {
    if (annotation(key)) continue;
    if (key == "$ref") {
      check(resolve(rule.get<std::string>()), v, at, errors);
    } else if (key == "type") {
      const std::vector<std::string> types =
          rule.is_array() ? rule.get<std::vector<std::string>>() : std::vector<std::string>{rule};
      bool any = false;
      for (const std::string& t : types) any = any || has_type(v, t);
      if (!any) errors.push_back(where + ": is " + std::string(v.type_name()) + ", not " + rule.dump());
    } else if (key == "const") {
      if (v != rule) errors.push_back(where + ": is " + v.dump() + ", not " + rule.dump());
    } else if (key == "enum") {
      bool any = false;
      for (const auto& option : rule) any = any || v == option;
      if (!any) errors.push_back(where + ": " + v.dump() + " is not one of " + rule.dump());
    } else if (key == "minimum" || key == "exclusiveMinimum") {
      if (v.is_number() &&
          (key == "minimum" ? v.get<double>() < rule.get<double>() : v.get<double>() <= rule.get<double>()))
        errors.push_back(where + ": " + v.dump() + " is below its " + key + " " + rule.dump());
    } else if (key == "required") {
      if (!v.is_object()) continue;
      for (const auto& name : rule) {
        if (!v.contains(name.get<std::string>()))
          errors.push_back(where + ": lacks the required field " + name.dump());
      }
    } else if (key == "properties") {
      if (!v.is_object()) continue;
      for (const auto& [name, sub] : rule.items()) {
        if (v.contains(name)) check(sub, v.at(name), at + "/" + name, errors);
      }
    } else if (key == "additionalProperties") {
      if (!v.is_object()) continue;
      const nlohmann::json properties = schema.value("properties", nlohmann::json::object());
      for (const auto& [name, sub] : v.items()) {
        if (!properties.contains(name)) check(rule, sub, at + "/" + name, errors);
      }
    } else if (key == "items") {
      if (!v.is_array()) continue;
      for (size_t k = 0; k < v.size(); ++k) check(rule, v[k], at + "/" + std::to_string(k), errors);
    } else if (key == "oneOf") {
      size_t matching = 0;
      for (const auto& option : rule) {
        std::vector<std::string> inner;
        check(option, v, at, inner);
        matching += inner.empty();
      }
      if (matching != 1)
        errors.push_back(where + ": " + v.dump().substr(0, 80) + " matches " + std::to_string(matching) +
                         " of the oneOf alternatives, not exactly one");
    } else {
      throw std::invalid_argument("schema: keyword `" + key + "` is not in the subset this validator checks");
    }
  }
}

}  // namespace openplx::testing
