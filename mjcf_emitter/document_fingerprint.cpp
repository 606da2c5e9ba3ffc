#include "mjcf_emitter/document_fingerprint.h"

#include <string>

namespace openplx::mjcf {
namespace {

void walk(const Element& body, std::string_view parent, std::string_view prefix, FingerprintLines& out) {
  std::string_view self = parent;  // a body without a name of the model's is not counted
  const std::string* name = body.get("name");
  std::string_view stripped;
  const bool ours = body.name() == "body" && name && strip_prefix(*name, prefix, stripped);
  if (ours) {
    self = stripped;
    out.body(stripped, parent);
  }
  for (const auto& child : body.children()) {
    const std::string& tag = child->name();
    if (tag == "body") {
      walk(*child, ours ? self : std::string_view("-"), prefix, out);
    } else if ((tag == "joint" || tag == "freejoint") && ours) {
      const std::string* joint = child->get("name");
      std::string_view joint_name;
      if (!joint || !strip_prefix(*joint, prefix, joint_name)) continue;
      const std::string* type = child->get("type");
      const std::string kind = tag == "freejoint" ? "free" : type ? *type : "hinge";
      out.joint(joint_name, kind, self);
    }
  }
}

}  // namespace

Fingerprint model_fingerprint(const Element& document, std::string_view prefix) {
  FingerprintLines out;
  for (const auto& section : document.children()) {
    if (section->name() != "worldbody") continue;
    for (const auto& child : section->children()) {
      if (child->name() == "body") walk(*child, "-", prefix, out);
    }
  }
  return out.finish();
}

}  // namespace openplx::mjcf
