// The C interface between the front end and the URDF importer module (libopenplx_urdf.so). The module
// carries urdfdom, tinyxml2 and console_bridge, which only a URDF import needs: loading them at every start
// cost more than a small model's whole evaluation. Only C types cross, because the converter carries its own
// C++ library while the module uses the system's.
#pragma once

#include <cstddef>
#include <cstdint>

extern "C" {

// Receives the import's results; `context` is the caller's. Strings are (pointer, size), valid only during
// the call.
struct OpenplxUrdfSink {
  void* context;
  void (*text)(void* context, const char* data, size_t size);  // the generated OpenPLX (absent: rejected)
  void (*line_origins)(void* context, const uint32_t* offsets, size_t count);
  void (*finding)(void* context, int error, uint32_t offset, const char* message, size_t size);
  void (*note)(void* context, const char* data, size_t size);  // belongs to the last finding
  void (*robot_name)(void* context, const char* data, size_t size);
};

// `options`: OPENPLX_URDF_PACKAGES_FINAL when no Urdf.PackagePath can name a package later (a URDF given
// directly), so a `package://` package found nowhere is reported at its <mesh>.
#define OPENPLX_URDF_PACKAGES_FINAL 1u

// Returns 0, or 1 when the importer failed inside (its message is then a finding at offset 0).
typedef int (*OpenplxUrdfImportFunction)(const char* path, const char* urdf_text, size_t urdf_size,
                                         const char* model_name, unsigned options,
                                         const OpenplxUrdfSink* sink);

}  // extern "C"

// The entry point's name; a changed interface gets a new name, so a stale module cannot be misread.
#define OPENPLX_URDF_IMPORT_SYMBOL "openplx_urdf_import_v2"
