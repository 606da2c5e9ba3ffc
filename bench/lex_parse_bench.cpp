// Lexer and parser throughput on a generated 10 MB document (target: >= 100 MB/s in a Release build).
#include <benchmark/benchmark.h>

#include "bench/model_generator.h"
#include "frontend/syntax/lexer.h"
#include "frontend/syntax/parser.h"

namespace fe = openplx::frontend;

namespace {

const std::string& document() {
  static const std::string text = openplx::bench::generate_document(10 * 1024 * 1024);
  return text;
}

void BM_Lex(benchmark::State& state) {
  fe::SourceFile file("bench.openplx", document());
  for (auto _ : state) {
    fe::DiagnosticSink sink;
    auto tokens = fe::lex(file, 0, sink);
    benchmark::DoNotOptimize(tokens.data());
    if (sink.has_errors()) state.SkipWithError("generated document has errors");
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * document().size()));
}

void BM_LexAndParse(benchmark::State& state) {
  fe::SourceManager sources;
  fe::FileId id = sources.add("bench.openplx", document());
  for (auto _ : state) {
    fe::DiagnosticSink sink;
    fe::Document doc = fe::parse_file(sources, id, sink);
    benchmark::DoNotOptimize(doc.decls.data());
    if (sink.has_errors()) state.SkipWithError("generated document has errors");
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * document().size()));
}

}  // namespace

BENCHMARK(BM_Lex)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LexAndParse)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
