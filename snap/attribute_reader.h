// Typed reads of evaluated attributes for the resolved-system builder: a missing attribute or one of another
// kind gives the fallback, never an error (the evaluator has already reported bad values).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "frontend/evaluation/evaluator.h"
#include "snap/resolved_system.h"

namespace openplx::snap {

// Where an attribute sits in the objects of one layout, found ahead of reading it (SlotTable).
struct AttributeSlot {
  static constexpr uint32_t kAbsent = UINT32_MAX;
  uint32_t index = kAbsent;
  bool present() const { return index != kAbsent; }
};

// The slots of a fixed list of attribute names, per layout: the instances of one layout share their slot
// index, so reading the same attributes of many instances looks each name up once, not once per read.
template <size_t N>
class SlotTable {
 public:
  using Slots = std::array<AttributeSlot, N>;
  explicit SlotTable(std::array<std::string_view, N> names) : names_(names) {}

  Slots of(const frontend::Object& object) {
    if (object.layout >= rows_.size()) rows_.resize(object.layout + 1);
    Row& row = rows_[object.layout];
    if (row.index != object.index.get()) {  // first met (the index confirms the layout)
      row.index = object.index.get();
      for (size_t k = 0; k < N; ++k) {
        auto it = object.index->find(names_[k]);
        row.slots[k] = it == object.index->end() ? AttributeSlot{} : AttributeSlot{it->second};
      }
    }
    return row.slots;
  }

 private:
  struct Row {
    const frontend::SlotIndex* index = nullptr;
    Slots slots;
  };
  std::array<std::string_view, N> names_;
  std::vector<Row> rows_;  // by layout
};

// Attributes are named (a string) or found ahead (an AttributeSlot). A read by slot marks the attribute used
// only while the evaluator tracks reads, as it does while resolve_system builds the resolved system.
class AttributeReader {
 public:
  explicit AttributeReader(frontend::Evaluator& evaluator, frontend::DiagnosticSink* sink = nullptr)
      : ev_(evaluator), sink_(sink) {}

  // Values nothing can simulate (a negative mass, an infinite position) are invalid-value errors at the
  // user's line (value_checks.cpp), reported to the sink given at construction, if any.
  // Where `object.name`'s value was written: the user's assignment of it or of the object holding it (a
  // vector written whole), else where the user declared the object; a bundle's default is no user's line.
  frontend::SourceRange written_at(frontend::ObjectId object, std::string_view name) const;
  // Reports "`path.name` is VALUE; RULE" unless `valid`; returns `valid`.
  bool require(bool valid, frontend::ObjectId object, std::string_view name, double value,
               std::string_view rule);
  // Reports "`path.name` WHAT" where it was written, for a value no number describes (an empty list).
  void refuse(frontend::ObjectId object, std::string_view name, std::string_view what);
  // The same for each component of a Math.Vec3 (x, y, z) or Math.Quat (also w) attribute: all finite.
  bool require_finite_components(frontend::ObjectId vector, std::string_view rule);

  frontend::Evaluator& evaluator() { return ev_; }
  const frontend::ObjectGraph& graph() const { return ev_.graph(); }

  const frontend::Value* value(frontend::ObjectId id, std::string_view name) { return ev_.value(id, name); }
  const frontend::Value* value(frontend::ObjectId id, AttributeSlot slot) {
    return slot.present() ? &ev_.value(id, slot.index) : nullptr;
  }

  template <typename Attribute>
  std::optional<double> number(frontend::ObjectId id, const Attribute& attribute) {
    const frontend::Value* v = value(id, attribute);
    return v && v->is_number() ? std::optional<double>(v->as_real()) : std::nullopt;
  }
  template <typename Attribute>
  double real(frontend::ObjectId id, const Attribute& attribute, double fallback = 0.0) {
    return number(id, attribute).value_or(fallback);
  }
  template <typename Attribute>
  std::optional<bool> boolean(frontend::ObjectId id, const Attribute& attribute) {
    const frontend::Value* v = value(id, attribute);
    return v && v->kind == frontend::Value::Kind::Bool ? std::optional<bool>(v->bool_value) : std::nullopt;
  }
  std::optional<std::string> string(frontend::ObjectId id, std::string_view name) {
    const frontend::Value* v = ev_.value(id, name);
    return v && v->kind == frontend::Value::Kind::String ? std::optional<std::string>(v->string_value())
                                                         : std::nullopt;
  }
  template <typename Attribute>
  frontend::ObjectId object(frontend::ObjectId id, const Attribute& attribute) {
    const frontend::Value* v = value(id, attribute);
    return v && v->kind == frontend::Value::Kind::Object ? v->object : frontend::kNoObject;
  }
  // The objects of an array attribute, in order (items that are not objects are skipped).
  template <typename Attribute>
  std::vector<frontend::ObjectId> objects(frontend::ObjectId id, const Attribute& attribute) {
    std::vector<frontend::ObjectId> out;
    const frontend::Value* v = value(id, attribute);
    if (v && v->kind == frontend::Value::Kind::Array) {
      for (const frontend::Value& item : v->array())
        if (item.kind == frontend::Value::Kind::Object) out.push_back(item.object);
    }
    return out;
  }
  const std::string& type_name(frontend::ObjectId id) const { return graph().at(id).type->qualified; }
  // The attribute's type when it is still to become that type's own default instance: nothing assigns it
  // or reaches into it, so its values are the type's alone and the same in every such attribute. A value
  // read from one can stand for all (a body's transforms are five objects each, read once). Else nullptr.
  template <typename Attribute>
  const frontend::ModelInfo* pending_default(frontend::ObjectId id, const Attribute& attribute) const;
  // An owned part read only for its values (never for where it is): a pending default reads as the checked
  // default of its type (Evaluator::checked_default), which has the same values, instead of being made.
  template <typename Attribute>
  frontend::ObjectId values_of(frontend::ObjectId id, const Attribute& attribute) {
    if (const frontend::ModelInfo* type = pending_default(id, attribute)) {
      if (const frontend::ObjectId same = ev_.checked_default(type); same != frontend::kNoObject) return same;
    }
    return object(id, attribute);
  }
  // A Math.Vec3 attribute (zero when absent; a component that is not a number is 0).
  // Two kinds of vector read once and remembered: a pending default's (by its type), and one written the
  // same way for every instance (`size: {0.1, 0.1, 1}` in a model that has a thousand instances; by entry).
  template <typename Attribute>
  Eigen::Vector3d vec3(frontend::ObjectId id, const Attribute& attribute) {
    const frontend::ModelInfo* shared = pending_default(id, attribute);
    if (shared) {
      if (auto it = default_vec3_.find(shared); it != default_vec3_.end()) return it->second;
    }
    const WrittenAlike alike = written_alike(id, attribute);
    if (alike.entry && ev_.instance_free(alike.entry)) {
      if (auto it = alike_vec3_.find(alike); it != alike_vec3_.end()) return it->second;
    }
    const frontend::ObjectId v = object(id, attribute);
    if (v == frontend::kNoObject) return Eigen::Vector3d::Zero();
    const SlotTable<3>::Slots xyz = xyz_.of(graph().at(v));
    const Eigen::Vector3d out{real(v, xyz[0]), real(v, xyz[1]), real(v, xyz[2])};
    if (shared) default_vec3_.emplace(shared, out);
    if (alike.entry && ev_.instance_free(alike.entry)) alike_vec3_.emplace(alike, out);
    return out;
  }
  // A Math.Quat's components x, y, z, w; one absent or not a number is 0 (w: 1).
  std::array<double, 4> xyzw(frontend::ObjectId quat) {
    const SlotTable<4>::Slots slots = xyzw_.of(graph().at(quat));
    std::array<double, 4> c = {0, 0, 0, 1};
    for (size_t i = 0; i < c.size(); ++i) c[i] = real(quat, slots[i], c[i]);
    return c;
  }

 private:
  frontend::Evaluator& ev_;
  frontend::DiagnosticSink* sink_;
  // Vectors and quaternions are read on every transform and connector.
  SlotTable<3> xyz_{{"x", "y", "z"}};
  SlotTable<4> xyzw_{{"x", "y", "z", "w"}};
  std::unordered_map<const frontend::ModelInfo*, Eigen::Vector3d> default_vec3_;  // by pending_default
  // An attribute's binding entry, with the attribute's type and the type of the instance the entry reads
  // names in: an entry that reads nothing of its instance gives equal values wherever all three are equal,
  // unless entries on the attribute's parts change them (then it has none).
  struct WrittenAlike {
    const frontend::Entry* entry = nullptr;
    const frontend::Type* type = nullptr;
    const frontend::ModelInfo* self_type = nullptr;
    bool operator==(const WrittenAlike&) const = default;
  };
  struct WrittenAlikeHash {
    size_t operator()(const WrittenAlike& k) const {
      const std::hash<const void*> h;
      return h(k.entry) ^ (h(k.type) * 31) ^ (h(k.self_type) * 961);
    }
  };
  template <typename Attribute>
  WrittenAlike written_alike(frontend::ObjectId id, const Attribute& attribute) const;
  std::unordered_map<WrittenAlike, Eigen::Vector3d, WrittenAlikeHash> alike_vec3_;
};

template <typename Attribute>
AttributeReader::WrittenAlike AttributeReader::written_alike(frontend::ObjectId id,
                                                             const Attribute& attribute) const {
  const frontend::Object& object = graph().at(id);
  uint32_t index = AttributeSlot::kAbsent;
  if constexpr (std::is_same_v<Attribute, AttributeSlot>) {
    index = attribute.index;
  } else if (auto it = object.index->find(attribute); it != object.index->end()) {
    index = it->second;
  }
  if (index == AttributeSlot::kAbsent) return {};
  const frontend::Slot& slot = object.slots[index];
  // Entries on its parts (`position.x: 2` beside `position: {0, 1, 0}`) make each instance's value its own.
  if (!slot.binding.entry || slot.entries_below || slot.binding.self == frontend::kNoObject) return {};
  return {slot.binding.entry, slot.type(), graph().at(slot.binding.self).type};
}

template <typename Attribute>
const frontend::ModelInfo* AttributeReader::pending_default(frontend::ObjectId id,
                                                            const Attribute& attribute) const {
  if constexpr (std::is_same_v<Attribute, AttributeSlot>) {
    return attribute.present() ? ev_.pending_default(id, attribute.index) : nullptr;
  } else {
    const frontend::Object& object = graph().at(id);
    auto it = object.index->find(attribute);
    return it == object.index->end() ? nullptr : ev_.pending_default(id, it->second);
  }
}

}  // namespace openplx::snap
