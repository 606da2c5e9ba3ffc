#include "frontend/semantics/entry_reach.h"

namespace openplx::frontend {

const EntryReach::Node* EntryReach::root(const ModelInfo* type) {
  auto [it, fresh] = trees_.try_emplace(type);
  std::deque<Node>& nodes = it->second;
  if (!fresh) return &nodes.front();
  nodes.emplace_back();
  auto add = [&nodes](const std::string& rel) {
    Node* node = &nodes.front();
    if (rel.empty()) return;  // the instance's own attributes: no path below it
    for (size_t start = 0; start <= rel.size();) {
      size_t end = rel.find('.', start);
      if (end == std::string::npos) end = rel.size();
      const std::string prefix = rel.substr(0, end);
      const std::string_view name = std::string_view(rel).substr(start, end - start);
      auto found = node->below.find(name);
      if (found == node->below.end()) {
        Node& child = nodes.emplace_back();
        child.rel = prefix;
        // The key views the child's own copy of the path, which lives as long as the tree.
        const std::string_view own = std::string_view(child.rel).substr(start);
        found = node->below.emplace(own, &child).first;
      }
      node = const_cast<Node*>(found->second);
      start = end + 1;
    }
    node->targeted = true;
  };
  for (const ModelInfo* model : type->linearization()) {
    for (const auto& [rel, unused] : model->by_parent) add(rel);
    for (const auto& [rel, unused] : model->children_below) add(rel);
    for (const auto& [rel, unused] : model->annotations_below) add(rel);
  }
  return &nodes.front();
}

}  // namespace openplx::frontend
