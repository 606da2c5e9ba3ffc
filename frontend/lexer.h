// Lexer: OpenPLX text to tokens, with Python-style layout tokens (spec/openplx-language.md §2).
//
// Indentation is relative: a stack of open columns; a deeper line opens one block (INDENT), a shallower
// line closes blocks (DEDENT) and must land on a column already open. Blank and comment-only lines, lines
// inside brackets and lines inside multi-line strings produce no layout tokens. Every error is reported to
// the sink and lexing goes on, so one run shows all of a file's lexical errors. The returned vector always
// ends with EndOfFile, and INDENT/DEDENT are balanced.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "frontend/diagnostics.h"
#include "frontend/source.h"
#include "frontend/token.h"

namespace openplx::frontend {

std::vector<Token> lex(const SourceFile& file, FileId file_id, DiagnosticSink& sink);

// The value of a string-like token (quotes and escapes removed). Unterminated strings decode up to the
// end of what was lexed.
std::string decode_string(TokenKind kind, std::string_view token_text);

}  // namespace openplx::frontend
