// What a URDF import gives the front end: the generated OpenPLX and the findings located in the URDF. Plain
// data with no XML types, so the loader can receive it from the importer module (urdf_importer.h).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace openplx::frontend {

// A located finding about the URDF: `offset` is a byte offset into its text.
struct UrdfFinding {
  bool error = true;
  uint32_t offset = 0;
  std::string message;
  std::vector<std::string> notes;
};

// How a URDF is imported.
struct UrdfImportOptions {
  // No Urdf.PackagePath can name a package after the import (a URDF given directly): a `package://` package
  // found nowhere is reported at its <mesh> (an error for collision, a warning and left out for a visual).
  // Otherwise the mesh is looked for beside the URDF and, missing, reported when the model is emitted.
  bool packages_final = false;
};

struct UrdfImport {
  std::optional<std::string> text;     // OpenPLX declaring the model; nullopt when the URDF is rejected
  std::vector<uint32_t> line_origins;  // per generated line: a byte offset into the URDF text
  std::vector<UrdfFinding> findings;   // errors and warnings, located in the URDF text
  std::string robot_name;              // <robot name="...">
};

}  // namespace openplx::frontend
