// A binary STL tetrahedron (MuJoCo reads binary STL) for tests that need a mesh file on disk.
#pragma once

#include <filesystem>

namespace openplx::testing {

// Writes a 0.1 m right tetrahedron at `path`, creating its folders.
void write_tetrahedron(const std::filesystem::path& path);

}  // namespace openplx::testing
