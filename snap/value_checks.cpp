// Values nothing can simulate, refused where the user wrote them (AttributeReader::require): the MJCF must
// never carry a number MuJoCo cannot use, and a value quietly replaced (a negative mass taken from the
// geometry) would be silently wrong.
#include <cmath>

#include "frontend/evaluation/value_format.h"
#include "snap/attribute_reader.h"
#include "snap/read_parameters.h"
#include "snap/resolve_system.h"

namespace openplx::snap {

namespace fe = openplx::frontend;

fe::SourceRange AttributeReader::written_at(fe::ObjectId object, std::string_view name) const {
  return written_value(*this, object, name).where;
}

// Named as written: a value in a declaration that several instances share is one error for all of them.
bool AttributeReader::require(bool valid, fe::ObjectId object, std::string_view name, double value,
                              std::string_view rule) {
  if (valid || !sink_) return valid;
  const WrittenValue written = written_value(*this, object, name);
  sink_->report(fe::DiagCode::InvalidValue, written.where,
                "`" + written.name + "` is " + fe::format_real(value) + "; " + std::string(rule));
  return false;
}

void AttributeReader::refuse(fe::ObjectId object, std::string_view name, std::string_view what) {
  if (!sink_) return;
  const WrittenValue written = written_value(*this, object, name);
  sink_->report(fe::DiagCode::InvalidValue, written.where, "`" + written.name + "` " + std::string(what));
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
