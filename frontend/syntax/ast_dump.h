// Deterministic text dumps for `--dump=tokens` and `--dump=ast`, used by golden tests.
//
// Tokens: one per line, `line:col KIND text`. AST: one line per declaration and member, indented two spaces
// per level, ending in its source range `@line:col-line:col`; expressions are printed fully parenthesised
// on their owner's line, so precedence is visible.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "frontend/diagnostics/source.h"
#include "frontend/syntax/ast.h"
#include "frontend/syntax/token.h"

namespace openplx::frontend {

void dump_tokens(std::ostream& out, const SourceFile& file, const std::vector<Token>& tokens);
void dump_ast(std::ostream& out, const SourceFile& file, const Document& doc);
std::string expr_to_string(const Document& doc, ExprId id);

}  // namespace openplx::frontend
