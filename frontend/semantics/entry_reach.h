// Where a type's entries reach below its instances: `a.b.c: 1` in a model reaches the instance at `a.b`.
// Kept as a tree of attribute names per type, so finding the ancestors whose entries aim at a new instance
// is a walk down its names (no path strings joined and hashed per ancestor for every instance).
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <string_view>
#include <unordered_map>

#include "frontend/semantics/program.h"

namespace openplx::frontend {

class EntryReach {
 public:
  struct Node {
    std::string rel;                   // the path from the type's instance, joined with '.'
    bool targeted = false;             // some entry aims at this path or its parts (not only deeper paths)
    mutable int8_t assigns_only = -1;  // Evaluator::assigns_only, once known (-1: not yet)
    std::unordered_map<std::string_view, const Node*> below;
  };

  // The root of `type`'s tree (the instance itself), built on first use.
  const Node* root(const ModelInfo* type);
  // One attribute further down; nullptr when no entry of the type goes there.
  static const Node* step(const Node* node, std::string_view name) {
    auto it = node->below.find(name);
    return it == node->below.end() ? nullptr : it->second;
  }

 private:
  std::unordered_map<const ModelInfo*, std::deque<Node>> trees_;
};

}  // namespace openplx::frontend
