#include "tests/support/tetrahedron_stl.h"

#include <cstdint>
#include <fstream>

namespace openplx::testing {

void write_tetrahedron(const std::filesystem::path& path) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  const float v[4][3] = {{0, 0, 0}, {0.1f, 0, 0}, {0, 0.1f, 0}, {0, 0, 0.1f}};
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const char header[80] = {};
  out.write(header, 80);
  const uint32_t count = 4;
  out.write(reinterpret_cast<const char*>(&count), 4);
  for (const auto& f : faces) {
    const float normal[3] = {0, 0, 0};
    out.write(reinterpret_cast<const char*>(normal), 12);
    for (int k : f) out.write(reinterpret_cast<const char*>(v[k]), 12);
    const uint16_t attribute = 0;
    out.write(reinterpret_cast<const char*>(&attribute), 2);
  }
}

}  // namespace openplx::testing
