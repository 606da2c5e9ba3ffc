#include "mjcf_emitter/mujoco3_collision.h"

#include <algorithm>

namespace openplx::mjcf {

namespace {

// The <flag> element of <option> that holds nativeccd (the emitter writes no other flag).
bool is_collision_flag(const std::unique_ptr<Element>& e) {
  return e->name() == "flag" && e->get("nativeccd");
}

}  // namespace

void add_mujoco3_collision_settings(Element& mujoco) {
  Element* option = mujoco.child("option");
  if (!option) option = &mujoco.add("option");
  option->add("flag").set("nativeccd", "disable");
}

Mujoco3SettingsSetAside::Mujoco3SettingsSetAside(Element& mujoco) : option_(mujoco.child("option")) {
  if (!option_) return;
  auto& children = option_->children();
  const auto it = std::find_if(children.begin(), children.end(), is_collision_flag);
  if (it == children.end()) return;
  position_ = static_cast<size_t>(it - children.begin());
  flag_ = std::move(*it);
  children.erase(it);
}

Mujoco3SettingsSetAside::~Mujoco3SettingsSetAside() {
  if (!flag_) return;
  auto& children = option_->children();
  children.insert(children.begin() + static_cast<long>(position_), std::move(flag_));
}

}  // namespace openplx::mjcf
