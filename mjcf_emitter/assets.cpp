// Lowering pass, assets: <material>s from visual materials and <mesh>es from files or vertices.
#include "mjcf_emitter/asset_file_checks.h"
#include "mjcf_emitter/lowering.h"
#include "mjcf_emitter/mesh_conversion.h"
#include "mjcf_emitter/mesh_input_file.h"
#include "mjcf_emitter/mesh_references.h"

#include <cctype>
#include <filesystem>
#include <memory>
#include <sstream>

namespace openplx::mjcf {

namespace {

// Whether a material's metallic or roughness factor sets its MJCF attribute. A map scaled by it is dropped
// (MuJoCo has no slot for it): the factor alone keeps the material's look only where the user wrote it; the
// trait's default (1, "the map decides") alone would make a mirror (metallic 1) or a matte surface
// (roughness 1), so the attribute is left at MuJoCo's default.
bool use_factor(const sn::VisualMaterial& m, const char* map, bool written) {
  if (written) return true;
  for (const sn::FileTexture& t : m.file_textures)
    if (t.attribute == map) return false;
  for (const sn::InlineTexture& t : m.inline_textures)
    if (t.attribute == map) return false;
  return true;
}

// What dropping a map leaves of the material's look, for the warning.
std::string dropped_map_effect(const sn::VisualMaterial& m, const std::string& map) {
  if (map == "base_color_map") return " and the material keeps its colour";
  if (map == "metallic_map")
    return m.metallic_written ? ", and `metallic` alone sets the reflectance"
                              : ", and the reflectance is MuJoCo's default (0), not the Metallic trait's "
                                "default factor 1 without its map (a mirror)";
  if (map == "roughness_map")
    return m.roughness_written ? ", and `roughness` alone sets the shininess"
                               : ", and the shininess is MuJoCo's default (0.5), not 1 minus the Roughness "
                                 "trait's default factor 1 without its map";
  return "";
}

}  // namespace

// Visuals materials as MJCF materials: base colour tint -> rgba, times the Transparency's alpha (MuJoCo
// draws a geom whose alpha is below 1 see-through), 1 - roughness -> shininess (MuJoCo's is a glossiness),
// metallic -> reflectance, a base colour image -> a 2-D <texture> the material repeats scale_u x scale_v
// times.
void Lowering::emit_visual_materials() {
  for (const sn::VisualMaterial& m : system_.visual_materials) {
    Element& material = assets_->add("material");
    material.set("name", name(m.path));
    if (m.tint || m.alpha) {
      Eigen::Vector4d c = m.tint.value_or(Eigen::Vector4d::Ones());
      c[3] = std::clamp(c[3] * m.alpha.value_or(1.0), 0.0, 1.0);
      material.set("rgba", number(c[0]) + " " + number(c[1]) + " " + number(c[2]) + " " + number(c[3]));
    }
    if (m.roughness && use_factor(m, "roughness_map", m.roughness_written))
      material.set("shininess", std::clamp(1.0 - *m.roughness, 0.0, 1.0));
    if (m.metallic && use_factor(m, "metallic_map", m.metallic_written))
      material.set("reflectance", std::clamp(*m.metallic, 0.0, 1.0));
    for (const sn::FileTexture& t : m.file_textures) emit_texture(material, m, t);
    // Texture maps carry pixels inline (base64); MuJoCo 2.2.2 reads textures only from image files.
    for (const sn::InlineTexture& texture : m.inline_textures) {
      warn(texture.map.where, "`" + texture.map.name +
                                  "` is an inline texture, which MuJoCo 2.2.2 cannot read (it takes image "
                                  "files); it was left out" +
                                  dropped_map_effect(m, texture.attribute));
    }
  }
}

// A texture map from an image file. MuJoCo 2.2.2 materials take one texture, shown as the surface colour
// (modulated by rgba), repeated and linearly filtered with mipmaps: other maps, channel swizzles, offsets,
// other wrap and filter modes are warned each where the user wrote it, with what was done instead.
void Lowering::emit_texture(Element& material, const sn::VisualMaterial& m, const sn::FileTexture& t) {
  namespace fs = std::filesystem;
  const std::string map = "`" + t.map.name + "`";
  if (t.attribute != "base_color_map") {
    warn(t.map.where, map +
                          " is a texture MuJoCo 2.2.2 materials have no slot for (they take one colour "
                          "texture); it was left out" +
                          dropped_map_effect(m, t.attribute));
    return;
  }
  std::error_code ec;
  if (!fs::is_regular_file(t.file, ec)) {
    sink_.report(fe::DiagCode::MjcfMissingAsset, t.map.where,
                 "texture file " + t.file + " of " + map + " not found");
    return;
  }
  // Only what the material looks like depends on it: a file MuJoCo could not read is left out, warned.
  if (const std::string problem = png_file_problem(t.file); !problem.empty()) {
    warn(t.map.where, "texture file " + t.file + " of " + map + " is no PNG image MuJoCo can read (" +
                          problem + "); the texture was left out and the material keeps its colour");
    return;
  }
  if (!t.swizzle.empty())
    warn(t.swizzle_at.where, "`" + t.swizzle_at.name + "` (\"" + t.swizzle +
                                 "\") has no MuJoCo counterpart; all channels of " + map + " were used");
  if (t.filter_mode != 1)
    warn(t.filter_at.where, "`" + t.filter_at.name +
                                "` has no MuJoCo counterpart (textures are filtered linearly, mipmapped); " +
                                map + " is filtered linearly");
  if (t.wrap_mode != 0)
    warn(t.wrap_at.where,
         "`" + t.wrap_at.name + "` has no MuJoCo counterpart (textures repeat); " + map + " repeats");
  if (t.offset_u != 0 || t.offset_v != 0)
    warn(t.offset_at.where, "`" + t.offset_at.name +
                                "` has no MuJoCo counterpart (textures have no offset); " + map +
                                " starts at 0");
  std::string file = t.file;
  if (!options_.output_dir.empty())
    file = fs::path(t.file).lexically_relative(options_.output_dir).generic_string();
  const std::string texture = name(m.path) + "/" + t.attribute;
  assets_->add("texture").set("name", texture).set("type", "2d").set("file", file);
  material.set("texture", texture).set("texrepeat", number(t.scale_u) + " " + number(t.scale_v));
}

// A mesh given by its vertices (and, for a TriMesh, its triangles) as an inline MJCF mesh asset.
std::string Lowering::vertex_mesh_asset(const sn::Geometry& g) {
  const size_t n = g.vertices.size();
  bool valid_faces = g.indices.size() % 3 == 0;
  for (int k : g.indices) valid_faces = valid_faces && k >= 0 && static_cast<size_t>(k) < n;
  if (n < 4 || !valid_faces) {
    warn(g.where,
         "`" + g.path +
             (n < 4 ? ".vertices` has fewer than 4 points" : ".indices` are not triangles of its vertices") +
             "; MuJoCo needs a solid mesh, so it was left out");
    return {};
  }
  if (const std::string problem = vertices_problem(g.vertices); !problem.empty()) {
    const std::string message = "`" + g.path + ".vertices` cannot be a MuJoCo mesh: " + problem;
    if (g.visual) {
      warn(g.where, message + "; this visual geometry was left out");
    } else {
      sink_.report(fe::DiagCode::MjcfBadAsset, g.where, message);
    }
    return {};
  }
  if (g.shape == sn::Geometry::Shape::TriMesh && g.collides) {
    warn(g.where, "`" + g.path +
                      "` is a triangle mesh; MuJoCo 2.2.2 collides with its convex hull, so contacts "
                      "use the hull");
  }
  std::string vertex, face;
  for (const Eigen::Vector3d& p : g.vertices) {
    for (double coordinate : {p.x(), p.y(), p.z()}) {
      if (!vertex.empty()) vertex += ' ';
      append_number(vertex, coordinate);
    }
  }
  for (int k : g.indices) (face += face.empty() ? "" : " ") += std::to_string(k);
  const std::string mesh_name = name(g.path);
  Element& mesh = assets_->add("mesh");
  mesh.set("name", mesh_name).set("vertex", std::move(vertex));
  if (!face.empty()) mesh.set("face", std::move(face));
  return mesh_name;
}

// A mesh MuJoCo cannot be given changes the physics where it collides or has mass: an error there. A visual
// one only changes the look: a warning, and the visual is left out (a robot is never lost to its looks).
void Lowering::mesh_left_out(const sn::Geometry& g, fe::DiagCode code, const std::string& message) {
  if (g.visual) {
    warn(g.where, message + "; this visual geometry was left out");
  } else {
    sink_.report(code, g.where, message);
  }
}

std::string Lowering::mesh_asset(const sn::Geometry& g) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(g.file, ec)) {
    mesh_left_out(g, fe::DiagCode::MjcfMissingAsset,
                  "mesh file " + g.file + " of `" + g.path + "` not found");
    return {};
  }
  if (!g.scale.allFinite() || (g.scale.array() == 0).any()) {
    // Not through number(): a non-finite number written is the emitter's backstop.
    std::ostringstream scale;
    scale << g.scale.x() << " " << g.scale.y() << " " << g.scale.z();
    mesh_left_out(g, fe::DiagCode::MjcfBadAsset,
                  "mesh file " + g.file + " of `" + g.path + ".path` cannot be a MuJoCo mesh: its scale " +
                      scale.str() + " is not finite and non-zero");
    return {};
  }
  // MuJoCo's own readers open what they are given to the end, and its OBJ reader the material library the
  // file names: a FIFO or a device there hangs the user's load (mesh_input_file.h, mesh_references.h).
  // (A converted file is checked so once, where it is read.)
  std::string problem = mesh_input_file_problem(g.file);
  if (!problem.empty()) problem = "it " + problem;
  if (problem.empty() && converted_with_assimp(g.file)) return converted_mesh_asset(g);
  // A file MuJoCo cannot make a mesh of fails the user's load (or crashes it). Read once per file, however
  // many geometries name it.
  if (problem.empty()) {
    auto [checked, first] = untouched_mesh_problems_.try_emplace(g.file);
    if (first) {
      checked->second = mesh_references_problem(g.file);
      if (checked->second.empty()) checked->second = mesh_file_problem(g.file);
    }
    problem = checked->second;
  }
  if (!problem.empty()) {
    mesh_left_out(g, fe::DiagCode::MjcfBadAsset,
                  "mesh file " + g.file + " of `" + g.path + ".path` cannot be a MuJoCo mesh: " + problem);
    return {};
  }
  std::string file = g.file;
  if (!options_.output_dir.empty())
    file = fs::path(g.file).lexically_relative(options_.output_dir).generic_string();
  const std::string mesh_name = name(g.path);
  assets_->add("mesh").set("name", mesh_name).set("file", file).set("scale", g.scale);
  return mesh_name;
}

// Said once per COLLADA file whose <up_axis> (`up`, Y_UP or X_UP) makes the two readings differ, at the first
// geometry that names it.
void Lowering::note_collada_up_axis(const sn::Geometry& g, const std::string& up) {
  const std::string declares = "mesh file " + g.file + " declares <up_axis>" + up + "</up_axis>: ";
  sink_.report(fe::DiagCode::MjcfColladaUpAxis, g.where,
               options_.collada_up_axis
                   ? declares +
                         "it was turned so that its up axis is +Z (--collada-up-axis), as COLLADA "
                         "defines; RViz and Gazebo show it unturned"
                   : declares +
                         "its coordinates were taken as written, as RViz and Gazebo show them; "
                         "--collada-up-axis turns its up axis onto +Z, as COLLADA defines");
}

// A mesh file MuJoCo 2.2.2 cannot read, read with assimp once per file and held inline; the geometries of one
// file and scale share one asset. Writing to a file, the converter moves it into a file (mesh_files.h).
std::string Lowering::converted_mesh_asset(const sn::Geometry& g) {
  auto [read, first] = read_meshes_.try_emplace(g.file);
  if (first) {
    auto mesh = std::make_shared<TriangleMesh>();
    read->second.problem = read_mesh_with_assimp(g.file, *mesh);
    // COLLADA coordinates as written, as RViz and Gazebo show them (where robots are drawn and checked);
    // --collada-up-axis turns <up_axis> onto MuJoCo's +Z, as the standard defines it. Where the two differ,
    // one note per file says which was taken.
    std::string up = read->second.problem.empty() ? collada_up_axis(g.file) : "";
    if (!up.empty() && up != "Z_UP") {
      if (options_.collada_up_axis) turn_up_axis_onto_z(*mesh, up);
      note_collada_up_axis(g, up);
    }
    if (read->second.problem.empty()) read->second.problem = converted_mesh_problem(*mesh);
    if (read->second.problem.empty()) read->second.mesh = std::move(mesh);
  }
  if (!read->second.mesh) {
    mesh_left_out(
        g, fe::DiagCode::MjcfBadAsset,
        "mesh file " + g.file + " of `" + g.path + ".path` cannot be a MuJoCo mesh: " + read->second.problem);
    return {};
  }
  const std::string key =
      g.file + '\n' + number(g.scale.x()) + ' ' + number(g.scale.y()) + ' ' + number(g.scale.z());
  if (auto shared = converted_assets_.find(key); shared != converted_assets_.end()) return shared->second;
  const std::string mesh_name = name(g.path);
  assets_->add("mesh")
      .set("name", mesh_name)
      .set("vertex", vertex_text(*read->second.mesh))
      .set("face", face_text(*read->second.mesh))
      .set("scale", g.scale);
  converted_assets_.emplace(key, mesh_name);
  converted_meshes_.push_back({mesh_name, g.file, read->second.mesh});
  return mesh_name;
}

}  // namespace openplx::mjcf
