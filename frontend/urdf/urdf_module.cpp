// The entry point of the URDF importer module: runs convert_urdf and hands its results over in C types.
#include <exception>
#include <string>

#include "frontend/urdf/urdf_import.h"
#include "frontend/urdf/urdf_module_abi.h"

namespace {

void send(void (*to)(void*, const char*, size_t), void* context, const std::string& s) {
  to(context, s.data(), s.size());
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int openplx_urdf_import_v2(
    const char* path, const char* urdf_text, size_t urdf_size, const char* model_name, unsigned options,
    const OpenplxUrdfSink* sink) {
  using openplx::frontend::UrdfFinding;
  try {
    const openplx::frontend::UrdfImport result = openplx::frontend::convert_urdf(
        path, std::string(urdf_text, urdf_size), model_name, {(options & OPENPLX_URDF_PACKAGES_FINAL) != 0});
    for (const UrdfFinding& f : result.findings) {
      sink->finding(sink->context, f.error, f.offset, f.message.data(), f.message.size());
      for (const std::string& note : f.notes) send(sink->note, sink->context, note);
    }
    send(sink->robot_name, sink->context, result.robot_name);
    sink->line_origins(sink->context, result.line_origins.data(), result.line_origins.size());
    if (result.text) send(sink->text, sink->context, *result.text);
    return 0;
  } catch (const std::exception& e) {  // exceptions must not cross into another C++ library
    const std::string message = std::string("the URDF importer failed: ") + e.what();
    sink->finding(sink->context, 1, 0, message.data(), message.size());
  } catch (...) {
    const std::string message = "the URDF importer failed";
    sink->finding(sink->context, 1, 0, message.data(), message.size());
  }
  return 1;
}
