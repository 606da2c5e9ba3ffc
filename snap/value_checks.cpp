// Values nothing can simulate, refused where the user wrote them (AttributeReader::require): the MJCF must
// never carry a number MuJoCo cannot use, and a value quietly replaced (a negative mass taken from the
// geometry) would be silently wrong.
#include <cmath>

#include "frontend/value_format.h"
#include "snap/attribute_reader.h"
#include "snap/resolve_system.h"

namespace openplx::snap {

namespace fe = openplx::frontend;

namespace {

bool in_bundle(const fe::ModelInfo* m) {
  return m && m->doc && m->doc->bundle;
}

}  // namespace

fe::SourceRange AttributeReader::written_at(fe::ObjectId object, std::string_view name) const {
  const fe::ObjectGraph& g = graph();
  fe::ObjectId at = object;
  std::string_view attribute = name;
  // Up through the owners: `position: {0, Math.INF, 0}` binds the vector, not its `y`.
  for (int depth = 0; at != fe::kNoObject && depth < 8; ++depth) {
    const fe::Slot* slot = g.at(at).find(attribute);
    if (slot && slot->binding.entry && slot->binding.entry->member && !in_bundle(slot->binding.model))
      return slot->binding.entry->member->range;
    const fe::Object& o = g.at(at);
    if (o.owner == fe::kNoObject) break;
    attribute = o.name;
    at = o.owner;
  }
  return source_of(g, object);
}

bool AttributeReader::require(bool valid, fe::ObjectId object, std::string_view name, double value,
                              std::string_view rule) {
  if (valid || !sink_) return valid;
  sink_->report(fe::DiagCode::InvalidValue, written_at(object, name),
                "`" + graph().path(object) + "." + std::string(name) + "` is " + fe::format_real(value) +
                    "; " + std::string(rule));
  return false;
}

bool AttributeReader::require_finite_components(fe::ObjectId vector, std::string_view rule) {
  bool valid = true;
  for (const char* component : {"x", "y", "z", "w"}) {
    const std::optional<double> v = number(vector, std::string_view(component));
    if (v) valid = require(std::isfinite(*v), vector, component, *v, rule) && valid;
  }
  return valid;
}

}  // namespace openplx::snap
