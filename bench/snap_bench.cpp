// SNAP scaling: wide trees of 100 to 10,000 bodies and a chain 90 deep, all left for SNAP to place.
// BM_Snap times the assembly alone on a resolved system built directly; BM_EvaluateAndSnap* time the whole
// front end (parse, evaluate every attribute of the bundle models, build the system, SNAP) on the same
// shapes.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>

#include "bench/model_generator.h"
#include "frontend/pipeline.h"
#include "snap/resolve_system.h"
#include "snap/snap.h"

namespace fe = openplx::frontend;
namespace sn = openplx::snap;

namespace {

// The system generate_mechanism() would give: links with connectors at 0 and 1 m, hinged to a base
// connector (trunks, or the first chain link) or to the previous link's top.
sn::ResolvedSystem mechanism_view(size_t bodies, bool chain) {
  sn::ResolvedSystem system;
  sn::FrameNode root;
  root.kind = sn::FrameNode::Kind::System;
  root.object = 0;
  root.defined = true;
  system.nodes.push_back(root);
  system.root = 0;
  sn::Connector base;
  base.owner = 0;
  base.local = *openplx::natives::affine_from_axes(Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(),
                                                   Eigen::Vector3d::Zero());
  system.connectors.push_back(base);
  for (size_t i = 0; i < bodies; ++i) {
    sn::FrameNode link;
    link.kind = sn::FrameNode::Kind::Body;
    link.object = static_cast<fe::ObjectId>(i + 1);
    link.parent = 0;
    system.nodes.push_back(link);
    sn::Connector bottom = base, top = base;
    bottom.owner = top.owner = static_cast<int>(i + 1);
    top.local.position = {0, 0, 1};
    system.connectors.push_back(bottom);
    system.connectors.push_back(top);
    sn::Mate hinge;
    hinge.type = sn::MateType::Hinge;
    hinge.initial_angle = 0.01;
    const size_t trunk = i / 10 * 10;
    const int parent_top =
        chain ? (i == 0 ? 0 : static_cast<int>(2 * i)) : (i == trunk ? 0 : static_cast<int>(2 * trunk + 2));
    hinge.connectors[0] = parent_top;
    hinge.connectors[1] = static_cast<int>(2 * i + 1);
    system.mates.push_back(hinge);
  }
  return system;
}

// range(0): bodies; range(1): 1 for a chain, 0 for a wide tree.
void BM_Snap(benchmark::State& state) {
  const auto bodies = static_cast<size_t>(state.range(0));
  for (auto _ : state) {
    state.PauseTiming();
    sn::ResolvedSystem system = mechanism_view(bodies, state.range(1) != 0);
    fe::DiagnosticSink sink;
    state.ResumeTiming();
    sn::SnapResult result = sn::run_snap(system, sink);
    benchmark::DoNotOptimize(result.node_world.data());
  }
  state.counters["bodies"] = static_cast<double>(bodies);
}

void BM_EvaluateAndSnap(benchmark::State& state) {
  const auto bodies = static_cast<size_t>(state.range(0));
  const bool chain = state.range(1) != 0;
  const std::string path = (std::filesystem::temp_directory_path() / "openplx_snap_bench.openplx").string();
  std::ofstream(path) << openplx::bench::generate_mechanism(bodies, chain);
  for (auto _ : state) {
    fe::SourceManager sources;
    fe::DiagnosticSink sink;
    fe::Evaluation evaluation = fe::evaluate_file({path, std::nullopt, {}, std::nullopt}, sources, sink);
    sn::ResolvedSystem system = sn::resolve_system(*evaluation.evaluator, evaluation.root, sink);
    sn::SnapResult result = sn::run_snap(system, sink);
    if (sink.has_errors()) state.SkipWithError("generated model has errors");
    benchmark::DoNotOptimize(result.node_world.data());
  }
  state.counters["bodies"] = static_cast<double>(bodies);
}

}  // namespace

BENCHMARK(BM_Snap)
    ->Args({100, 0})
    ->Args({1000, 0})
    ->Args({10000, 0})
    ->Args({90, 1})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EvaluateAndSnap)
    ->Args({100, 0})
    ->Args({1000, 0})
    ->Args({90, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_MAIN();
