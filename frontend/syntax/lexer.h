// Lexer: OpenPLX text to tokens, with Python-style layout tokens (../shared/spec/openplx-language.md §2).
//
// Indentation is relative: a stack of open columns; a deeper line opens one block (INDENT), a shallower
// line closes blocks (DEDENT) and must land on a column already open. Blank and comment-only lines, lines
// inside brackets and lines inside multi-line strings produce no layout tokens. Every error is reported to
// the sink and lexing goes on, so one run shows a file's lexical errors, up to kMaxErrorsPerFile (then a
// `too-many-errors` note, and the rest of the file is not read: garbage costs time and memory bounded by
// that, not by its size). A binary file (a NUL byte among much that is not UTF-8 text) is one error at its
// first NUL and no tokens. The returned vector always ends with EndOfFile, and INDENT/DEDENT are balanced.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "frontend/diagnostics/diagnostics.h"
#include "frontend/diagnostics/source.h"
#include "frontend/syntax/token.h"

namespace openplx::frontend {

// Errors the lexer, and then the parser, report in one file before they stop reading it: as many as a
// diagnostics printout shows (print_diagnostics), so what a user sees of a broken file does not change.
inline constexpr uint32_t kMaxErrorsPerFile = 100;

std::vector<Token> lex(const SourceFile& file, FileId file_id, DiagnosticSink& sink);

// The value of a string-like token (quotes and escapes removed). Unterminated strings decode up to the
// end of what was lexed.
std::string decode_string(TokenKind kind, std::string_view token_text);

}  // namespace openplx::frontend
