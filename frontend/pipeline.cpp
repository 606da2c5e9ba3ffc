#include "frontend/pipeline.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <unordered_set>

#include "frontend/bundles/bundles.h"
#include "frontend/bundles/import_plugins.h"
#include "frontend/evaluation/large_stack.h"

namespace openplx::frontend {

namespace fs = std::filesystem;

Evaluation evaluate_file(const LoadRequest& request, SourceManager& sources, DiagnosticSink& sink) {
  Evaluation result;
  result.program = std::make_unique<Program>(sources, sink);
  result.program->set_bundles(
      discover_bundles(bundle_search_path(request.bundle_dirs, request.default_bundles), sources, sink));
  // A URDF given directly is read as a one-line document importing it, rooted at a model of the robot's name
  // (the file's stem), so the command line and the runtime take robots like any OpenPLX file.
  const fs::path file(request.path);
  if (!request.text && is_urdf_extension(lowercase_extension(request.path))) {
    const std::string robot = file.stem().string();
    const std::string text = "import @\"" + fs::absolute(file).lexically_normal().generic_string() + "\"\n`" +
                             robot + "_robot` is `" + robot + "`\n";
    result.program->set_urdf_given_directly();
    result.document = result.program->load_text(request.path + ".openplx", text);
  } else {
    result.document = request.text ? result.program->load_text(request.path, *request.text)
                                   : result.program->load_main(request.path);
  }
  if (!result.document) return result;
  const bool syntax_errors = sink.has_errors();
  ModelInfo* root_model =
      select_root_model(*result.program, result.document, request.model ? &*request.model : nullptr);
  if (syntax_errors) return result;  // evaluating would only repeat them
  // Every declaration of the user's file is checked, used or not; bundles only as far as they are used.
  // On the large stack: resolving a cycle of models recurses once per model in it.
  run_with_large_stack([&] {
    for (const Decl& decl : result.document->doc.decls) {
      if (decl.kind != DeclKind::Model && decl.kind != DeclKind::Trait) continue;
      Symbol symbol = result.program->lookup_in(result.document->ns, decl.name.text);
      if (symbol.model && symbol.model->decl == &decl) result.program->resolve(symbol.model);
    }
  });
  if (!root_model) return result;
  result.evaluator = std::make_unique<Evaluator>(*result.program, sink);
  run_with_large_stack([&] {
    result.root = result.evaluator->instantiate_root(root_model);
    if (result.root == kNoObject) return;
    // OPENPLX_EVALUATE_EVERYTHING=1 evaluates every attribute up front, as before layouts were shared:
    // the output must not change (tests/frontend/lazy_evaluation_test.cpp holds the two to that).
    if (std::getenv("OPENPLX_EVALUATE_EVERYTHING")) {
      result.evaluator->evaluate_all(result.root);
    } else {
      result.evaluator->evaluate_layouts(result.root);
    }
  });
  if (result.root != kNoObject) {
    // The models the root holds: every instance's type and what it extends (found once, if asked at all).
    std::unordered_set<const ModelInfo*> held;
    bool found = false;
    result.program->report_agx_annotations([&](const ModelInfo* m) {
      if (!found) {
        std::unordered_set<const ModelInfo*> types;
        const ObjectGraph& graph = result.evaluator->graph();
        for (size_t k = 0; k < graph.objects.size(); ++k) types.insert(graph.objects[k].type);
        for (const ModelInfo* type : types)
          if (type) held.insert(type->linearization().begin(), type->linearization().end());
        found = true;
      }
      return held.count(m) > 0;
    });
  }
  return result;
}

}  // namespace openplx::frontend
