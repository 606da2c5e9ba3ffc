// End to end: openplx2mjcf's whole pipeline (parse, evaluate, SNAP, emit MJCF) on generated wide trees of
// 100, 1,000 and 10,000 bodies, next to MuJoCo's mj_loadXML of the very file it wrote, in the same run.
// Target: ours <= 0.5x MuJoCo's compile at 1,000 bodies.
#include <benchmark/benchmark.h>
#include <malloc.h>
#include <mujoco/mujoco.h>

#include <filesystem>
#include <fstream>

#include "bench/model_generator.h"
#include "frontend/pipeline.h"
#include "mjcf_emitter/emitter.h"
#include "snap/resolve_system.h"
#include "snap/snap.h"

namespace fe = openplx::frontend;
namespace sn = openplx::snap;
namespace fs = std::filesystem;

namespace {

fs::path model_file(size_t bodies) {
  const fs::path path =
      fs::temp_directory_path() / ("openplx_mjcf_bench_" + std::to_string(bodies) + ".openplx");
  if (!fs::exists(path)) std::ofstream(path) << openplx::bench::generate_mechanism(bodies, false);
  return path;
}

fs::path xml_file(size_t bodies) {
  return fs::path(model_file(bodies)).replace_extension(".xml");
}

void BM_Openplx2Mjcf(benchmark::State& state) {
  const auto bodies = static_cast<size_t>(state.range(0));
  const fs::path input = model_file(bodies);
  for (auto _ : state) {
    fe::SourceManager sources;
    fe::DiagnosticSink sink;
    fe::Evaluation evaluation =
        fe::evaluate_file({input.string(), std::nullopt, {}, std::nullopt}, sources, sink);
    sn::ResolvedSystem system = sn::resolve_system(*evaluation.evaluator, evaluation.root, sink);
    sn::run_snap(system, sink);
    openplx::mjcf::EmitOptions options;
    options.model_name = "Scene";
    openplx::mjcf::Emitted emitted = openplx::mjcf::emit_mjcf(system, options, sink);
    std::ofstream(xml_file(bodies)) << emitted.document.to_string();
    if (sink.has_errors()) state.SkipWithError("generated model has errors");
  }
  state.counters["bodies"] = static_cast<double>(bodies);
}

void BM_MujocoLoadXml(benchmark::State& state) {
  const auto bodies = static_cast<size_t>(state.range(0));
  const std::string xml = xml_file(bodies).string();
  for (auto _ : state) {
    char error[1000] = "";
    mjModel* model = mj_loadXML(xml.c_str(), nullptr, error, sizeof(error));
    if (!model) {
      state.SkipWithError(error);
      break;
    }
    mj_deleteModel(model);
  }
  state.counters["bodies"] = static_cast<double>(bodies);
}

}  // namespace

// Each size: ours first (it writes the XML), then MuJoCo loading it.
BENCHMARK(BM_Openplx2Mjcf)->Arg(100)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_MujocoLoadXml)->Arg(100)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Openplx2Mjcf)->Arg(1000)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_MujocoLoadXml)->Arg(1000)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_Openplx2Mjcf)->Arg(10000)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_MujocoLoadXml)->Arg(10000)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
int main(int argc, char** argv) {
  // The same allocator settings as the openplx2mjcf executable (tools/cli/main.cpp).
  mallopt(M_ARENA_MAX, 1);
  mallopt(M_TOP_PAD, 16 << 20);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
