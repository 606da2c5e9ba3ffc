// The body of the lexer+parser fuzz target, shared by the libFuzzer entry point and the regression test
// that replays saved inputs in the normal test run.
#pragma once

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "frontend/diagnostics/diagnostics.h"
#include "frontend/syntax/ast_dump.h"
#include "frontend/syntax/parser.h"

namespace openplx::fuzz {

inline void lex_parse_one(const uint8_t* data, size_t size) {
  namespace fe = openplx::frontend;
  fe::SourceManager sources;
  fe::FileId id = sources.add("fuzz.openplx", std::string(reinterpret_cast<const char*>(data), size));
  fe::DiagnosticSink sink;
  fe::Document doc = fe::parse_file(sources, id, sink);
  // Exercise the consumers of the tree and of the diagnostics too: ranges and ids must stay valid.
  std::ostringstream sink_out;
  fe::dump_ast(sink_out, sources.file(id), doc);
  fe::print_diagnostics(sink_out, sources, sink.diagnostics());
  doc.last_model();
}

}  // namespace openplx::fuzz
