// libFuzzer target for mesh files (COLLADA, PLY, glTF, .glb, OBJ, STL) as the converter reads them: build
// and run with tools/fuzz.sh 300 mesh_fuzzer.
#include <unistd.h>

#include <filesystem>
#include <string>

#include "tests/fuzz/fuzz_mesh.h"

namespace {

// The mesh and its neighbours' folder: one per process, so parallel fuzzers share nothing; removed at exit.
struct Folder {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("openplx_mesh_fuzz_" + std::to_string(getpid()));
  Folder() { std::filesystem::create_directories(path); }
  ~Folder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const Folder folder;
  openplx::fuzz::mesh_one(data, size, folder.path);
  return 0;
}
