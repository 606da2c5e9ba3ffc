// The body of the URDF fuzz target: the bytes as a URDF file, read the way `openplx2mjcf robot.urdf` reads it
// (tinyxml2, urdfdom, the generated OpenPLX, evaluation, SNAP, the MJCF emitter), diagnostics printed.
// Shared by the libFuzzer entry point and the regression test.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "frontend/pipeline.h"
#include "mjcf_emitter/emitter.h"
#include "snap/resolve_system.h"
#include "snap/snap.h"

namespace openplx::fuzz {

inline void urdf_one(const uint8_t* data, size_t size) {
  namespace fe = openplx::frontend;
  // A URDF enters through a file (its folder resolves meshes): one per process, rewritten each run.
  static const std::string path =
      (std::filesystem::temp_directory_path() / ("openplx_fuzz_" + std::to_string(getpid()) + ".urdf"))
          .string();
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  fe::SourceManager sources;
  fe::DiagnosticSink sink;
  fe::Evaluation evaluation = fe::evaluate_file({path, std::nullopt, {}, std::nullopt}, sources, sink);
  std::ostringstream out;
  if (evaluation.root != fe::kNoObject) {
    openplx::snap::ResolvedSystem view =
        openplx::snap::resolve_system(*evaluation.evaluator, evaluation.root, sink);
    openplx::snap::run_snap(view, sink);
    openplx::mjcf::EmitOptions options;
    options.model_name = evaluation.evaluator->root_name();
    out << openplx::mjcf::emit_mjcf(view, options, sink).document.to_string();
  }
  fe::print_diagnostics(out, sources, sink.diagnostics());
}

}  // namespace openplx::fuzz
