// Test support: a JSON Schema validator for the subset docs/signals.schema.json uses (no JSON Schema library
// is packaged here): type, const, enum, required, properties, additionalProperties, items, oneOf, minimum,
// exclusiveMinimum and local $ref ("#/$defs/..."). Annotations (description, title, $comment, x-*, ...) are
// skipped; any other keyword is an error, so the schema cannot rely on a rule this validator would not check.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace openplx::testing {

class SchemaSubset {
 public:
  explicit SchemaSubset(nlohmann::json schema) : root_(std::move(schema)) {}

  // Every violation, each as "JSON-POINTER: what"; empty when `value` is valid.
  std::vector<std::string> validate(const nlohmann::json& value) const;

 private:
  const nlohmann::json& resolve(const std::string& ref) const;
  void check(const nlohmann::json& schema, const nlohmann::json& v, const std::string& at,
             std::vector<std::string>& errors) const;

  nlohmann::json root_;
};

}  // namespace openplx::testing
