// `package://P/rest` mesh names (ROS): which package, and the path inside it. Shared by the URDF import
// (which looks for P beside the URDF) and the resolved system (which honours a model's Urdf.PackagePath).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace openplx::frontend {

struct PackageUri {
  std::string package;
  std::string inside;  // may be empty
};

inline std::optional<PackageUri> parse_package_uri(std::string_view uri) {
  constexpr std::string_view kScheme = "package://";
  if (uri.substr(0, kScheme.size()) != kScheme) return std::nullopt;
  const std::string_view rest = uri.substr(kScheme.size());
  const size_t slash = rest.find('/');
  return PackageUri{std::string(rest.substr(0, slash)),
                    slash == std::string_view::npos ? std::string() : std::string(rest.substr(slash + 1))};
}

}  // namespace openplx::frontend
