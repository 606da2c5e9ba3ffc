// `--dump=snap`: one line per system, body and mate connector of the root model, in declaration order:
// `path position {x, y, z} rotation {x, y, z, w}`, world frame, paths relative to the root (the root itself
// by its model name).
#pragma once

#include <iosfwd>
#include <string>

#include "snap/snap.h"

namespace openplx::snap {

void dump_snap(std::ostream& out, const ResolvedSystem& system, const SnapResult& result,
               const std::string& root_name);

}  // namespace openplx::snap
