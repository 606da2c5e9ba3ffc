// Lowering pass: room in MuJoCo 2.2.2's contact and constraint buffers. By default it keeps 100 contacts and
// 500 constraint rows; a hand of many small collision shapes can start with more contacts than that (116 on a
// Valkyrie-like hand, tests/urdf/robots/unstable), and MuJoCo then drops contacts and warns every step, which
// --check reports as unstable. The buffers are sized by the collision geometry, only past the defaults: rows
// grow with contacts (a pyramidal contact of condim 3 takes 4), and MuJoCo 2.2.2 holds some row buffers dense
// (rows squared), so they stay as small as the model allows.
#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {
namespace {

constexpr int kDefaultContacts = 100;    // MuJoCo 2.2.2's nconmax when none is given
constexpr int kDefaultRows = 500;        // its njmax
constexpr int kContactsPerGeometry = 4;  // a box on a box touches at up to 4 points of its face
constexpr int kRowsPerContact = 4;       // condim 3, pyramidal friction

}  // namespace

void Lowering::size_contact_buffers(Element& root, int extra_contacts, int extra_rows) {
  int colliding = 0;
  for (const sn::Geometry& g : system_.geometries) colliding += g.collides && !g.visual ? 1 : 0;
  const int geometry_contacts = std::max(0, kContactsPerGeometry * colliding - kDefaultContacts);
  extra_contacts += geometry_contacts;
  extra_rows += kRowsPerContact * geometry_contacts;
  if (extra_contacts == 0 && extra_rows == 0) {
    drop_empty(root, "size");
    return;
  }
  size_->set("njmax", kDefaultRows + extra_rows).set("nconmax", kDefaultContacts + extra_contacts);
}

}  // namespace openplx::mjcf
