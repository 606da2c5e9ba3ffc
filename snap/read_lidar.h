// Sensors lidars (Sensors.LidarLogic): the ray pattern of their ray source, their distortions, and the
// configurations AGX rejects.
#pragma once

#include "frontend/diagnostics/diagnostics.h"
#include "snap/attribute_reader.h"
#include "snap/resolved_system.h"

namespace openplx::snap {

// Reads lidar `id` (connector left at -1: resolved later from `attachment`). Invalid configurations are
// errors at the user's line; distortions MuJoCo does not apply are warnings.
Lidar read_lidar(AttributeReader& in, frontend::ObjectId id, frontend::SourceRange where,
                 frontend::DiagnosticSink& sink);

}  // namespace openplx::snap
