// The evaluator: instantiates a root model into an ObjectGraph and computes attribute values lazily,
// memoised, independent of declaration order (../shared/spec/openplx-language.md §16).
//
// Which expression binds an attribute (§16.2): among the instance's ancestors, the one closest to the root
// that assigns it wins; within one instance's type chain, the most derived model; a declaration's default
// comes last. `becomes` chooses the attribute's type by the same rule. Errors are reported to the sink
// with the user's source line; a failed value is poisoned (Value::Kind::Error) and does not cascade.
#pragma once

#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "frontend/evaluation/function_ref.h"
#include "frontend/evaluation/object_graph.h"
#include "frontend/semantics/entry_reach.h"
#include "frontend/semantics/program.h"

namespace openplx::frontend {

class Evaluator;

// What a native function sees: its arguments, and helpers to read and make Math values.
class NativeCall {
 public:
  NativeCall(Evaluator& evaluator, SourceRange where) : evaluator_(evaluator), where_(where) {}
  Evaluator& evaluator() { return evaluator_; }
  SourceRange where() const { return where_; }
  double real(const Value& v);
  std::vector<double> reals(const Value& array);
  // Reads the Real attributes `fields` of an object value (e.g. {"x","y","z"}).
  std::vector<double> fields(const Value& object, std::initializer_list<std::string_view> names);
  Value object(const Value& of, std::string_view attribute);
  // A new free object of a bundle model (e.g. "Math.Vec3") with the given Real fields preset.
  Value make(std::string_view model, std::initializer_list<std::pair<std::string_view, double>> fields);
  Value make_with(std::string_view model, std::initializer_list<std::pair<std::string_view, Value>> fields);
  Value fail(const std::string& message);  // reports at the call and returns an error value
  // True when an input turned out to be an error value (already reported); the result is then discarded.
  bool poisoned() const { return poisoned_; }

 private:
  bool is_object(const Value& v);

  Evaluator& evaluator_;
  SourceRange where_;
  bool poisoned_ = false;
};

using NativeFunction = std::function<Value(NativeCall&, std::span<const Value>)>;

// Natives by qualified name: "Math.Vec3.from_xyz" for methods (instance methods get `this` as argument 0),
// "operator*(Math.Vec3,Real)" for operators.
class NativeRegistry {
 public:
  static NativeRegistry& global();
  void add(std::string name, NativeFunction fn) { functions_[std::move(name)] = std::move(fn); }
  const NativeFunction* find(const std::string& name) const {
    auto it = functions_.find(name);
    return it == functions_.end() ? nullptr : &it->second;
  }

 private:
  std::unordered_map<std::string, NativeFunction> functions_;
};

class Evaluator {
 public:
  Evaluator(Program& program, DiagnosticSink& sink);

  // Creates the root instance of `model` (errors: traits and non-models cannot be instantiated).
  ObjectId instantiate_root(ModelInfo* model);
  // Evaluates every attribute of the tree under `root`, reporting incomplete models.
  void evaluate_all(ObjectId root);
  // Checks the tree under `root` as evaluate_all would, evaluating far less: instances that share a slot
  // layout are bound by the same entries, so the first instance of each layout is evaluated in full and the
  // others are left to be evaluated when something reads them. Every instance of a layout whose check
  // reported anything (there or anywhere below it) is evaluated in full, so each reports at its own path.
  void evaluate_layouts(ObjectId root);
  // The instance of `object`'s layout that evaluate_layouts evaluated in full; kNoObject when none was.
  ObjectId checked_instance(const Object& object) const;
  // The type of the pure default (Object::pure_default) that slot `slot` of `object` will hold once read;
  // nullptr when it is evaluated already or holds anything else.
  const ModelInfo* pending_default(ObjectId object, uint32_t slot) const;
  // The first pure default of `type` that evaluate_layouts checked, with everything below it, without a
  // report; kNoObject when there is none. Every other pure default of the type has the same values, so
  // evaluate_layouts leaves those unmade and a reader may read this one in their place.
  ObjectId checked_default(const ModelInfo* type) const;
  // Whether `entry` made a new object for its attribute without reading anything of the instance it binds
  // (`{0, 0, 1}`, `Math.Vec3.Y_AXIS()`), every time it was evaluated: the object then has the same values
  // wherever the entry binds an attribute of one type. False until it has been evaluated once.
  bool instance_free(const Entry* entry) const {
    auto it = instance_free_.find(entry);
    return it != instance_free_.end() && it->second;
  }
  // The value of one attribute (evaluated on first use).
  const Value& value(ObjectId object, uint32_t slot);
  const Value* value(ObjectId object, std::string_view slot);

  ObjectGraph& graph() { return graph_; }
  const ObjectGraph& graph() const { return graph_; }

  // Marks attributes read by index as used while on (expressions, natives and reads by name always mark
  // them): the pipeline turns it on after evaluation, so an attribute never used is one nothing honours
  // (snap/unread_attributes.h warns about the ones a user set).
  void track_reads(bool on) { tracking_ = on; }
  Program& program() { return program_; }
  DiagnosticSink& sink() { return sink_; }
  std::string root_name() const;

  // Used by natives.
  ObjectId make_free_object(ModelInfo* model);
  void preset(ObjectId object, std::string_view slot, Value value);
  Type resolve_type(DocumentInfo* doc, const TypeExpr& type);
  Type resolve_type_ref(DocumentInfo* doc, const TypeRef& ref);

 private:
  bool tracking_ = false;
  bool reads_instance_ = false;  // the expression being evaluated read its instance (see instance_free)
  std::unordered_map<const Entry*, bool> instance_free_;

  struct Scope {
    DocumentInfo* doc = nullptr;
    ModelInfo* home = nullptr;
    ObjectId self = kNoObject;
  };
  struct Entity {
    enum class Kind { Value, Model, Namespace } kind = Kind::Value;
    Value value;
    ModelInfo* model = nullptr;
    Namespace* ns = nullptr;
  };
  struct Level {
    ObjectId object;
    std::string rel;        // path from this ancestor to the object being built, joined with '.'
    bool left_out = false;  // its entries are laid over the layout afterwards (overlay_assignments)
  };

  ObjectId new_object(ModelInfo* type, ObjectId owner, std::string name);
  bool owns_transitively(ObjectId owner, ObjectId id) const;
  void build_slots(ObjectId id);
  void build_slots_by_key(ObjectId id, const std::vector<ObjectId>& chain, uint32_t own_level);
  // Whether `type`'s entries at `rel` only assign values to attributes (no declarations, `becomes`, `with`,
  // annotations or entries on parts): such entries bind an instance without changing its layout.
  bool assigns_only(const ModelInfo* type, const std::string& rel) const;
  // Gives `id` the slots of the layout `key`, built now (without the entries of `left_out` levels) if new.
  // An enclosing level whose entries only assign the instance's attributes, and where they aim.
  using Overlay = std::pair<uint32_t, const EntryReach::Node*>;
  bool use_layout(ObjectId id, const std::string& key, const std::vector<ObjectId>& chain, uint32_t own_level,
                  const std::vector<Overlay>& left_out);
  // Binds `id`'s attributes to the assignments of the `overlays` levels; false (nothing changed) when one
  // is aimed at an attribute the layout lacks.
  bool overlay_assignments(ObjectId id, const std::vector<ObjectId>& chain,
                           const std::vector<Overlay>& overlays);
  void build_slots_from(ObjectId id, const std::vector<Level>& levels);
  // Calls visit(level, node) for each ancestor in `chain` (root first, the instance last) whose type's
  // entries aim at the instance or its parts, nearest the root first, until visit returns true.
  // `id` and its owners, root first.
  void owner_chain(ObjectId id, std::vector<ObjectId>& chain) const;
  template <typename Visit>
  void for_each_reaching(const std::vector<ObjectId>& chain, Visit&& visit) const;
  bool assigns_only(const ModelInfo* type, const EntryReach::Node& node) const;
  std::vector<Level> levels_of(ObjectId id) const;
  // The entries aimed at one instance's attributes (see collect_targeting).
  struct Targeting {
    std::vector<Binding> ordered;  // priority order
    std::unordered_map<std::string_view, std::vector<uint32_t>> by_name;
    std::unordered_map<std::string_view, bool> below;  // attributes with entries on their parts: assigned?
    std::vector<std::pair<const Entry*, ModelInfo*>> annotations;
  };
  Targeting collect_targeting(const std::vector<Level>& levels) const;
  static std::vector<uint32_t> candidates(const Targeting& t, const Object& object, std::string_view slot);
  static Binding pick_value(const Targeting& t, const std::vector<uint32_t>& candidates,
                            bool include_declarations);
  const Entry* entry_below(ObjectId id, std::string_view slot) const;
  const Type& declared_type(const Entry& declaration, ModelInfo* model);
  Type merged_becomes_type(const std::vector<Binding>& all);
  // An entry written with a 0.17.8 attribute name (`charges`) that binds this slot (`connectors`).
  static bool is_renamed_to(const Object& object, std::string_view written, std::string_view slot);
  void evaluate_slot(ObjectId id, uint32_t slot_index);
  Value owned_default(ObjectId id, Slot& slot);
  void adopt(ObjectId child, ObjectId owner, const std::string& name, uint32_t level);
  // Whether an enclosing model's entries aim at `id` or its parts.
  bool reached_by_entries(ObjectId id) const;
  // A free object's subtree (itself and the values preset in it) placed `levels` below the root.
  void move_free_subtree(ObjectId id, uint32_t levels);
  ObjectId singleton(ModelInfo* model);
  Value global_value(GlobalInfo* global);
  std::string slot_path(ObjectId id, std::string_view slot) const;

  Value eval(ExprId expr, const Scope& scope, const Type* expected);
  Entity eval_entity(ExprId expr, const Scope& scope);
  Entity eval_member_entity(const Expr& member, const Scope& scope);
  // eval_entity's dotted model and namespace names, by document and text (a thousand `Math.Vec3.Y_AXIS()`).
  std::unordered_map<std::string, Entity> static_names_;
  std::string static_name_key_;
  Value member_of(const Value& object, std::string_view name, SourceRange where);
  Value eval_call(const Expr& call, const Scope& scope);
  struct PreparedMethod {
    std::string qualified;  // "Math.Vec3.from_xyz"
    std::vector<Type> params;
    Type result;
    const NativeFunction* native = nullptr;
    std::optional<std::string_view> renamed;  // its current name, when this one is a pre-0.10 name
  };
  const PreparedMethod& prepare(ModelInfo* owner, const MethodInfo& method);
  Value call_method(ModelInfo* owner_type, const MethodInfo& method, std::optional<Value> self,
                    std::vector<ExprId> args, const Scope& scope, SourceRange where);
  Value eval_binary(const Expr& e, const Scope& scope, const Type* expected);
  Value eval_unary(const Expr& e, const Scope& scope, const Type* expected);
  Value eval_initializer(const Expr& e, const Scope& scope, const Type* expected);
  Value apply_operator(char op, const std::vector<Value>& operands, SourceRange where, bool report);
  const OperatorInfo* find_operator(char op, const std::vector<Type>& operand_types,
                                    std::vector<Type>* params);
  Type type_of(const Value& v) const;
  const MethodInfo* find_method(ModelInfo* model, std::string_view name, ModelInfo** owner);

  // Checks and converts `v` for a slot or parameter of type `target`; reports at `where`.
  using Describe = FunctionRef<std::string()>;  // valid only during the call it is passed to
  Value convert(Value v, const Type& target, SourceRange where, const Describe& what);
  bool assignable(const Value& v, const Type& target) const;
  static bool is_path_expression(const Document& doc, ExprId expr);

  Program& program_;
  DiagnosticSink& sink_;
  ObjectGraph graph_;
  std::unordered_map<ModelInfo*, ObjectId> singletons_;
  std::unordered_map<GlobalInfo*, std::pair<int, Value>> globals_;  // state 1 = evaluating, 2 = done
  std::unordered_set<const Entry*> reported_unknown_;
  std::unordered_map<const Entry*, Type>
      declared_types_;  // a declaration's type resolves the same everywhere  // one message per wrong entry,
                        // however many instances
  int eval_depth_ = 0;
  std::unordered_map<const MethodInfo*, PreparedMethod> prepared_methods_;
  std::unordered_map<uint32_t, ObjectId> checked_;  // layout -> its instance evaluated in full
  // Type -> its first pure default once that was checked through (kNoObject: it reported something).
  std::unordered_map<const ModelInfo*, ObjectId> checked_defaults_;
  bool may_skip(ObjectId holder, uint32_t slot) const;
  std::unordered_set<uint32_t> noisy_;  // layouts whose check reported something
  // Slot layouts shared by instances of one type reached by the same enclosing entries (see build_slots).
  struct Layout {
    ModelInfo* type = nullptr;  // after `with` lines of enclosing blocks
    uint32_t own_level = 0;     // the level of the instance it was built for (bindings' levels count from it)
    std::vector<Slot> slots;
    std::shared_ptr<const SlotIndex> index;
    std::shared_ptr<const std::vector<SlotInfo>> infos;
    uint32_t id = 0;
  };
  void copy_layout(ObjectId id, const Layout& layout, const std::vector<ObjectId>& chain, uint32_t own_level);
  std::unordered_map<std::string, Layout> layouts_;
  // Reach states: for an instance, every enclosing model's (and its own type's) node of entries that goes
  // down to it, with its distance. A part's layout follows from its owner's reach state, its attribute and
  // its type, so each combination is worked out once (build_slots) and then copied.
  using ReachState = std::vector<std::pair<uint32_t, const EntryReach::Node*>>;
  uint32_t reach_state(const std::vector<ObjectId>& chain);
  void forget_reach(ObjectId id);  // a value adopted with its parts: their reach states no longer hold
  std::map<ReachState, uint32_t> reach_ids_;
  struct PartKey {  // the owner's reach state and slot (its index names the slot), the part's type
    uint32_t owner_reach;
    uint32_t slot;
    const SlotIndex* index;
    const ModelInfo* type;
    bool operator==(const PartKey&) const = default;
  };
  struct PartKeyHash {
    size_t operator()(const PartKey& k) const {
      const std::hash<const void*> h;
      return h(k.type) ^ h(k.index) * 31 ^ (size_t{k.owner_reach} << 32 | k.slot) * 0x9e3779b97f4a7c15ull;
    }
  };
  struct PartLayout {
    const Layout* layout;
    uint32_t reach;
  };
  std::unordered_map<PartKey, PartLayout, PartKeyHash> part_layouts_;
  uint32_t next_layout_ = 1;
  mutable EntryReach entry_reach_;             // built per type on first use
  std::vector<ObjectId> chain_;                // build_slots' ancestor chain
  mutable std::vector<ObjectId> reach_chain_;  // reached_by_entries' ancestor chain
  std::string layout_key_, full_layout_key_;   // build_slots' keys, reused
  std::vector<Overlay> overlays_;              // build_slots' overlays, reused
  std::deque<Type> narrowed_types_;            // types `becomes` gave slots (slots point at them)
};

// The root model of a loaded file: `name` if given, else the last model declared. Reports
// `No model could be found` / unknown model.
ModelInfo* select_root_model(Program& program, DocumentInfo* doc, const std::string* name);

}  // namespace openplx::frontend
