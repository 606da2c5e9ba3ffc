// Lowering pass, tree choice: which mates become joints of MuJoCo's body tree and which close loops (writes
// no MJCF).
#include "mjcf_emitter/lowering.h"

#include <queue>
#include <tuple>

namespace openplx::mjcf {

int Lowering::edge_cost(const sn::Mate& mate, bool carries_interactions) {
  if (carries_interactions) return 0;
  switch (mate.type) {
    case sn::MateType::Hinge:
    case sn::MateType::Prismatic:
    case sn::MateType::Cylindrical:
    case sn::MateType::Planar:  // only a tree joint can express it
    case sn::MateType::Suspension:
    case sn::MateType::ElasticTire:
      return 1;
    case sn::MateType::Lock:
      return 2;
    case sn::MateType::Ball:
      return 3;
    default:
      return 4;
  }
}

bool Lowering::joint_mapped(const sn::Mate& mate) const {
  switch (mate.type) {
    case sn::MateType::Hinge:
    case sn::MateType::Prismatic:
    case sn::MateType::Cylindrical:
    case sn::MateType::Planar:
    case sn::MateType::Suspension:
    case sn::MateType::ElasticTire:
    case sn::MateType::Ball:
    case sn::MateType::Lock:
      return true;
    default:
      return false;
  }
}

// Prim's algorithm from the world (and static bodies) over the enabled mates, cheapest edge first; components
// the world does not reach get a free joint at their first declared body.
void Lowering::choose_tree() {
  edges_.assign(system_.nodes.size(), TreeEdge{});
  in_tree_.assign(system_.nodes.size(), false);
  std::vector<bool> has_interactions(system_.mates.size(), false);
  for (const sn::Interaction1D& i : system_.interactions) {
    if (i.mate >= 0) has_interactions[i.mate] = true;
  }
  for (const sn::Signal& signal : system_.signals) {  // a read mate needs a joint to read
    if (signal.input || !signal.enabled) continue;
    if (signal.source_kind == sn::SignalSource::Mate) has_interactions[signal.source] = true;
  }
  for (size_t m = 0; m < system_.mates.size(); ++m) {
    const sn::Mate& mate = system_.mates[m];
    if (mate.connectors[0] < 0 || mate.connectors[1] < 0) continue;
    if (mate.type == sn::MateType::Distance) continue;  // a tendon constraint (emit_distance_mates)
    if (!joint_mapped(mate)) {
      warn(mate.where, "`" + mate.path + "` is a " + sn::mate_type_name(mate.type) +
                           " mate, which has no MuJoCo 2.2.2 joint here; it was left out");
      continue;
    }
    const int a = vertex_of_connector(mate.connectors[0]);
    const int b = vertex_of_connector(mate.connectors[1]);
    if (a == b) {
      warn(mate.where, "`" + mate.path + "` joins two connectors of " +
                           (a >= 0 ? "the same body `" + system_.nodes[a].path + "`" : "the world") +
                           "; there is nothing for MuJoCo to constrain, so it was left out");
      continue;
    }
    adjacency_.push_back({static_cast<int>(m), a, b, edge_cost(mate, has_interactions[m])});
  }
  using Item =
      std::tuple<int, int, int>;  // cost, mate index (declaration order breaks ties), adjacency index
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  std::unordered_map<int, std::vector<int>> incident;  // vertex -> adjacency indices
  for (size_t k = 0; k < adjacency_.size(); ++k) {
    incident[adjacency_[k].a].push_back(static_cast<int>(k));
    incident[adjacency_[k].b].push_back(static_cast<int>(k));
  }
  // A disabled mate (`enabled: false`) never joins the tree: it becomes an inactive equality (equalities.cpp)
  // that its enable input can switch on, and its bodies move as if it were not there.
  auto reach = [&](int vertex) {
    for (int k : incident[vertex]) {
      if (system_.mates[adjacency_[k].mate].enabled) queue.emplace(adjacency_[k].cost, adjacency_[k].mate, k);
    }
  };
  auto grow = [&]() {
    while (!queue.empty()) {
      const auto [cost, mate, k] = queue.top();
      queue.pop();
      const auto& e = adjacency_[k];
      const bool a_in = e.a == kWorldVertex || in_tree_[e.a];
      const bool b_in = e.b == kWorldVertex || in_tree_[e.b];
      if (a_in && b_in) continue;
      const int child = a_in ? e.b : e.a;
      if (is_static(child)) continue;  // static bodies are roots of their own
      in_tree_[child] = true;
      edges_[child] = {e.mate, a_in ? e.a : e.b};
      tree_mates_.insert(e.mate);
      reach(child);
    }
  };
  reach(kWorldVertex);
  for (size_t n = 0; n < system_.nodes.size(); ++n) {
    if (is_static(static_cast<int>(n))) {
      in_tree_[n] = true;
      reach(static_cast<int>(n));
    }
  }
  grow();
  for (size_t n = 0; n < system_.nodes.size(); ++n) {
    if (!is_body(static_cast<int>(n)) || in_tree_[n]) continue;
    in_tree_[n] = true;  // a floating component: free joint at its first declared body
    free_roots_.insert(static_cast<int>(n));
    reach(static_cast<int>(n));
    grow();
  }
}

}  // namespace openplx::mjcf
