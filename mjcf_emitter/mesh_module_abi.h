// The C interface between the emitter and the mesh reader module (libopenplx_meshes.so), which carries the
// Open Asset Import Library: linked into the converter, assimp and the libraries it needs cost every start
// about 5 ms; loaded, only a conversion that meets a mesh MuJoCo cannot read pays for it. Only C types cross,
// because the converter carries its own C++ library while the module uses the system's.
#pragma once

#include <cstddef>
#include <cstdint>

extern "C" {

// Receives what was read; `context` is the caller's. Arrays are valid only during the call.
struct OpenplxMeshSink {
  void* context;
  // x y z per vertex, three 0-based vertex indices per triangle.
  void (*mesh)(void* context, const float* vertices, size_t vertex_floats, const uint32_t* faces,
               size_t face_indices);
  void (*problem)(void* context, const char* message, size_t size);  // why the file cannot be read
};

// Reads the mesh file at `path` (mesh_conversion.h says how); calls exactly one of the sink's functions.
typedef void (*OpenplxReadMeshFunction)(const char* path, const OpenplxMeshSink* sink);

}  // extern "C"

// The entry point's name; a changed interface gets a new name, so a stale module cannot be misread.
#define OPENPLX_READ_MESH_SYMBOL "openplx_read_mesh_v1"

// The problem text of a read that ran out of memory: the caller, which set the limit, words the message.
#define OPENPLX_MESH_OUT_OF_MEMORY "out of memory"
