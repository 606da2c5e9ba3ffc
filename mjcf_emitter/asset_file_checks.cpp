#include "mjcf_emitter/asset_file_checks.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>
#include <vector>

namespace openplx::mjcf {
namespace {

namespace fs = std::filesystem;

constexpr double kMaxCoordinate = 1 << 30;  // MuJoCo 2.2.2 calls larger vertices invalid
constexpr uint32_t kMaxStlFaces = 200000;   // and reads at most this many STL triangles

bool read_all(const std::string& path, std::string& bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream text;
  text << in.rdbuf();
  bytes = text.str();
  return true;
}

template <typename T>
T little_endian(const std::string& bytes, size_t at) {
  T value;
  std::memcpy(&value, bytes.data() + at, sizeof(T));  // x86 and ARM Linux are little-endian
  return value;
}

uint32_t big_endian32(const std::string& bytes, size_t at) {
  uint32_t v = 0;
  for (size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(bytes[at + k]);
  return v;
}

struct Mesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> faces;  // 0-based
  std::vector<size_t> face_lines;         // an OBJ face's line, one per triangle
  size_t first_object_faces = 0;          // how many faces MuJoCo reads of an OBJ (its first object's)
};

std::string bad_vertex(const Eigen::Vector3d& v, size_t index) {
  if (v.allFinite() && v.cwiseAbs().maxCoeff() <= kMaxCoordinate) return {};
  std::ostringstream text;
  text << "vertex " << index + 1 << " is " << v.x() << " " << v.y() << " " << v.z()
       << " (MuJoCo takes finite coordinates up to 2^30)";
  return text.str();
}

std::string read_stl(const std::string& bytes, Mesh& mesh) {
  if (bytes.size() < 84)
    return "it is " + std::to_string(bytes.size()) + " bytes, shorter than a binary STL header";
  const auto faces = little_endian<uint32_t>(bytes, 80);
  if (faces < 1 || faces > kMaxStlFaces)
    return "it claims " + std::to_string(faces) +
           " triangles (MuJoCo 2.2.2 reads binary STL of 1 to 200000; " + "ASCII STL it cannot read)";
  if (bytes.size() != 84 + 50 * static_cast<uint64_t>(faces))
    return "it is " + std::to_string(bytes.size()) + " bytes, where " + std::to_string(faces) +
           " triangles take " + std::to_string(84 + 50 * static_cast<uint64_t>(faces)) +
           " (truncated, or ASCII STL, which MuJoCo 2.2.2 cannot read)";
  for (uint32_t f = 0; f < faces; ++f) {
    std::array<int, 3> face;
    for (int k = 0; k < 3; ++k) {
      const size_t at = 84 + 50 * static_cast<size_t>(f) + 12 + 12 * k;
      mesh.vertices.emplace_back(little_endian<float>(bytes, at), little_endian<float>(bytes, at + 4),
                                 little_endian<float>(bytes, at + 8));
      face[k] = static_cast<int>(mesh.vertices.size() - 1);
    }
    mesh.faces.push_back(face);
  }
  return {};
}

// An OBJ index ("3", "3/1", "3//2", "-1") as a 0-based vertex index; -1 when it names no vertex so far.
int obj_index(const std::string& token, size_t vertices) {
  char* end = nullptr;
  const long k = std::strtol(token.c_str(), &end, 10);
  if (end == token.c_str() || (*end != '\0' && *end != '/')) return -1;
  const long n = static_cast<long>(vertices);
  const long index = k > 0 ? k - 1 : n + k;
  return k != 0 && index >= 0 && index < n ? static_cast<int>(index) : -1;
}

// Whether a face corner's texture-coordinate and normal indices ("3/1", "3//2", "3/1/2", negatives counting
// back) name ones given before it: MuJoCo 2.2.2 uses them unchecked, and one far out of range crashes it.
bool obj_attribute_indices_valid(const std::string& token, size_t texcoords, size_t normals) {
  size_t at = token.find('/');
  for (size_t count : {texcoords, normals}) {
    if (at == std::string::npos) return true;
    const size_t begin = at + 1;
    at = token.find('/', begin);
    const std::string part = token.substr(begin, at == std::string::npos ? std::string::npos : at - begin);
    if (part.empty()) continue;  // "3//2": no texture coordinate
    char* end = nullptr;
    const long k = std::strtol(part.c_str(), &end, 10);
    const long n = static_cast<long>(count);
    const long index = k > 0 ? k - 1 : n + k;
    if (*end != '\0' || k == 0 || index < 0 || index >= n) return false;
  }
  return at == std::string::npos;  // no fourth part
}

// The whitespace `std::istream >> std::string` skips in the classic locale.
bool obj_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r';
}

// The next whitespace-separated word of `line` (advanced past it); empty at the end.
std::string_view next_word(std::string_view& line) {
  size_t begin = 0;
  while (begin < line.size() && obj_space(line[begin])) ++begin;
  size_t end = begin;
  while (end < line.size() && !obj_space(line[end])) ++end;
  const std::string_view word = line.substr(begin, end - begin);
  line.remove_prefix(end);
  return word;
}

std::string read_obj(const std::string& bytes, Mesh& mesh) {
  // Lines and words as std::getline and `>>` split them, without a stream per line (a stream's construction
  // was a third of reading a mesh-heavy robot); numbers go through strtod and strtol as before, from one
  // reused buffer.
  std::string word;  // the current word, NUL-terminated for strtod and strtol
  std::vector<double> values;
  std::vector<int> corners;
  bool first_object_ended = false;
  size_t texcoords = 0, normals = 0;
  size_t start = 0;
  for (size_t number = 1; start < bytes.size(); ++number) {
    const size_t eol = bytes.find('\n', start);
    std::string_view line(bytes.data() + start, (eol == std::string::npos ? bytes.size() : eol) - start);
    start = eol == std::string::npos ? bytes.size() : eol + 1;
    const std::string_view kind = next_word(line);
    auto at = [number] { return "line " + std::to_string(number) + ": "; };
    // MuJoCo 2.2.2 reads the faces of the file's first object (tinyobjloader's first shape): an `o` or `g`
    // after faces ends it.
    if ((kind == "o" || kind == "g") && !mesh.faces.empty()) first_object_ended = true;
    texcoords += kind == "vt" ? 1 : 0;
    normals += kind == "vn" ? 1 : 0;
    if (kind == "v") {
      values.clear();
      for (std::string_view w = next_word(line); !w.empty(); w = next_word(line)) {
        word.assign(w);
        char* end = nullptr;
        values.push_back(std::strtod(word.c_str(), &end));
        if (*end != '\0') return at() + "vertex coordinate '" + word + "' is no number";
      }
      if (values.size() < 3 || values.size() > 7)  // x y z, optionally w or a colour
        return at() + "a vertex of " + std::to_string(values.size()) + " numbers, not 3";
      mesh.vertices.emplace_back(values[0], values[1], values[2]);
      if (std::string bad = bad_vertex(mesh.vertices.back(), mesh.vertices.size() - 1); !bad.empty())
        return at() + bad;
    } else if (kind == "f") {
      corners.clear();
      for (std::string_view w = next_word(line); !w.empty(); w = next_word(line)) {
        word.assign(w);
        corners.push_back(obj_index(word, mesh.vertices.size()));
        if (corners.back() < 0) return at() + "face corner '" + word + "' names no vertex before it";
        if (!obj_attribute_indices_valid(word, texcoords, normals))
          return at() + "face corner '" + word +
                 "' names a texture coordinate or normal not given before it (" + std::to_string(texcoords) +
                 " and " + std::to_string(normals) + " are)";
      }
      if (corners.size() < 3) return at() + "a face of fewer than 3 corners";
      for (size_t k = 1; k + 1 < corners.size(); ++k) {  // fanned from the first corner, as MuJoCo 2.2.2 does
        mesh.faces.push_back({corners[0], corners[k], corners[k + 1]});
        mesh.face_lines.push_back(number);
      }
      if (!first_object_ended) mesh.first_object_faces = mesh.faces.size();
    }
  }
  return {};
}

// MuJoCo 2.2.2 refuses an OBJ whose faces run along one edge in the same direction (two faces from vertex a
// to vertex b: one of them is turned inside out, or the face is there twice). It compares the file's vertex
// indices, not positions, and counts every face of the first object, degenerate ones too. It asks only where
// it computes a geom's inertia from the mesh (a body without <inertial>, inertiafromgeom="true" in a scene
// that includes the file, a primitive fitted to it), so it is held to everywhere.
std::string orientation_problem(const Mesh& mesh) {
  // Every directed edge (from << 32 | to) with the face that runs it, sorted so that a repeated edge is
  // adjacent (a sorted array: a fraction of a hash map's memory on a large mesh).
  std::vector<std::pair<uint64_t, size_t>> edges;
  edges.reserve(3 * mesh.first_object_faces);
  for (size_t f = 0; f < mesh.first_object_faces; ++f)
    for (int k = 0; k < 3; ++k)
      edges.emplace_back(uint64_t{static_cast<uint32_t>(mesh.faces[f][k])} << 32 |
                             static_cast<uint32_t>(mesh.faces[f][(k + 1) % 3]),
                         f);
  std::sort(edges.begin(), edges.end());
  size_t clash = 0;  // the repeated edge named: its later face first in the file, then its earlier one
  for (size_t k = 1; k < edges.size(); ++k) {
    if (edges[k].first != edges[k - 1].first) continue;
    if (!clash || std::pair(edges[k].second, edges[k - 1].second) <
                      std::pair(edges[clash].second, edges[clash - 1].second))
      clash = k;
  }
  if (!clash) return {};
  const uint64_t edge = edges[clash].first;
  return "its faces have inconsistent orientation (MuJoCo 2.2.2 refuses it): the faces on lines " +
         std::to_string(mesh.face_lines[edges[clash - 1].second]) + " and " +
         std::to_string(mesh.face_lines[edges[clash].second]) + " both run from vertex " +
         std::to_string((edge >> 32) + 1) + " to vertex " + std::to_string((edge & 0xffffffffu) + 1) +
         ", so one is turned inside out or given twice";
}

std::string read_msh(const std::string& bytes, Mesh& mesh) {
  if (bytes.size() < 16) return "it is shorter than an MSH header";
  const auto nvert = little_endian<int32_t>(bytes, 0), nnormal = little_endian<int32_t>(bytes, 4),
             ntexcoord = little_endian<int32_t>(bytes, 8), nface = little_endian<int32_t>(bytes, 12);
  if (nvert < 0 || nnormal < 0 || ntexcoord < 0 || nface < 0) return "its header has negative counts";
  const uint64_t expected = 16 + 12 * static_cast<uint64_t>(nvert) + 12 * static_cast<uint64_t>(nnormal) +
                            8 * static_cast<uint64_t>(ntexcoord) + 12 * static_cast<uint64_t>(nface);
  if (bytes.size() != expected)
    return "it is " + std::to_string(bytes.size()) + " bytes where its header's counts take " +
           std::to_string(expected);
  for (int32_t v = 0; v < nvert; ++v) {
    const size_t at = 16 + 12 * static_cast<size_t>(v);
    mesh.vertices.emplace_back(little_endian<float>(bytes, at), little_endian<float>(bytes, at + 4),
                               little_endian<float>(bytes, at + 8));
  }
  const size_t faces_at = 16 + 12 * static_cast<size_t>(nvert + nnormal) + 8 * static_cast<size_t>(ntexcoord);
  for (int32_t f = 0; f < nface; ++f) {
    std::array<int, 3> face;
    for (int k = 0; k < 3; ++k) {
      face[k] = little_endian<int32_t>(bytes, faces_at + 12 * static_cast<size_t>(f) + 4 * k);
      if (face[k] < 0 || face[k] >= nvert) return "face " + std::to_string(f + 1) + " names no vertex";
    }
    mesh.faces.push_back(face);
  }
  return {};
}

// What MuJoCo's compiler then needs: finite vertices, a solid hull for qhull (not all on one plane), and
// triangles of some area when there are triangles.
std::string solid_problem(const Mesh& mesh) {
  for (size_t k = 0; k < mesh.vertices.size(); ++k)
    if (std::string bad = bad_vertex(mesh.vertices[k], k); !bad.empty()) return bad;
  if (mesh.vertices.size() < 4)
    return "it has " + std::to_string(mesh.vertices.size()) + " vertices; a solid needs 4 or more";
  const Eigen::Vector3d& origin = mesh.vertices.front();
  Eigen::Vector3d far = origin;
  for (const Eigen::Vector3d& v : mesh.vertices)
    if ((v - origin).squaredNorm() > (far - origin).squaredNorm()) far = v;
  const double size = (far - origin).norm();
  const Eigen::Vector3d along = size > 0 ? Eigen::Vector3d((far - origin) / size) : Eigen::Vector3d::Zero();
  Eigen::Vector3d off = Eigen::Vector3d::Zero();  // the farthest point from the line origin-far
  for (const Eigen::Vector3d& v : mesh.vertices) {
    const Eigen::Vector3d d = (v - origin) - (v - origin).dot(along) * along;
    if (d.squaredNorm() > off.squaredNorm()) off = d;
  }
  double height = 0;  // the farthest distance from the plane through origin, far and off
  if (off.norm() > 1e-9 * size) {
    const Eigen::Vector3d normal = along.cross(off.normalized());
    for (const Eigen::Vector3d& v : mesh.vertices)
      height = std::max(height, std::abs((v - origin).dot(normal)));
  }
  if (!(size > 0) || height <= 1e-9 * size)
    return "its vertices lie on one plane (or line, or point), so it encloses no volume and has no convex "
           "hull";
  if (!mesh.faces.empty()) {
    double area = 0;
    for (const auto& f : mesh.faces)
      area += (mesh.vertices[f[1]] - mesh.vertices[f[0]])
                  .cross(mesh.vertices[f[2]] - mesh.vertices[f[0]])
                  .norm() /
              2;
    if (!(area > 1e-15)) return "its triangles have no area";
  }
  return {};
}

uint32_t crc32(const char* data, size_t size) {
  uint32_t crc = 0xffffffffu;
  for (size_t k = 0; k < size; ++k) {
    crc ^= static_cast<unsigned char>(data[k]);
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

}  // namespace

std::string vertices_problem(const std::vector<Eigen::Vector3d>& vertices) {
  Mesh mesh;
  mesh.vertices = vertices;
  return solid_problem(mesh);
}

std::string converted_mesh_problem(const TriangleMesh& converted) {
  Mesh mesh;
  for (size_t k = 0; k + 2 < converted.vertices.size(); k += 3)
    mesh.vertices.emplace_back(converted.vertices[k], converted.vertices[k + 1], converted.vertices[k + 2]);
  for (size_t k = 0; k + 2 < converted.faces.size(); k += 3)
    mesh.faces.push_back({static_cast<int>(converted.faces[k]), static_cast<int>(converted.faces[k + 1]),
                          static_cast<int>(converted.faces[k + 2])});
  return solid_problem(mesh);
}

std::string mesh_file_problem(const std::string& path) {
  std::string bytes;
  if (!read_all(path, bytes)) return "it cannot be read";
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  Mesh mesh;
  const std::string problem = ext == ".stl"   ? read_stl(bytes, mesh)
                              : ext == ".msh" ? read_msh(bytes, mesh)
                                              : read_obj(bytes, mesh);
  if (!problem.empty()) return problem;
  if (std::string solid = solid_problem(mesh); !solid.empty()) return solid;
  // A binary STL reaches MuJoCo's check as separate triangles, and an MSH is not checked.
  return ext != ".stl" && ext != ".msh" ? orientation_problem(mesh) : std::string();
}

std::string png_file_problem(const std::string& path) {
  std::string bytes;
  if (!read_all(path, bytes)) return "it cannot be read";
  static const char kSignature[] = "\x89PNG\r\n\x1a\n";
  if (bytes.size() < 8 || bytes.compare(0, 8, kSignature, 8) != 0)
    return "it does not start as a PNG file does";
  bool header = false, data = false;
  for (size_t at = 8;;) {
    if (at + 12 > bytes.size()) return "it ends before its last chunk (IEND): truncated";
    const uint32_t length = big_endian32(bytes, at);
    if (length > bytes.size() - at - 12) return "a chunk runs past the end of the file: truncated";
    const std::string type = bytes.substr(at + 4, 4);
    if (crc32(bytes.data() + at + 4, 4 + length) != big_endian32(bytes, at + 8 + length))
      return "its " + type + " chunk fails its checksum: the file is damaged";
    if (!header) {
      if (type != "IHDR" || length != 13) return "it does not begin with an image header (IHDR)";
      const uint64_t width = big_endian32(bytes, at + 8), height = big_endian32(bytes, at + 12);
      if (width == 0 || height == 0) return "its image has no pixels";
      // MuJoCo 2.2.2 keeps a texture as 3 bytes a pixel and counts them in an int (mjModel::ntexdata):
      // larger, it would first try to decode gigabytes and then overflow the count.
      if (3 * width * height > static_cast<uint64_t>(std::numeric_limits<int>::max()))
        return "its header claims " + std::to_string(width) + " x " + std::to_string(height) +
               " pixels, more than MuJoCo keeps in a texture (3 bytes a pixel, fewer than 2^31 bytes)";
      header = true;
    }
    data = data || type == "IDAT";
    if (type == "IEND") return data ? std::string() : "it holds no image data (IDAT)";
    at += 12 + length;
  }
}

}  // namespace openplx::mjcf
