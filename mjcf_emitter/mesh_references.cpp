#include "mjcf_emitter/mesh_references.h"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string_view>

#include "mjcf_emitter/mesh_input_file.h"

namespace openplx::mjcf {
namespace {

namespace fs = std::filesystem;

// More names than any real mesh carries; each costs a stat.
constexpr size_t kMaxReferences = 10000;

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// glTF's top-level "buffers" and "images" (an array in glTF 2, an object of named entries in glTF 1): the
// "uri" of each entry. A SAX handler, so no tree is built and nesting costs no stack: containers below the
// three levels that matter are only counted.
class GltfUris {
 public:
  using json = nlohmann::json;
  explicit GltfUris(std::vector<MeshReference>& out) : out_(out) {}

  bool start_object(size_t) { return open(); }
  bool start_array(size_t) { return open(); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }
  bool key(json::string_t& k) {
    if (below_ == 0) key_ = k;
    return true;
  }
  bool string(json::string_t& s) {
    if (below_ == 0 && level_ == Level::Entry && key_ == "uri") out_.push_back({role_, s});
    return true;
  }
  bool null() { return true; }
  bool boolean(bool) { return true; }
  bool number_integer(json::number_integer_t) { return true; }
  bool number_unsigned(json::number_unsigned_t) { return true; }
  bool number_float(json::number_float_t, const json::string_t&) { return true; }
  bool binary(json::binary_t&) { return true; }
  bool parse_error(size_t, const std::string&, const nlohmann::detail::exception&) { return false; }

 private:
  enum class Level {
    None,
    Top,
    List,
    Entry
  };  // outside, the top object, buffers/images, one of their entries

  bool open() {
    if (below_ > 0) {
      ++below_;
    } else if (level_ == Level::None) {
      level_ = Level::Top;
    } else if (level_ == Level::Top && (key_ == "buffers" || key_ == "images")) {
      level_ = Level::List;
      role_ = key_ == "buffers" ? "buffer" : "image";
    } else if (level_ == Level::List) {
      level_ = Level::Entry;
      key_.clear();
    } else {
      below_ = 1;
    }
    return true;
  }
  bool close() {
    if (below_ > 0) {
      --below_;
    } else {
      level_ = level_ == Level::Entry ? Level::List : level_ == Level::List ? Level::Top : Level::None;
      key_.clear();
    }
    return true;
  }

  std::vector<MeshReference>& out_;
  Level level_ = Level::None;
  size_t below_ = 0;  // containers open below the levels that matter
  std::string key_;
  std::string role_;
};

void gltf_references(std::string_view json_text, std::vector<MeshReference>& out) {
  GltfUris handler(out);
  try {
    nlohmann::json::sax_parse(json_text, &handler);
  } catch (const std::exception&) {  // damaged text: what was read before it stands
  }
}

uint32_t little_endian32(const std::string& bytes, size_t at) {
  uint32_t v = 0;
  for (size_t k = 4; k-- > 0;) v = (v << 8) | static_cast<unsigned char>(bytes[at + k]);
  return v;
}

// A .glb's JSON: the first chunk of a glTF 2 container, or the content of a glTF 1 one.
std::string_view glb_json(const std::string& bytes) {
  if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0) return {};
  const uint32_t version = little_endian32(bytes, 4), length = little_endian32(bytes, 12);
  const uint32_t kind = little_endian32(bytes, 16);
  const bool json = version == 2 ? kind == 0x4E4F534Au /* "JSON" */ : version == 1 && kind == 0;
  if (!json) return {};
  return std::string_view(bytes).substr(20, length);
}

// XML's five named entities; numeric ones are left as written (no path needs them).
std::string xml_text(std::string_view raw) {
  static const std::pair<std::string_view, char> kEntities[] = {
      {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
  std::string text;
  for (size_t at = 0; at < raw.size();) {
    bool replaced = false;
    for (const auto& [entity, c] : kEntities) {
      if (raw.compare(at, entity.size(), entity) == 0) {
        text += c;
        at += entity.size();
        replaced = true;
        break;
      }
    }
    if (!replaced) text += raw[at++];
  }
  const size_t first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
}

// The text of every <init_from> (COLLADA 1.4) or <init_from><ref> (1.5) inside an <image>. A scan, not a
// parse: comments, CDATA and declarations are skipped, quoted attribute values may hold '>', and depth is a
// counter, so nesting costs no memory.
void collada_references(const std::string& xml, std::vector<MeshReference>& out) {
  long depth = 0, image_depth = -1;  // the open <image>'s depth, -1 outside one
  for (size_t at = xml.find('<'); at != std::string::npos; at = xml.find('<', at)) {
    if (xml.compare(at, 4, "<!--") == 0) {
      at = xml.find("-->", at + 4);
      if (at != std::string::npos) at += 3;
      continue;
    }
    if (xml.compare(at, 9, "<![CDATA[") == 0) {
      at = xml.find("]]>", at + 9);
      if (at != std::string::npos) at += 3;
      continue;
    }
    if (xml.compare(at, 2, "<?") == 0 || xml.compare(at, 2, "<!") == 0) {
      at = xml.find('>', at + 2);
      if (at != std::string::npos) ++at;
      continue;
    }
    const bool closing = xml.compare(at, 2, "</") == 0;
    size_t name_begin = at + (closing ? 2 : 1), name_end = name_begin;
    while (name_end < xml.size() && !std::isspace(static_cast<unsigned char>(xml[name_end])) &&
           xml[name_end] != '/' && xml[name_end] != '>')
      ++name_end;
    std::string_view name(xml.data() + name_begin, name_end - name_begin);
    if (const size_t colon = name.rfind(':'); colon != std::string_view::npos) name.remove_prefix(colon + 1);
    // The tag's end: the first '>' outside a quoted attribute value.
    size_t end = name_end;
    for (char quote = 0; end < xml.size() && (quote || xml[end] != '>'); ++end) {
      if (quote && xml[end] == quote)
        quote = 0;
      else if (!quote && (xml[end] == '"' || xml[end] == '\''))
        quote = xml[end];
    }
    if (end >= xml.size()) return;  // a tag cut off: the file ends there
    if (closing) {
      if (--depth < image_depth) image_depth = -1;
    } else if (xml[end - 1] != '/') {  // not self-closing
      ++depth;
      if (name == "image") image_depth = depth;
      if (image_depth >= 0 && depth > image_depth && (name == "init_from" || name == "ref")) {
        const size_t text_end = xml.find('<', end + 1);
        const std::string text = xml_text(std::string_view(xml).substr(
            end + 1, text_end == std::string::npos ? text_end : text_end - end - 1));
        if (!text.empty()) out.push_back({"image", text});
      }
    }
    at = end + 1;
  }
}

// OBJ's `mtllib` lines; each may list several files (MuJoCo's reader takes the first it can open).
void obj_references(const std::string& text, std::vector<MeshReference>& out) {
  for (size_t at = 0; at < text.size();) {
    size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + at, end - at);
    at = end + 1;
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string_view::npos || line.compare(first, 6, "mtllib") != 0) continue;
    line.remove_prefix(first + 6);
    if (line.empty() || !std::isspace(static_cast<unsigned char>(line[0]))) continue;  // "mtllibx"
    for (size_t word = 0; (word = line.find_first_not_of(" \t\r\v\f", word)) != std::string_view::npos;) {
      const size_t word_end = std::min(line.size(), line.find_first_of(" \t\r\v\f", word));
      out.push_back({"material library", std::string(line.substr(word, word_end - word))});
      word = word_end;
    }
  }
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
}

std::string percent_decoded(const std::string& name) {
  std::string out;
  for (size_t k = 0; k < name.size(); ++k) {
    if (name[k] == '%' && k + 2 < name.size() && hex_digit(name[k + 1]) >= 0 && hex_digit(name[k + 2]) >= 0) {
      out += static_cast<char>(hex_digit(name[k + 1]) * 16 + hex_digit(name[k + 2]));
      k += 2;
    } else {
      out += name[k];
    }
  }
  return out;
}

// The paths a name may stand for, beside the mesh in `dir`: as written and percent-decoded (readers differ
// on URIs); none for inline data and URLs.
std::vector<std::string> candidate_paths(const fs::path& dir, std::string name) {
  size_t scheme = 0;
  while (scheme < name.size() && (std::isalnum(static_cast<unsigned char>(name[scheme])) ||
                                  name[scheme] == '+' || name[scheme] == '-' || name[scheme] == '.'))
    ++scheme;
  if (scheme > 1 && scheme < name.size() && name[scheme] == ':') {  // one letter is a Windows drive
    std::string lower = name.substr(0, scheme);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (lower != "file") return {};  // data:, http:, ...: no file here
    name.erase(0, scheme + 1);
    if (name.compare(0, 2, "//") == 0) {  // file://host/path: only this host's paths are files here
      const size_t path = name.find('/', 2);
      if (path == std::string::npos) return {};
      name.erase(0, path);
    }
  }
  if (name.empty()) return {};
  std::vector<std::string> paths;
  for (const std::string& form : {name, percent_decoded(name)}) {
    const fs::path p(form);
    const std::string path = (p.is_absolute() ? p : dir / p).string();
    if (std::find(paths.begin(), paths.end(), path) == paths.end()) paths.push_back(path);
  }
  return paths;
}

}  // namespace

std::vector<MeshReference> mesh_references(const std::string& ext, const std::string& bytes) {
  std::vector<MeshReference> references;
  if (ext == ".gltf") gltf_references(bytes, references);
  if (ext == ".glb") gltf_references(glb_json(bytes), references);
  if (ext == ".dae") collada_references(bytes, references);
  if (ext == ".obj") obj_references(bytes, references);
  return references;
}

std::string mesh_references_problem(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext != ".gltf" && ext != ".glb" && ext != ".dae" && ext != ".obj") return {};
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const fs::path dir = fs::path(path).parent_path();
  std::set<std::string> checked;
  for (const MeshReference& reference : mesh_references(ext, bytes)) {
    for (const std::string& candidate : candidate_paths(dir, reference.name)) {
      if (!checked.insert(candidate).second) continue;
      if (checked.size() > kMaxReferences)
        return "it names more than " + std::to_string(kMaxReferences) + " files";
      struct stat st {};
      if (::stat(candidate.c_str(), &st) != 0) continue;  // not there: the reader says so if it needs it
      if (const std::string problem = mesh_input_file_problem(candidate); !problem.empty())
        return "the " + reference.role + " it names, " + reference.name + ", " + problem;
    }
  }
  return {};
}

}  // namespace openplx::mjcf
