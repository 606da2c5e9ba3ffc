// The whole front end in one call: find bundles, load the file, check every declaration of the file, pick
// the root model, instantiate it and evaluate one instance of each layout (the rest is evaluated on demand
// when SNAP or the emitter read it; OPENPLX_EVALUATE_EVERYTHING=1 evaluates all up front). Used by the CLI,
// the tests, the fuzzers and the benchmarks, so they all see the same behaviour.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "frontend/evaluation/evaluator.h"
#include "frontend/semantics/program.h"

namespace openplx::frontend {

struct LoadRequest {
  std::string path;
  std::optional<std::string> model;      // root model; default: the last model of the file
  std::vector<std::string> bundle_dirs;  // -B folders
  std::optional<std::string> text;       // when set, the file's content (not read from disk)
  bool default_bundles = true;           // false (--no-default-bundles): only -B and OPENPLX_BUNDLE_PATH
};

struct Evaluation {
  std::unique_ptr<Program> program;
  std::unique_ptr<Evaluator> evaluator;
  DocumentInfo* document = nullptr;
  ObjectId root = kNoObject;  // kNoObject when loading or instantiation failed
};

// Errors go to `sink`; the result holds whatever could be built.
Evaluation evaluate_file(const LoadRequest& request, SourceManager& sources, DiagnosticSink& sink);

}  // namespace openplx::frontend
