// Types and values of evaluated OpenPLX (spec §5, §10, §12). Model instances are Objects in the
// ObjectGraph; a Value refers to one by ObjectId.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace openplx::frontend {

struct ModelInfo;

enum class TypeKind : uint8_t { Error, Int, Real, Bool, String, Model, Union };

struct Type {
  TypeKind kind = TypeKind::Error;
  ModelInfo* model = nullptr;      // Model
  std::vector<Type> alternatives;  // Union
  bool is_array = false;

  static Type primitive(TypeKind kind) {
    Type t;
    t.kind = kind;
    return t;
  }
  static Type of_model(ModelInfo* model) {
    Type t;
    t.kind = TypeKind::Model;
    t.model = model;
    return t;
  }
  bool is_primitive() const { return kind != TypeKind::Model && kind != TypeKind::Union; }
  Type element() const {
    Type t = *this;
    t.is_array = false;
    return t;
  }
  std::string describe() const;
};

using ObjectId = uint32_t;
inline constexpr ObjectId kNoObject = UINT32_MAX;

struct Value {
  enum class Kind : uint8_t { Unset, Error, Int, Real, Bool, String, Object, Array };
  Kind kind = Kind::Unset;
  bool bool_value = false;
  ObjectId object = kNoObject;  // beside the two small fields: no padding
  union {                       // by kind: one number, never both
    int64_t int_value = 0;
    double real_value;
  };

  Value() = default;
  Value(const Value& other)
      : kind(other.kind),
        bool_value(other.bool_value),
        object(other.object),
        int_value(other.int_value),  // the whole union, whichever member it holds
        payload_(other.payload_ ? std::make_unique<Payload>(*other.payload_) : nullptr) {}
  Value(Value&&) noexcept = default;
  Value& operator=(const Value& other);
  Value& operator=(Value&&) noexcept = default;
  ~Value();

  // A string's text and an array's items are rare beside numbers and objects; they live behind one pointer
  // so that a Value, held by every attribute of every instance, stays 24 bytes.
  const std::string& string_value() const;
  const std::vector<Value>& array() const;
  std::vector<Value>& array();

  static Value error() { return make(Kind::Error); }
  static Value of_int(int64_t v) {
    Value r = make(Kind::Int);
    r.int_value = v;
    return r;
  }
  static Value of_real(double v) {
    Value r = make(Kind::Real);
    r.real_value = v;
    return r;
  }
  static Value of_bool(bool v) {
    Value r = make(Kind::Bool);
    r.bool_value = v;
    return r;
  }
  static Value of_string(std::string v);
  static Value of_object(ObjectId id) {
    Value r = make(Kind::Object);
    r.object = id;
    return r;
  }
  static Value of_array(std::vector<Value> items);
  bool is_error() const { return kind == Kind::Error; }
  bool is_number() const { return kind == Kind::Int || kind == Kind::Real; }
  double as_real() const { return kind == Kind::Int ? static_cast<double>(int_value) : real_value; }

 private:
  struct Payload;
  static Value make(Kind kind) {
    Value v;
    v.kind = kind;
    return v;
  }
  Payload& payload();
  std::unique_ptr<Payload> payload_;
};

struct Value::Payload {
  std::string text;
  std::vector<Value> items;
};

inline Value::~Value() = default;

inline Value& Value::operator=(const Value& other) {
  if (this == &other) return *this;
  kind = other.kind;
  bool_value = other.bool_value;
  object = other.object;
  int_value = other.int_value;  // the whole union, whichever member it holds
  payload_ = other.payload_ ? std::make_unique<Payload>(*other.payload_) : nullptr;
  return *this;
}

inline Value::Payload& Value::payload() {
  if (!payload_) payload_ = std::make_unique<Payload>();
  return *payload_;
}

inline const std::string& Value::string_value() const {
  static const std::string none;
  return payload_ ? payload_->text : none;
}

inline const std::vector<Value>& Value::array() const {
  static const std::vector<Value> none;
  return payload_ ? payload_->items : none;
}

inline std::vector<Value>& Value::array() {
  return payload().items;
}

inline Value Value::of_string(std::string v) {
  Value r = make(Kind::String);
  r.payload().text = std::move(v);
  return r;
}

inline Value Value::of_array(std::vector<Value> items) {
  Value r = make(Kind::Array);
  r.payload().items = std::move(items);
  return r;
}

static_assert(sizeof(Value) == 24, "a Value is held by every slot of every instance");

}  // namespace openplx::frontend
