#include "frontend/pipeline.h"

#include "frontend/bundles.h"
#include "frontend/large_stack.h"

namespace openplx::frontend {

Evaluation evaluate_file(const LoadRequest& request, SourceManager& sources, DiagnosticSink& sink) {
  Evaluation result;
  result.program = std::make_unique<Program>(sources, sink);
  result.program->set_bundles(discover_bundles(bundle_search_path(request.bundle_dirs), sources, sink));
  result.document = request.text ? result.program->load_text(request.path, *request.text)
                                 : result.program->load_main(request.path);
  if (!result.document) return result;
  const bool syntax_errors = sink.has_errors();
  ModelInfo* root_model =
      select_root_model(*result.program, result.document, request.model ? &*request.model : nullptr);
  if (syntax_errors) return result;  // evaluating would only repeat them
  // Every declaration of the user's file is checked, used or not; bundles only as far as they are used.
  for (const Decl& decl : result.document->doc.decls) {
    if (decl.kind != DeclKind::Model && decl.kind != DeclKind::Trait) continue;
    Symbol symbol = result.program->lookup_in(result.document->ns, decl.name.text);
    if (symbol.model && symbol.model->decl == &decl) result.program->resolve(symbol.model);
  }
  if (!root_model) return result;
  result.evaluator = std::make_unique<Evaluator>(*result.program, sink);
  run_with_large_stack([&] {
    result.root = result.evaluator->instantiate_root(root_model);
    if (result.root != kNoObject) result.evaluator->evaluate_all(result.root);
  });
  return result;
}

}  // namespace openplx::frontend
