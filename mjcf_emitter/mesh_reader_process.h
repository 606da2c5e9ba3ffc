// Meshes read in a child process. assimp parses untrusted files (a user's robot names them) and crashes,
// recurses without bound or loops on some; in a forked child with CPU, wall-clock and memory limits, such a
// file ends the child, and the converter, openplx-sim or the user's program that calls Simulation::load
// gets a problem to report at the line that names the file. The mesh comes back through a pipe, read while
// the child writes it, and is checked again here (sizes, every index), as it was made from hostile input.
//
// fork() without exec: the module is loaded before the fork, and the child only reads and writes its pipe
// before _exit, so no lock another thread held can matter but the allocator's, which glibc makes safe. A
// child that still blocks is killed at the deadline.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "mjcf_emitter/mesh_conversion.h"
#include "mjcf_emitter/mesh_module_abi.h"

namespace openplx::mjcf {

// What a child run gave: what it wrote, and why it failed ("" when it exited normally), worded as a
// problem with the file ("the mesh reader crashed on it (signal 11, SIGSEGV)", "... took longer than 60 s",
// "... needed more than 4096 MiB").
struct ChildRun {
  std::string output;
  std::string failure;
};

// Runs `work` in a forked child within `limits`; `work` writes its answer to the descriptor it is given.
// Memory is its address space; under AddressSanitizer, which reserves terabytes of it, its resident memory.
ChildRun run_in_child(const std::function<void(int fd)>& work, const MeshReaderLimits& limits);

// Reads the mesh at `path` with the module's `read` in a child: empty on success (`mesh` filled), else the
// module's problem or the child's failure.
std::string read_mesh_in_child(OpenplxReadMeshFunction read, const std::string& path, TriangleMesh& mesh,
                               const MeshReaderLimits& limits);

// The same in this process, unprotected: for the fuzz target, which reads again in process a file the child
// read without failing, so that libFuzzer sees the module's coverage and the sanitizers its faults.
std::string read_mesh_in_process(OpenplxReadMeshFunction read, const std::string& path, TriangleMesh& mesh);

}  // namespace openplx::mjcf
