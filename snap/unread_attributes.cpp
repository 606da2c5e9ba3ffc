#include "snap/unread_attributes.h"

#include <set>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "snap/read_parameters.h"

namespace openplx::snap {

namespace fe = openplx::frontend;

namespace {

bool in_bundle(const fe::ModelInfo* model) {
  return model && model->doc && model->doc->bundle;
}

// Math values (vectors, quaternions, transforms) are read whole where they matter; an unread one is warned
// once at the attribute holding it, not per component.
bool is_math(const fe::Object& obj) {
  return obj.type && obj.type->qualified.rfind("Math.", 0) == 0;
}

// A bundle's attribute, assigned in the user's own text (the resolver should have looked at it).
bool user_assignment_to_bundle(const fe::Slot& slot) {
  const fe::Entry* entry = slot.binding.entry;
  return entry && !entry->from_declaration && entry->kind == fe::Entry::Kind::Value &&
         in_bundle(slot.declared_in()) && !in_bundle(slot.binding.model);
}

// 1: below `root` and mapped, 0: elsewhere or inside a part already warned as having no counterpart.
std::vector<signed char> reachable(const fe::ObjectGraph& graph, fe::ObjectId root,
                                   const std::set<fe::ObjectId>& left_out) {
  const size_t count = graph.objects.size();
  std::vector<signed char> state(count, -1);
  state[root] = 1;
  std::vector<size_t> chain;  // the undecided owners of one object, reused
  for (size_t id = 0; id < count; ++id) {
    chain.clear();
    size_t at = id;
    while (state[at] < 0) {
      chain.push_back(at);
      const fe::Object& obj = graph.at(static_cast<fe::ObjectId>(at));
      if (obj.owner == fe::kNoObject || left_out.count(static_cast<fe::ObjectId>(at))) {
        state[at] = 0;
        break;
      }
      at = obj.owner;
    }
    for (size_t c : chain) state[c] = state[at] == 1 && !left_out.count(static_cast<fe::ObjectId>(c)) ? 1 : 0;
  }
  return state;
}

}  // namespace

void warn_unread_attributes(const fe::Evaluator& evaluator, fe::ObjectId root, const ResolvedSystem& system,
                            fe::DiagnosticSink& sink) {
  const fe::ObjectGraph& graph = evaluator.graph();
  if (root == fe::kNoObject || system.nodes.empty()) return;  // not a physical system: nothing maps it
  std::set<fe::ObjectId> left_out;  // warned whole ("it and its parts were left out")
  for (const Unsupported& u : system.unsupported) left_out.insert(u.object);
  const std::vector<signed char> mapped = reachable(graph, root, left_out);
  // One pass over every slot (a large model has hundreds of thousands): the assignments read anywhere, and
  // the slots that may be warned about, in order. An assignment is honoured when it was read in any instance
  // it binds: instances that share their entries are evaluated only as far as something reads them
  // (Evaluator::evaluate_layouts).
  // Only slots bound by the user's own entries matter, and instances of one layout have them at the same
  // places: found once per layout.
  std::unordered_set<const fe::Entry*> read;
  std::vector<std::pair<fe::ObjectId, uint32_t>> candidates;
  std::unordered_map<uint32_t, std::vector<uint32_t>> user_bound;  // by layout (0: none, found per object)
  std::vector<uint32_t> own;
  for (fe::ObjectId id = 0; id < graph.objects.size(); ++id) {
    const fe::Object& obj = graph.at(id);
    const std::vector<uint32_t>* slots = &own;
    auto find = [&](std::vector<uint32_t>& out) {
      out.clear();
      for (uint32_t k = 0; k < obj.slots.size(); ++k) {
        const fe::Slot& slot = obj.slots[k];
        if (slot.binding.entry && !in_bundle(slot.binding.model)) out.push_back(k);
      }
    };
    if (obj.layout == 0) {
      find(own);
    } else {
      auto [it, fresh] = user_bound.try_emplace(obj.layout);
      if (fresh) find(it->second);
      slots = &it->second;
    }
    const bool checked = mapped[id] == 1 && !is_math(obj);
    for (uint32_t k : *slots) {
      const fe::Slot& slot = obj.slots[k];
      if (slot.used) read.insert(slot.binding.entry);
      if (checked && user_assignment_to_bundle(slot)) candidates.emplace_back(id, k);
    }
  }
  std::set<const fe::Entry*> warned;  // one warning per assignment, however many instances share it
  for (const auto& [id, k] : candidates) {
    const fe::Slot& slot = graph.at(id).slots[k];
    const fe::Entry* entry = slot.binding.entry;
    if (read.count(entry) || !warned.insert(entry).second) continue;
    // Named by the declaration holding the assignment, which every instance it binds shares.
    const std::string name =
        written_name(graph, slot)
            .value_or(graph.path(id) + (id == root ? "" : ".") + std::string(slot.name()));
    sink.report(fe::DiagCode::MjcfUnmapped, entry->member->range,
                "`" + name + "` (" + slot.declared_in()->qualified +
                    ") has no MuJoCo counterpart here; it was ignored");
  }
}

}  // namespace openplx::snap
