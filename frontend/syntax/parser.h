// Parser: tokens to a Document (../shared/spec/openplx-language.md §3).
//
// Recursive descent with one token of lookahead. Errors are reported to the sink and the parser resumes at
// the next line of the same block, so one run reports every syntax error of a file. Nesting of blocks and
// expressions is limited to kMaxNesting levels (a `nesting-too-deep` error), which bounds the recursion of
// the parser and of every later pass that walks the tree.
#pragma once

#include <vector>

#include "frontend/diagnostics/diagnostics.h"
#include "frontend/diagnostics/source.h"
#include "frontend/syntax/ast.h"
#include "frontend/syntax/token.h"

namespace openplx::frontend {

inline constexpr int kMaxNesting = 200;

Document parse(const SourceFile& file, FileId file_id, const std::vector<Token>& tokens,
               DiagnosticSink& sink);

// Lexes and parses one file already in `sources`.
Document parse_file(const SourceManager& sources, FileId file_id, DiagnosticSink& sink);

}  // namespace openplx::frontend
