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

// `dir` is where the URDF file goes: the regression test passes its own scratch folder.
inline void urdf_one(const uint8_t* data, size_t size,
                     const std::filesystem::path& dir = std::filesystem::temp_directory_path()) {
  namespace fe = openplx::frontend;
  // A URDF enters through a file (its folder resolves meshes): named by the process so parallel fuzzers do
  // not share it, and removed after each run so none is left behind.
  const std::string path = (dir / ("openplx_fuzz_" + std::to_string(getpid()) + ".urdf")).string();
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  fe::SourceManager sources;
  fe::DiagnosticSink sink;
  fe::Evaluation evaluation = fe::evaluate_file({path, std::nullopt, {}, std::nullopt}, sources, sink);
  std::ostringstream out;
  if (evaluation.root != fe::kNoObject) {
    openplx::snap::ResolvedSystem system =
        openplx::snap::resolve_system(*evaluation.evaluator, evaluation.root, sink);
    openplx::snap::run_snap(system, sink);
    openplx::mjcf::EmitOptions options;
    options.model_name = evaluation.evaluator->root_name();
    out << openplx::mjcf::emit_mjcf(system, options, sink).document.to_string();
  }
  fe::print_diagnostics(out, sources, sink.diagnostics());
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
}

}  // namespace openplx::fuzz
