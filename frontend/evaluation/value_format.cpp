#include "frontend/evaluation/value_format.h"

#include <charconv>
#include <cmath>
#include <ostream>

#include "frontend/syntax/quoted.h"

#include "frontend/evaluation/evaluator.h"

namespace openplx::frontend {
namespace {

// Vectors and quaternions read best as one value; every other model instance is a subtree.
bool is_inline_type(const ModelInfo* type) {
  for (const ModelInfo* m : type->linearization()) {
    if (m->qualified == "Math.Vec2" || m->qualified == "Math.Vec3" || m->qualified == "Math.Quat")
      return true;
  }
  return false;
}

}  // namespace

std::string format_real(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  std::string text(buffer, end);
  if (text.find_first_of(".en") == std::string::npos) text += ".0";
  return text;
}

std::string describe_value_type(const Value& value, const ObjectGraph& graph) {
  switch (value.kind) {
    case Value::Kind::Unset:
      return "unset";
    case Value::Kind::Error:
      return "<error>";
    case Value::Kind::Int:
      return "Int";
    case Value::Kind::Real:
      return "Real";
    case Value::Kind::Bool:
      return "Bool";
    case Value::Kind::String:
      return "String";
    case Value::Kind::Object:
      return graph.at(value.object).type->qualified;
    case Value::Kind::Array:
      return "array";
  }
  return "?";
}

std::string format_value(Evaluator& evaluator, const Value& value, bool owned) {
  const ObjectGraph& graph = evaluator.graph();
  switch (value.kind) {
    case Value::Kind::Unset:
      return "unset";
    case Value::Kind::Error:
      return "<error>";
    case Value::Kind::Int:
      return std::to_string(value.int_value);
    case Value::Kind::Real:
      return format_real(value.real_value);
    case Value::Kind::Bool:
      return value.bool_value ? "true" : "false";
    case Value::Kind::String:
      return quoted(value.string_value());
    case Value::Kind::Array: {
      std::string out = "[";
      for (size_t i = 0; i < value.array().size(); ++i) {
        const Value& item = value.array()[i];
        const bool item_owned = item.kind == Value::Kind::Object &&
                                graph.at(item.object).owner == kNoObject &&
                                !graph.at(item.object).is_const_singleton;
        out += (i ? ", " : "") + format_value(evaluator, item, item_owned);
      }
      return out + "]";
    }
    case Value::Kind::Object: {
      const Object& obj = graph.at(value.object);
      if (is_inline_type(obj.type)) {
        std::string out = "{";
        for (uint32_t i = 0; i < obj.slots.size(); ++i) {
          out += (i ? ", " : "") + format_value(evaluator, evaluator.value(value.object, i), true);
        }
        return out + "}";
      }
      if (owned) return obj.type->qualified;
      const std::string path = graph.path(value.object);
      return "-> " + (path.empty() ? evaluator.root_name() : path);
    }
  }
  return "?";
}

void dump_values(std::ostream& out, Evaluator& evaluator, ObjectId root) {
  // Iterative, so deep instance trees cannot exhaust the stack.
  struct Frame {
    ObjectId object;
    uint32_t next;
  };
  std::vector<Frame> stack{{root, 0}};
  while (!stack.empty()) {
    Frame& frame = stack.back();
    if (frame.next >= evaluator.graph().at(frame.object).slots.size()) {
      stack.pop_back();
      continue;
    }
    const ObjectId id = frame.object;
    const uint32_t index = frame.next++;
    const Value& value = evaluator.value(id, index);
    const Slot& slot = evaluator.graph().at(id).slots[index];
    const std::string base = evaluator.graph().path(id);
    out << (base.empty() ? "" : base + ".") << slot.name() << " = "
        << format_value(evaluator, value, slot.owns) << '\n';
    if (slot.owns && value.kind == Value::Kind::Object &&
        !is_inline_type(evaluator.graph().at(value.object).type)) {
      stack.push_back({value.object, 0});
    }
  }
}

}  // namespace openplx::frontend
