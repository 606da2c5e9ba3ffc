// --stub-missing-meshes: most robots in the wild come without their mesh files (or with binary ones a text
// index does not hold), and then both importers refuse them for that alone. To still compare bodies, masses
// and poses, the survey can give both importers the same copy of the URDF in which every mesh file that is
// missing is replaced by one small binary STL cube (every mesh that exists is kept, by its absolute path).
// Links whose mass comes from their mesh then get the cube's, in both importers alike.
#pragma once

#include <filesystem>

namespace openplx::urdf_survey {

// Writes the copy (same file name as `urdf`) and the cube into `work_dir` and returns the copy's path, or
// `urdf` itself when none of its meshes is missing.
std::filesystem::path stub_missing_meshes(const std::filesystem::path& urdf,
                                          const std::filesystem::path& work_dir, int& stubbed);

}  // namespace openplx::urdf_survey
