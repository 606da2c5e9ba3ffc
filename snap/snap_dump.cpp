#include "snap/snap_dump.h"

#include <ostream>

#include "frontend/evaluation/value_format.h"

namespace openplx::snap {
namespace {

using frontend::format_real;

void line(std::ostream& out, const std::string& path, Transform t) {
  if (t.rotation.w() < 0)
    t.rotation.coeffs() = -t.rotation.coeffs();  // q and -q are one rotation: print w >= 0
  out << path << " position {" << format_real(t.position.x()) << ", " << format_real(t.position.y()) << ", "
      << format_real(t.position.z()) << "} rotation {" << format_real(t.rotation.x()) << ", "
      << format_real(t.rotation.y()) << ", " << format_real(t.rotation.z()) << ", "
      << format_real(t.rotation.w()) << "}\n";
}

}  // namespace

void dump_snap(std::ostream& out, const ResolvedSystem& system, const SnapResult& result,
               const std::string& root_name) {
  for (const auto& [is_node, index] : system.order) {
    if (is_node) {
      const std::string& path = system.nodes[index].path;
      line(out, path.empty() ? root_name : path, result.node_world[index]);
    } else {
      line(out, system.connectors[index].path, result.connector_world[index]);
    }
  }
}

}  // namespace openplx::snap
