// The evaluated instance tree: the IR the resolved-system builder (snap/) reads; the emitter and the runtime
// see only the resolved system built from it.
//
// Objects are model instances held by index. Each attribute is a Slot with its effective type, the entry
// that bound it, whether that binding is an explicit assignment (SNAP needs "undefined local transform"),
// and its value once evaluated. An owned model-typed attribute holds a child object; a reference holds the
// id of an object owned elsewhere (or of a const singleton).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "frontend/evaluation/value.h"
#include "frontend/semantics/program.h"

namespace openplx::frontend {

struct Binding {
  const Entry* entry = nullptr;
  ModelInfo* model = nullptr;   // the model whose text holds the entry (name lookup, `this` type)
  ObjectId self = kNoObject;    // the instance `this` means when evaluating it
  uint32_t level = UINT32_MAX;  // ancestor depth it came from: 0 = root; lower wins
};

struct AnnotationValue {
  ExprId expr = 0;
  const Document* doc = nullptr;
};

// What every instance of one layout shares about an attribute (see Slot).
struct SlotInfo {
  std::string_view name;
  const Entry* declaration = nullptr;
  ModelInfo* declared_in = nullptr;
  const Type* type =
      nullptr;  // the declared type or the one `becomes` narrowed it to (owned by the Evaluator)
  bool optional = false;
  // Annotations on the attribute (few have any).
  std::shared_ptr<std::map<std::string, AnnotationValue, std::less<>>> annotations;
};

// One attribute of one instance: what its layout says of it (info, shared), and its own binding and value.
struct Slot {
  const SlotInfo* info = nullptr;
  Binding binding;              // the value's source; entry == nullptr when nothing binds it
  bool explicit_value = false;  // assigned (not a declaration default), itself or any part of it
  bool entries_below = false;   // some entry targets a part of it (an error unless it owns an instance)
  enum class State : uint8_t { Pending, Evaluating, Done } state = State::Pending;
  bool owns = false;    // value is an object owned by this slot
  bool preset = false;  // value given directly (initializer or native result), not by an entry
  bool used = false;    // read by an expression, a native or the pipeline (Evaluator::track_reads)
  Value value;

  std::string_view name() const { return info->name; }
  const Entry* declaration() const { return info->declaration; }
  ModelInfo* declared_in() const { return info->declared_in; }
  const Type* type() const { return info->type; }
  bool optional() const { return info->optional; }
  const std::map<std::string, AnnotationValue, std::less<>>* annotations() const {
    return info->annotations.get();
  }
};

// Attribute name -> slot index. Instances whose layout comes from their type alone share one.
using SlotIndex = std::unordered_map<std::string_view, uint32_t>;

struct Object {  // fields ordered so that none pads: there is one per instance
  ModelInfo* type = nullptr;
  ObjectId owner = kNoObject;
  uint32_t depth = 0;
  std::string name;  // attribute name in the owner; the model name for roots and const singletons
  const Entry* created_by = nullptr;  // the declaration of the owning attribute, for owned defaults
  uint32_t layout = 0;  // instances with one layout have the same slots bound by the same entries
  // Where the entries of it and its owners reach (Evaluator::build_slots); 0 when unknown (a value adopted
  // after it was made).
  uint32_t reach = 0;
  bool is_const_singleton = false;
  // An owned default no entry assigns or reaches into: its values are its type's alone, the same in every
  // such instance (Evaluator::checked_default).
  bool pure_default = false;
  std::vector<Slot> slots;
  std::shared_ptr<const SlotIndex> index;
  std::shared_ptr<const std::vector<SlotInfo>> infos;  // what the slots' info point at

  const Slot* find(std::string_view slot) const {
    auto it = index->find(slot);
    return it == index->end() ? nullptr : &slots[it->second];
  }
  bool has(std::string_view slot) const { return index->count(slot) != 0; }
};

// Elements by index in fixed chunks that never move, so references stay valid while evaluation adds
// objects; indexing is a shift and a mask (std::deque keeps only four Objects per block and divides).
template <typename T>
class ChunkedVector {
 public:
  size_t size() const { return size_; }
  T& operator[](size_t i) { return chunks_[i >> kShift][i & kMask]; }
  const T& operator[](size_t i) const { return chunks_[i >> kShift][i & kMask]; }
  T& emplace_back() {
    if ((size_ >> kShift) == chunks_.size()) chunks_.push_back(std::make_unique<T[]>(kMask + 1));
    return (*this)[size_++];
  }

 private:
  static constexpr size_t kShift = 10, kMask = (size_t{1} << kShift) - 1;
  std::vector<std::unique_ptr<T[]>> chunks_;
  size_t size_ = 0;
};

struct ObjectGraph {
  ChunkedVector<Object> objects;  // stable references: evaluation creates objects while others are in use
  ObjectId root = kNoObject;

  Object& at(ObjectId id) { return objects[id]; }
  const Object& at(ObjectId id) const { return objects[id]; }
  // Dotted path from the root (not including the root's name); const singletons by their model name.
  std::string path(ObjectId id) const;
};

}  // namespace openplx::frontend
