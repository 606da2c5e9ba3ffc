// Lowering pass, contacts: <pair>s from SurfaceContact models, <exclude>s from collision filters and, with
// --exclude-initial-overlaps, for bodies whose collision geometry overlaps at the initial state.
#include "mjcf_emitter/check.h"
#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {

namespace {

// The MuJoCo bodies (node indices) of each wheel and the chassis it hangs on: the two bodies of a
// suspension mate, and the chassis with an elastic wheel's tire (its tire mate's other body, below the rim).
// AGX's wheel joint keeps them out of contact with each other; so must MuJoCo.
std::set<std::pair<int, int>> wheel_chassis_bodies(const sn::ResolvedSystem& system) {
  std::set<std::pair<int, int>> pairs;
  auto body_of = [&](int connector) {
    const int owner = connector < 0 ? sn::kWorld : system.connectors[connector].owner;
    return owner >= 0 && system.nodes[owner].kind == sn::FrameNode::Kind::Body ? owner : sn::kWorld;
  };
  for (const sn::Mate& suspension : system.mates) {
    if (suspension.type != sn::MateType::Suspension) continue;
    const int chassis = body_of(suspension.connectors[0]), wheel = body_of(suspension.connectors[1]);
    if (chassis < 0 || wheel < 0 || chassis == wheel) continue;  // on the world: the ground's contacts stay
    pairs.insert(std::minmax(chassis, wheel));
    for (const sn::Mate& tire : system.mates) {
      if (tire.type != sn::MateType::ElasticTire) continue;
      const int a = body_of(tire.connectors[0]), b = body_of(tire.connectors[1]);
      const int other = a == wheel ? b : b == wheel ? a : sn::kWorld;
      if (other >= 0 && other != chassis) pairs.insert(std::minmax(chassis, other));
    }
  }
  return pairs;
}

// Whether MuJoCo leaves out the contacts of two bodies by itself: bodies of one weld group never touch,
// and a weld group does not touch its parent's, unless either is welded to the world (a static chassis
// is: its wheels would touch it). A body's weld group is its nearest ancestor-or-self with a joint.
bool mujoco_filters(int a, int b, const std::vector<TreeEdge>& edges, const std::map<int, Element*>& bodies) {
  auto weld = [&](int n) {
    for (; n != kWorldVertex; n = edges[n].parent) {
      auto it = bodies.find(n);
      if (it == bodies.end()) return kWorldVertex;
      for (const std::unique_ptr<Element>& e : it->second->children())
        if (e->name() == "joint" || e->name() == "freejoint") return n;
    }
    return kWorldVertex;
  };
  const int wa = weld(a), wb = weld(b);
  if (wa == wb) return true;
  if (wa == kWorldVertex || wb == kWorldVertex) return false;
  return wa == weld(edges[wb].parent) || wb == weld(edges[wa].parent);
}

}  // namespace

// One <pair> per pair of colliding geometries whose materials a SurfaceContact model names.
void Lowering::emit_contact_pairs(Element& root) {
  Element* contact = root.child("contact");
  const std::set<std::pair<int, int>> wheels =
      system_.contact_models.empty() ? std::set<std::pair<int, int>>{} : wheel_chassis_bodies(system_);
  for (const sn::ContactModel& cm : system_.contact_models) {
    if (!cm.enabled) continue;
    const double mu = cm.friction;
    for (const sn::WrittenValue* restitution : {&cm.normal_restitution_at, &cm.tangential_restitution_at}) {
      if (!restitution->name.empty())  // only a restitution that is not 0 has a place
        warn(restitution->where,
             "`" + restitution->name +
                 "` has no MuJoCo 2.2.2 parameter; its contacts are emitted without restitution");
    }
    size_t pairs = 0;
    for (const sn::Geometry& a : system_.geometries) {
      for (const sn::Geometry& b : system_.geometries) {
        if (&a >= &b || a.visual || b.visual || !a.collides || !b.collides || a.owner == b.owner) continue;
        const bool match = (a.material == cm.material1 && b.material == cm.material2) ||
                           (a.material == cm.material2 && b.material == cm.material1);
        if (!match || !emitted_geoms_.count(a.path) || !emitted_geoms_.count(b.path)) continue;
        if (wheels.count(std::minmax(a.owner, b.owner))) continue;  // a <pair> would bypass the exclusion
        contact->add("pair")
            .set("name", name(cm.path) + "/" + std::to_string(pairs++))
            .set("geom1", name(a.path))
            .set("geom2", name(b.path))
            .set("condim", 3)
            .set("friction", number(mu) + " " + number(mu) + " 0.005 0.0001 0.0001");
      }
    }
  }
}

// Contacts filtered out: each wheel from its chassis, where MuJoCo does not already keep them apart (a
// static chassis, an elastic wheel's tire two bodies below it, a suspension closing a loop), and
// Simulation.DisableCollisionPair. MuJoCo excludes contacts per pair of bodies, so each group becomes the
// bodies that hold its systems', bodies' and geometries' shapes; a group naming only some of a body's
// colliding geometries is widened to the whole body, with a warning.
void Lowering::emit_collision_filters(Element& root) {
  Element* contact = root.child("contact");
  std::set<std::pair<std::string, std::string>> excluded;
  for (const std::unique_ptr<Element>& e : contact->children()) {
    if (e->name() == "exclude") excluded.insert({*e->get("body1"), *e->get("body2")});
  }
  for (const auto& [a, b] : wheel_chassis_bodies(system_)) {
    if (!body_element_.count(a) || !body_element_.count(b) || mujoco_filters(a, b, edges_, body_element_))
      continue;
    const std::string body_a = mujoco_body(a), body_b = mujoco_body(b);
    const auto pair = std::minmax(body_a, body_b);
    if (excluded.insert({pair.first, pair.second}).second)
      contact->add("exclude").set("body1", pair.first).set("body2", pair.second);
  }
  for (const sn::CollisionFilter& f : system_.collision_filters) {
    std::vector<std::string> widened;
    const std::set<std::string> first = group_bodies(f.group1, widened);
    const std::set<std::string> second = group_bodies(f.group2, widened);
    for (const std::string& body : widened) {
      warn(f.where, "`" + f.path + "`: MuJoCo excludes contacts between whole bodies, so all of `" + body +
                        "`'s geometries were excluded, not only those its group names");
    }
    for (const std::string& a : first) {
      for (const std::string& b : second) {
        if (a == b) continue;  // a body's own geometries never collide in MuJoCo
        const auto pair = std::minmax(a, b);
        if (excluded.insert({pair.first, pair.second}).second)
          contact->add("exclude").set("body1", pair.first).set("body2", pair.second);
      }
    }
  }
}

// --exclude-initial-overlaps: MuJoCo finds the contacts of the initial state in a draft of the finished
// document; every pair of bodies overlapping there gets an <exclude> (sorted by name: the output stays
// deterministic) and loses the <pair>s between them, which an exclude does not reach, with a note each.
// Overlaps with the world's own geometry (ground planes, terrains, a system's shapes) are left: excluding a
// body from it would let the body fall through the ground.
void Lowering::exclude_initial_overlaps(Element& root) {
  if (!options_.exclude_initial_overlaps || sink_.has_errors()) return;
  const fe::SourceRange at_root = system_.root >= 0 ? system_.nodes[system_.root].where : fe::SourceRange{};
  const DraftModel draft(root, options_.output_dir);
  std::string error = draft.error();
  const MuJoCoLibrary* mj = draft.model() ? mujoco_library(error) : nullptr;
  std::vector<InitialOverlap> overlaps;
  if (mj) {
    const mjModel* m = draft.model();
    MuJoCoMessages messages(*mj);
    mjData* d = nullptr;
    const std::string key = name("initial");
    if (messages.call(
            nullptr, [&] { d = mj->makeData(m); }, error) &&
        d &&
        messages.call(
            d, [&] { reset_to_initial_state(*mj, m, d, key); }, error)) {
      overlaps = overlapping_bodies(*mj, m, d);
    } else {
      mj = nullptr;
    }
    if (d) mj->deleteData(d);
  }
  if (!mj) {
    warn(at_root, "--exclude-initial-overlaps: MuJoCo could not load the model (" + error +
                      "), so no overlapping bodies were excluded");
    return;
  }
  auto unprefixed = [&](const std::string& body) { return body.substr(options_.prefix.size()); };
  auto declaration = [&](const std::string& body) {
    for (const sn::FrameNode& n : system_.nodes)
      if (n.kind == sn::FrameNode::Kind::Body && name(n.path) == body) return n.where;
    return at_root;
  };
  Element* contact = root.child("contact");
  std::set<std::pair<std::string, std::string>> excluded;
  for (const InitialOverlap& o : overlaps) {
    if (o.body1 == "world" || o.body2 == "world") continue;
    if (!contact) contact = &root.add("contact");
    contact->add("exclude").set("body1", o.body1).set("body2", o.body2);
    excluded.insert({o.body1, o.body2});
    sink_.report(fe::DiagCode::MjcfOverlapExcluded, declaration(o.body1),
                 "contacts between `" + unprefixed(o.body1) + "` and `" + unprefixed(o.body2) +
                     "` are excluded (--exclude-initial-overlaps): their collision geometry overlaps by " +
                     length_text(o.depth) + " at the start");
  }
  if (excluded.empty() || !contact) return;
  // <pair>s between excluded bodies go too: MuJoCo applies <exclude> to its own contact detection only.
  std::map<std::string, std::string> geom_body;
  std::vector<const Element*> stack{world_};
  while (!stack.empty()) {
    const Element* body = stack.back();
    stack.pop_back();
    const std::string* body_name = body->get("name");
    for (const std::unique_ptr<Element>& e : body->children()) {
      if (e->name() == "body") stack.push_back(e.get());
      const std::string* geom_name = e->get("name");
      if (e->name() == "geom" && geom_name) geom_body[*geom_name] = body_name ? *body_name : "world";
    }
  }
  auto& kids = contact->children();
  kids.erase(std::remove_if(kids.begin(), kids.end(),
                            [&](const std::unique_ptr<Element>& e) {
                              if (e->name() != "pair") return false;
                              const auto b1 = geom_body.find(*e->get("geom1"));
                              const auto b2 = geom_body.find(*e->get("geom2"));
                              if (b1 == geom_body.end() || b2 == geom_body.end()) return false;
                              return excluded.count(std::minmax(b1->second, b2->second)) > 0;
                            }),
             kids.end());
}

// The MuJoCo bodies holding the shapes of a Simulation.CollisionGroup.
std::set<std::string> Lowering::group_bodies(const sn::CollisionGroup& group,
                                             std::vector<std::string>& widened) {
  std::set<std::string> bodies;
  auto within = [&](int n, int ancestor) {
    for (; n >= 0; n = system_.nodes[n].parent) {
      if (n == ancestor) return true;
    }
    return false;
  };
  for (int body : group.bodies) bodies.insert(mujoco_body(body));
  for (int system : group.systems) {
    for (const sn::Geometry& g : system_.geometries) {
      if (g.collides && within(g.owner, system)) bodies.insert(mujoco_body(g.owner));
    }
  }
  const std::set<int> geometries(group.geometries.begin(), group.geometries.end());
  std::set<int> owners;
  for (int g : geometries) owners.insert(system_.geometries[g].owner);
  for (int owner : owners) {
    const std::string body = mujoco_body(owner);
    bodies.insert(body);
    for (size_t k = 0; k < system_.geometries.size(); ++k) {
      const sn::Geometry& g = system_.geometries[k];
      if (g.owner == owner && g.collides && !geometries.count(static_cast<int>(k))) {
        if (std::find(widened.begin(), widened.end(), body) == widened.end()) widened.push_back(body);
        break;
      }
    }
  }
  return bodies;
}

// The MuJoCo body a node's shapes end up in: its own, or the world for a system's (emit_world_geoms).
std::string Lowering::mujoco_body(int n) {
  return n >= 0 && is_body(n) ? name(system_.nodes[n].path) : "world";
}

}  // namespace openplx::mjcf
