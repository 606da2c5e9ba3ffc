// Mesh and image files read before MuJoCo reads them: a file MuJoCo 2.2.2 cannot use (garbage, truncated,
// NaN vertices, a flat mesh qhull cannot wrap, an OBJ with faces turned inside out, a PNG that is none)
// otherwise fails the draft compile or the user's load with an unlocated message, qhull's raw text on stderr,
// or a crash (an OBJ vertex of two numbers). These checks follow MuJoCo 2.2.2's own readers (user_mesh.cc,
// lodepng), so a file that passes them loads.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mjcf_emitter/mesh_conversion.h"

namespace openplx::mjcf {

// Why MuJoCo 2.2.2 cannot make a mesh of the OBJ, binary STL or MSH file at `path`; empty when it can. An
// OBJ's faces must also be consistently oriented: no two run along one edge in the same direction.
std::string mesh_file_problem(const std::string& path);

// Why MuJoCo 2.2.2 cannot make a solid mesh of these vertices (non-finite, fewer than 4, all on one plane:
// qhull fails, printing to stderr); empty when it can.
std::string vertices_problem(const std::vector<Eigen::Vector3d>& vertices);

// Why MuJoCo 2.2.2 cannot make a solid mesh of a mesh read with assimp (the same checks as for a file it
// reads); empty when it can.
std::string converted_mesh_problem(const TriangleMesh& mesh);

// Why the file at `path` is no PNG image MuJoCo 2.2.2 can read; empty when it is one.
std::string png_file_problem(const std::string& path);

}  // namespace openplx::mjcf
