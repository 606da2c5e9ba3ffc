// Builds the resolved system (resolved_system.h) from an evaluated ObjectGraph: the one place after the
// evaluator that reads OpenPLX attributes. Models are recognised by type (Physics3D.System,
// Physics3D.Bodies.Body, Physics3D.Interactions.MateConnector, ...Mate), so user models deriving from the
// bundle models are recognised. Problems (a normal parallel to its main axis, a mate without two connectors)
// are reported at the user's line.
#pragma once

#include "frontend/diagnostics/diagnostics.h"
#include "frontend/evaluation/evaluator.h"
#include "snap/resolved_system.h"

namespace openplx::snap {

// Where an instance was declared: its attribute's line in the owner, or its model's declaration for roots.
frontend::SourceRange source_of(const frontend::ObjectGraph& graph, frontend::ObjectId id);

// Builds the resolved system of the tree under `root`. Its attribute reads go through `evaluator`, which
// evaluates on demand what was not evaluated yet (the converter evaluates lazily), so this pass calls back
// into evaluation.
ResolvedSystem resolve_system(frontend::Evaluator& evaluator, frontend::ObjectId root,
                              frontend::DiagnosticSink& sink);

}  // namespace openplx::snap
