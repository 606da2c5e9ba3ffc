// Names of the 0.17.8 API generation that still load, each mapped to its current name. Using one gives a
// `deprecated-name` warning that names the replacement (an error under --strict).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace openplx::frontend {

// Namespaces that no longer exist, with the current qualified name of each model they held:
// "Physics3D.Charges" + "MateConnector" -> "Physics3D.Interactions.MateConnector".
std::optional<std::string> renamed_model(std::string_view old_namespace, std::string_view name);
std::vector<std::string_view> renamed_namespaces();  // "Physics.Charges", "Physics1D.Charges", ...

// 0.17.8 attribute names: "charges" -> "connectors" (interactions), and back.
std::optional<std::string_view> renamed_attribute(std::string_view name);
std::optional<std::string_view> legacy_attribute(std::string_view current);

// Pre-0.10 camelCase methods: "Math.Quat.angleAxis" -> "Math.Quat.angle_axis".
std::optional<std::string_view> renamed_method(std::string_view qualified);

}  // namespace openplx::frontend
