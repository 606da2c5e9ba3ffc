#include "tools/urdf_survey/stub_meshes.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "tools/urdf_survey/mujoco_urdf.h"

namespace openplx::urdf_survey {

namespace fs = std::filesystem;

namespace {

// A 2 cm cube centred at the origin as binary STL (MuJoCo 2.2.2 reads binary STL only).
void write_cube(const fs::path& file) {
  const float h = 0.01f;
  const std::array<std::array<float, 3>, 8> v{
      {{-h, -h, -h}, {h, -h, -h}, {h, h, -h}, {-h, h, -h}, {-h, -h, h}, {h, -h, h}, {h, h, h}, {-h, h, h}}};
  // Counter-clockwise seen from outside.
  const std::array<std::array<int, 3>, 12> faces{{{0, 2, 1},
                                                  {0, 3, 2},
                                                  {4, 5, 6},
                                                  {4, 6, 7},
                                                  {0, 1, 5},
                                                  {0, 5, 4},
                                                  {1, 2, 6},
                                                  {1, 6, 5},
                                                  {2, 3, 7},
                                                  {2, 7, 6},
                                                  {3, 0, 4},
                                                  {3, 4, 7}}};
  std::ofstream out(file, std::ios::binary);
  char header[80] = "urdf-survey stub cube";
  out.write(header, sizeof(header));
  const std::uint32_t count = faces.size();
  out.write(reinterpret_cast<const char*>(&count), sizeof(count));
  for (const auto& f : faces) {
    const float normal[3] = {0, 0, 0};  // readers compute their own
    out.write(reinterpret_cast<const char*>(normal), sizeof(normal));
    for (int k : f) out.write(reinterpret_cast<const char*>(v[k].data()), 3 * sizeof(float));
    const std::uint16_t attributes = 0;
    out.write(reinterpret_cast<const char*>(&attributes), sizeof(attributes));
  }
}

// Where a URDF mesh name points on this machine (empty when a package cannot be found).
fs::path resolve(const std::string& name, const fs::path& urdf_dir) {
  const std::string package = "package://", file = "file://";
  if (name.rfind(package, 0) == 0) {
    const size_t slash = name.find('/', package.size());
    if (slash == std::string::npos) return {};
    const fs::path folder = find_package(name.substr(package.size(), slash - package.size()), urdf_dir);
    return folder.empty() ? fs::path() : folder / name.substr(slash + 1);
  }
  if (name.rfind(file, 0) == 0) return fs::path(name.substr(file.size()));
  const fs::path p(name);
  return p.is_absolute() ? p : urdf_dir / p;
}

}  // namespace

fs::path stub_missing_meshes(const fs::path& urdf, const fs::path& work_dir, int& stubbed) {
  stubbed = 0;
  std::ifstream in(urdf, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  const std::string xml = text.str();
  const fs::path cube = work_dir / "stub_cube.stl";
  static const std::regex mesh_file(R"((<mesh\b[^>]*?\bfilename\s*=\s*)(["'])(.*?)\2)");
  std::string out;
  size_t last = 0;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), mesh_file); it != std::sregex_iterator();
       ++it) {
    const std::smatch& m = *it;
    const fs::path target = resolve(m[3].str(), urdf.parent_path());
    std::error_code ec;
    const bool exists = !target.empty() && fs::is_regular_file(target, ec);
    out += xml.substr(last, m.position(0) - last);
    out += m[1].str() + m[2].str() + (exists ? fs::absolute(target).string() : cube.string()) + m[2].str();
    last = m.position(0) + m.length(0);
    stubbed += !exists;
  }
  if (stubbed == 0) return urdf;
  out += xml.substr(last);
  write_cube(cube);
  const fs::path copy = work_dir / "stubbed" / urdf.filename();
  fs::create_directories(copy.parent_path());
  std::ofstream(copy, std::ios::binary) << out;
  return copy;
}

}  // namespace openplx::urdf_survey
