// Whether a file may be given to a mesh reader at all: the mesh file itself and every file it names (glTF
// buffers and images, COLLADA images, OBJ material libraries, whatever else assimp opens). A reader opens
// and reads what it is given to the end: a FIFO blocks it for ever, /dev/zero never ends, and a file under
// /proc or /sys claims a size it does not hold. Shared by the converter and the mesh reader module.
#pragma once

#include <cstdint>
#include <string>

namespace openplx::mjcf {

// Larger than any robot part's mesh (MuJoCo 2.2.2 reads at most 200000 triangles of an STL, 10 MB); a
// reader needs several times the file in memory.
inline constexpr uintmax_t kMaxMeshFileBytes = uintmax_t{256} << 20;

// Why the file at `path` must not be read, as a predicate ("is a FIFO, not a regular file", "is larger than
// ...", "lies in a kernel file system (proc), ..."); empty when it may. Symbolic links are followed.
std::string mesh_input_file_problem(const std::string& path);

}  // namespace openplx::mjcf
