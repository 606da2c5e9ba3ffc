// Evaluation of a generated model of 10,000 Part instances (100 groups x 100 parts): loading, instantiating
// and evaluating every attribute, as `openplx2mjcf --dump=values` does. Reports time and peak memory.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <filesystem>
#include <fstream>

#include "bench/model_generator.h"
#include "frontend/bundles/bundles.h"
#include "frontend/evaluation/evaluator.h"
#include "frontend/pipeline.h"

namespace fe = openplx::frontend;

namespace {

void BM_EvaluateInstances(benchmark::State& state) {
  const size_t groups = static_cast<size_t>(state.range(0));
  const std::string path = (std::filesystem::temp_directory_path() / "openplx_eval_bench.openplx").string();
  std::ofstream(path) << openplx::bench::generate_instances(groups, 100);
  size_t objects = 0;
  for (auto _ : state) {
    fe::SourceManager sources;
    fe::DiagnosticSink sink;
    fe::Evaluation evaluation = fe::evaluate_file({path, std::nullopt, {}, std::nullopt}, sources, sink);
    if (sink.has_errors()) state.SkipWithError("generated model has errors");
    objects = evaluation.evaluator ? evaluation.evaluator->graph().objects.size() : 0;
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["instances"] = static_cast<double>(groups * 100);
  state.counters["objects"] = static_cast<double>(objects);
  state.counters["peak_rss_MB"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
}

}  // namespace

BENCHMARK(BM_EvaluateInstances)->Arg(10)->Arg(100)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
