// Attributes a user sets that nothing in the pipeline honours: every bundle attribute assigned in a user's
// file that the resolver never read (Evaluator::track_reads) is a warning at the assignment, naming it.
#pragma once

#include "frontend/diagnostics/diagnostics.h"
#include "frontend/evaluation/evaluator.h"
#include "snap/resolved_system.h"

namespace openplx::snap {

void warn_unread_attributes(const frontend::Evaluator& evaluator, frontend::ObjectId root,
                            const ResolvedSystem& system, frontend::DiagnosticSink& sink);

}  // namespace openplx::snap
