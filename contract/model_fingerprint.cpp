#include "contract/model_fingerprint.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <vector>

namespace openplx::mjcf {

bool strip_prefix(std::string_view name, std::string_view prefix, std::string_view& out) {
  if (name.empty() || name.substr(0, prefix.size()) != prefix) return false;
  out = name.substr(prefix.size());
  return true;
}

void FingerprintLines::body(std::string_view name, std::string_view parent) {
  lines.push_back("body " + std::string(name) + " " + std::string(parent));
  ++bodies;
}

void FingerprintLines::joint(std::string_view name, std::string_view type, std::string_view body) {
  lines.push_back("joint " + std::string(name) + " " + std::string(type) + " " + std::string(body));
  ++joints;
}

Fingerprint FingerprintLines::finish() {
  std::sort(lines.begin(), lines.end());
  uint64_t h = 1469598103934665603ull;  // FNV-1a, 64 bits
  for (const std::string& line : lines) {
    for (unsigned char c : line) h = (h ^ c) * 1099511628211ull;
    h = (h ^ '\n') * 1099511628211ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(h));
  return {bodies, joints, hex};
}

namespace {

const char* joint_type(int type) {
  switch (type) {
    case mjJNT_FREE:
      return "free";
    case mjJNT_BALL:
      return "ball";
    case mjJNT_SLIDE:
      return "slide";
    default:
      return "hinge";
  }
}

}  // namespace

std::string Fingerprint::text() const {
  return "v1 bodies=" + std::to_string(bodies) + " joints=" + std::to_string(joints) + " hash=" + hash;
}

bool Fingerprint::parse(std::string_view text, Fingerprint& out) {
  int bodies = 0, joints = 0;
  char hash[17] = "";
  const std::string copy(text);
  int used = 0;
  if (std::sscanf(copy.c_str(), "v1 bodies=%d joints=%d hash=%16[0-9a-f]%n", &bodies, &joints, hash, &used) !=
          3 ||
      static_cast<size_t>(used) != copy.size() || std::string_view(hash).size() != 16 || bodies < 0 ||
      joints < 0)
    return false;
  out = {bodies, joints, hash};
  return true;
}

Fingerprint model_fingerprint(const mjModel* m, std::string_view prefix, const std::vector<bool>* bodies) {
  FingerprintLines out;
  auto kept = [&](int body) {
    return !bodies || (static_cast<size_t>(body) < bodies->size() && (*bodies)[body]);
  };
  auto name_of = [&](const int* address, int id, std::string_view& stripped) {
    if (address == m->name_bodyadr && !kept(id)) return false;
    return strip_prefix(m->names + address[id], prefix, stripped);
  };
  for (int b = 1; b < m->nbody; ++b) {
    std::string_view name, parent;
    if (!name_of(m->name_bodyadr, b, name)) continue;
    const int p = m->body_parentid[b];
    if (p == 0 || !name_of(m->name_bodyadr, p, parent)) parent = "-";
    out.body(name, parent);
  }
  for (int j = 0; j < m->njnt; ++j) {
    std::string_view name, body;
    if (!name_of(m->name_jntadr, j, name) || !name_of(m->name_bodyadr, m->jnt_bodyid[j], body)) continue;
    out.joint(name, joint_type(m->jnt_type[j]), body);
  }
  return out.finish();
}

}  // namespace openplx::mjcf
