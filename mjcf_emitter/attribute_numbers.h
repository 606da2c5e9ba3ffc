// Reading back numbers the emitter has already written into an element (passes that run over the finished
// document: placement.cpp, viewer_defaults.cpp).
#pragma once

#include <Eigen/Geometry>
#include <charconv>
#include <optional>
#include <string>
#include <vector>

#include "mjcf_emitter/xml.h"

namespace openplx::mjcf {

// The space-separated numbers of `key` ("0 0 1.5"); empty when the attribute is missing or not numbers.
inline std::vector<double> attribute_numbers(const Element& e, std::string_view key) {
  std::vector<double> values;
  const std::string* text = e.get(key);
  if (!text) return values;
  const char* at = text->data();
  const char* end = at + text->size();
  while (at < end) {
    while (at < end && (*at == ' ' || *at == ',')) ++at;
    if (at == end) break;
    double v = 0;
    auto [next, ec] = std::from_chars(at, end, v);
    if (ec != std::errc()) return {};
    values.push_back(v);
    at = next;
  }
  return values;
}

inline std::optional<Eigen::Vector3d> attribute_vector(const Element& e, std::string_view key) {
  const std::vector<double> v = attribute_numbers(e, key);
  if (v.size() != 3) return std::nullopt;
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

// MJCF's quat="w x y z"; identity when missing.
inline Eigen::Quaterniond attribute_quat(const Element& e, std::string_view key = "quat") {
  const std::vector<double> v = attribute_numbers(e, key);
  if (v.size() != 4) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(v[0], v[1], v[2], v[3]).normalized();
}

}  // namespace openplx::mjcf
