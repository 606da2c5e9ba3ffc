// Every Input and Output model the project's bundles declare, found from the bundles themselves: each file's
// declared names (the bundle index, as this build carries it) are looked up as models in a Program and kept
// when they derive from Physics.Signals.Input or Physics.Signals.Output. For each, the attribute naming what
// it attaches to (`source`, else the first own attribute of a model type: `torque_converter`, `targets`)
// and the types that attribute accepts.
#pragma once

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "frontend/bundles/bundles.h"
#include "frontend/bundles/embedded_bundles.h"
#include "frontend/semantics/program.h"

namespace openplx::catalogue {

namespace fe = openplx::frontend;

struct SignalType {
  std::string name;  // qualified, e.g. "Physics.Signals.AngleOutput"
  bool input = false;
  std::string source_attribute;      // "source", "torque_converter", "targets"; "" when it has none
  std::vector<std::string> accepts;  // qualified types the attribute takes (`A or B`: both)
  bool accepts_array = false;        // `targets is Physics.Signals.Input[]`
  bool has_relative_to = false;      // it can be measured relative to something (`relative_to`)
};

namespace detail {

inline void collect_names(const fe::embedded::Dir& dir, const std::string& ns,
                          std::vector<std::string>& out) {
  for (const fe::embedded::File& file : fe::embedded::files(dir)) {
    if (file.name == "config.openplx") continue;
    for (const std::string& name : fe::embedded::declarations(file).names) out.push_back(ns + "." + name);
  }
  for (const fe::embedded::Dir& sub : fe::embedded::subdirs(dir))
    collect_names(sub, ns.empty() ? std::string(sub.name) : ns + "." + std::string(sub.name), out);
}

// Attributes every signal has that say nothing of what it is attached to.
inline bool is_signal_plumbing(std::string_view attribute) {
  return attribute == "type" || attribute == "marshalling" || attribute == "enabled" ||
         attribute == "reference_id" || attribute == "initial_value" || attribute == "relative_to";
}

// The declaration (or `becomes`) of `attribute` nearest `model` in its linearization.
inline const fe::Entry* declaration_of(const fe::ModelInfo* model, std::string_view attribute) {
  for (const fe::ModelInfo* m : model->linearization()) {
    for (const fe::Entry& e : m->entries) {
      if ((e.kind == fe::Entry::Kind::Declare || e.kind == fe::Entry::Kind::Becomes) && e.path.size() == 1 &&
          e.path[0] == attribute)
        return &e;
    }
  }
  return nullptr;
}

// The model that declares `entry` (its text resolves the entry's type names).
inline fe::ModelInfo* owner_of(fe::ModelInfo* model, const fe::Entry* entry) {
  for (fe::ModelInfo* m : model->linearization()) {
    if (!m->entries.empty() && entry >= &m->entries.front() && entry <= &m->entries.back()) return m;
  }
  return model;
}

// The attribute a signal attaches by: `source`, else the first attribute (own, then inherited) whose type
// is a bundle model rather than a number, flag or text.
inline const fe::Entry* attachment(fe::Program& program, fe::ModelInfo* model) {
  if (const fe::Entry* source = declaration_of(model, "source")) return source;
  for (fe::ModelInfo* m : model->linearization()) {
    for (const fe::Entry& e : m->entries) {
      if (e.kind != fe::Entry::Kind::Declare || e.path.size() != 1 || !e.member) continue;
      if (is_signal_plumbing(e.path[0]) || e.member->type.alternatives.empty()) continue;
      fe::ModelInfo* type = program.resolve_model_name(m->doc, e.member->type.alternatives[0].name, false);
      if (type && type->doc && type->doc->bundle) return &e;
    }
  }
  return nullptr;
}

}  // namespace detail

// Sorted by name. `program` must hold the project's bundles (set_bundles); diagnostics go to its sink.
inline std::vector<SignalType> bundle_signal_types(fe::Program& program) {
  std::vector<std::string> names;
  detail::collect_names(fe::embedded::root(), "", names);
  fe::ModelInfo* input = program.builtin_model("Physics.Signals.Input");
  fe::ModelInfo* output = program.builtin_model("Physics.Signals.Output");
  if (!input || !output || !program.resolve(input) || !program.resolve(output)) return {};
  std::vector<SignalType> types;
  for (const std::string& name : names) {
    fe::ModelInfo* model = program.builtin_model(name);
    if (!model || model->is_trait || model == input || model == output || !program.resolve(model)) continue;
    const bool is_input = model->is_subtype_of(input), is_output = model->is_subtype_of(output);
    if (!is_input && !is_output) continue;
    SignalType t;
    t.name = model->qualified;
    t.input = is_input;
    t.has_relative_to = detail::declaration_of(model, "relative_to") != nullptr;
    if (const fe::Entry* e = detail::attachment(program, model)) {
      t.source_attribute = std::string(e->path[0]);
      fe::ModelInfo* owner = detail::owner_of(model, e);
      for (const fe::TypeRef& ref : e->member->type.alternatives) {
        fe::ModelInfo* accepted = program.resolve_model_name(owner->doc, ref.name, false);
        t.accepts.push_back(accepted ? accepted->qualified : fe::to_string(ref.name));
        t.accepts_array = t.accepts_array || ref.is_array;
      }
    }
    types.push_back(std::move(t));
  }
  std::sort(types.begin(), types.end(),
            [](const SignalType& a, const SignalType& b) { return a.name < b.name; });
  types.erase(std::unique(types.begin(), types.end(),
                          [](const SignalType& a, const SignalType& b) { return a.name == b.name; }),
              types.end());
  return types;
}

}  // namespace openplx::catalogue
