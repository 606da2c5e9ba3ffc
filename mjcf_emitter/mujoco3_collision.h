// Collision settings that make MuJoCo 3.x find the contacts 2.2.2 finds, written under `--mujoco 3`.
// Since 3.3.0 MuJoCo collides convex pairs without a dedicated function (cylinder-box, mesh-primitive,
// mesh-mesh, ...) with its own GJK/EPA instead of libccd's MPR. On a line contact (a wheel on a box ground)
// EPA picks a point on the cylinder's rim edge where MPR picks the middle, and the motion follows: a car
// driven in a circle ends 1.3 m from 2.2.2's path after 3 s. `<flag nativeccd="disable"/>` puts MPR back.
// Only 3.x reads it (2.2.2 rejects the attribute), so a file written with it is a 3.x file.
#pragma once

#include <memory>

#include "mjcf_emitter/xml.h"

namespace openplx::mjcf {

// Adds `<flag nativeccd="disable"/>` to the document's <option>.
void add_mujoco3_collision_settings(Element& mujoco);

// Takes what add_mujoco3_collision_settings added out of `mujoco` while it lives and puts it back after, so
// that MuJoCo 2.2.2 (--check) can load the document: without it 2.2.2 collides as the settings make 3.x do.
class Mujoco3SettingsSetAside {
 public:
  explicit Mujoco3SettingsSetAside(Element& mujoco);
  ~Mujoco3SettingsSetAside();
  Mujoco3SettingsSetAside(const Mujoco3SettingsSetAside&) = delete;
  Mujoco3SettingsSetAside& operator=(const Mujoco3SettingsSetAside&) = delete;

  bool any() const { return flag_ != nullptr; }  // whether the document had them

 private:
  Element* option_ = nullptr;
  std::unique_ptr<Element> flag_;
  size_t position_ = 0;
};

}  // namespace openplx::mjcf
