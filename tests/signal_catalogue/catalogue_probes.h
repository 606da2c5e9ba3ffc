// The catalogue's probes, shared by the catalogue (signal_catalogue_test.cpp) and the schema check of its
// manifests (catalogue_manifests_schema_test.cpp): the bundles' signal types, which of them accept each
// source fixture, and the lines that attach one as `probe`.
#pragma once

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "frontend/pipeline.h"
#include "tests/signal_catalogue/signal_types.h"
#include "tests/signal_catalogue/source_fixtures.h"

namespace openplx::catalogue {

inline std::vector<SignalType> bundle_types() {
  fe::SourceManager sources;
  fe::DiagnosticSink sink;
  fe::Program program(sources, sink);
  program.set_bundles(fe::discover_bundles(fe::bundle_search_path({}), sources, sink));
  return bundle_signal_types(program);
}

// A fixture evaluated: the model of its source, and which of `types` accept it.
struct Evaluated {
  std::string source_type;  // "" when the source was not found
  std::vector<const SignalType*> accepting;
};

inline Evaluated evaluate(const std::filesystem::path& file, const SourceFixture& fixture,
                          const std::vector<SignalType>& types) {
  fe::SourceManager sources;
  fe::DiagnosticSink sink;
  fe::Evaluation e =
      fe::evaluate_file(fe::LoadRequest{file.string(), std::nullopt, {}, std::nullopt}, sources, sink);
  Evaluated out;
  if (e.root == fe::kNoObject) return out;
  fe::ObjectId at = e.root;
  std::istringstream parts(fixture.source);
  for (std::string part; at != fe::kNoObject && std::getline(parts, part, '.');) {
    const fe::Value* v = e.evaluator->value(at, part);
    at = v && v->kind == fe::Value::Kind::Object ? v->object : fe::kNoObject;
  }
  if (at == fe::kNoObject) return out;
  const fe::ModelInfo* model = e.evaluator->graph().at(at).type;
  // A model of the fixture's own file is named with the bundle model it extends.
  out.source_type = model->qualified.empty() ? model->name : model->qualified;
  if (!model->doc || !model->doc->bundle) {
    const fe::ModelInfo* base = model->base;
    while (base && !(base->doc && base->doc->bundle)) base = base->base;
    if (base) out.source_type += " is " + base->qualified;
  }
  for (const SignalType& t : types) {
    for (const std::string& accepted : t.accepts) {
      const fe::ModelInfo* wanted = e.program->builtin_model(accepted);
      if (wanted && model->is_subtype_of(wanted)) {
        out.accepting.push_back(&t);
        break;
      }
    }
  }
  return out;
}

inline std::string probe_lines(const SignalType& t, const SourceFixture& fixture) {
  const std::string& source = fixture.source;
  std::string extra = extra_lines(t.name) + fixture.probe_lines;
  for (size_t at; (at = extra.find("{source}")) != std::string::npos;) extra.replace(at, 8, source);
  return "    probe is " + t.name + ":\n        " + t.source_attribute + ": " +
         (t.accepts_array ? "[" + source + "]" : source) + "\n" + extra;
}

}  // namespace openplx::catalogue
