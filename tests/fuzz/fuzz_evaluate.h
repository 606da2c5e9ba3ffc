// The body of the evaluator fuzz target: parse, pick the root model, instantiate and check it, assemble it,
// print every value, then emit MJCF. Shared by the libFuzzer entry point and the regression test.
#pragma once

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "frontend/bundles/bundles.h"
#include "frontend/evaluation/evaluator.h"
#include "frontend/evaluation/value_format.h"
#include "frontend/pipeline.h"
#include "mjcf_emitter/emitter.h"
#include "snap/resolve_system.h"
#include "snap/snap.h"

namespace openplx::fuzz {

inline void evaluate_one(const uint8_t* data, size_t size) {
  namespace fe = openplx::frontend;
  fe::SourceManager sources;
  fe::DiagnosticSink sink;
  fe::LoadRequest request{
      "/fuzz/input.openplx", std::nullopt, {}, std::string(reinterpret_cast<const char*>(data), size)};
  fe::Evaluation evaluation = fe::evaluate_file(request, sources, sink);
  if (evaluation.root == fe::kNoObject) return;
  std::ostringstream out;
  // The passes after evaluation: the resolved system (which evaluates what the evaluator left for when it is
  // read), SNAP and the MJCF emitter; then every value, read or not.
  openplx::snap::ResolvedSystem system =
      openplx::snap::resolve_system(*evaluation.evaluator, evaluation.root, sink);
  openplx::snap::run_snap(system, sink);
  fe::dump_values(out, *evaluation.evaluator, evaluation.root);
  openplx::mjcf::EmitOptions options;
  options.model_name = evaluation.evaluator->root_name();
  out << openplx::mjcf::emit_mjcf(system, options, sink).document.to_string();
  fe::print_diagnostics(out, sources, sink.diagnostics());
}

}  // namespace openplx::fuzz
