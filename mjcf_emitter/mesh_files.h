// Converted meshes (mesh_conversion.h) as files beside a written MJCF: a folder OUT.meshes/ beside OUT.xml
// holds one file per source mesh, named after it, which the <mesh> assets name relative to the MJCF. The
// emitter keeps them inline until then (every triangle with its own vertices, as MuJoCo reads the STL), so
// its draft compile reads them without any file; --check loads copies of the files (move_mesh_folder).
#pragma once

#include <string>
#include <vector>

#include "mjcf_emitter/emitter.h"

namespace openplx::mjcf {

struct MeshFile {
  std::string path;   // relative to the MJCF's folder, '/'-separated
  std::string bytes;  // binary STL or OBJ (mesh_file_bytes)
};

// The folder beside `output` (an MJCF path) its converted meshes go to: "robot.xml" -> "robot.meshes".
std::string mesh_folder_for(const std::string& output);

// Moves `emitted`'s converted meshes out of its document: each such <mesh> asset names its file under
// `folder` instead of holding its vertices. Returns the files to write, in emission order; their names come
// from the source files' names (numbered when two share one), so the same input gives the same names.
std::vector<MeshFile> move_meshes_to_files(Emitted& emitted, const std::string& folder);

// Names `files` (from move_meshes_to_files) under `folder`, keeping their file names, and points the <mesh>
// assets of `document` that name them there too (nothing on disk moves): --check loads its own copies.
void move_mesh_folder(Element& document, std::vector<MeshFile>& files, const std::string& folder);

}  // namespace openplx::mjcf
