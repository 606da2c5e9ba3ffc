// Tokens of the OpenPLX lexical grammar (../shared/spec/openplx-language.md §2). A token is a kind and a
// byte range; its text is a view into the SourceFile, so lexing allocates nothing per token.
#pragma once

#include <cstdint>
#include <string_view>

#include "frontend/diagnostics/source.h"

namespace openplx::frontend {

enum class TokenKind : uint8_t {
  // Layout
  Newline,
  Indent,
  Dedent,
  EndOfFile,
  // Names and literals
  Identifier,        // plain `name`
  QuotedIdentifier,  // `a.b` written in backticks; the range covers the backticks
  Int,
  Real,
  String,            // "..."
  MultilineString,   // """..."""
  PathString,        // @"..."
  DollarPathString,  // $"..." (imports only)
  // Keywords
  KwIs,
  KwBecomes,
  KwWith,
  KwTrait,
  KwConst,
  KwImport,
  KwFn,
  KwStatic,
  KwOperator,
  KwThis,
  KwTrue,
  KwFalse,
  KwOr,
  KwOptional,
  // Punctuation
  Colon,
  Dot,
  Comma,
  LParen,
  RParen,
  LBracket,
  RBracket,
  LBrace,
  RBrace,
  Arrow,
  Plus,
  Minus,
  Star,
  Slash,
  // Text the lexer could not make sense of; already reported.
  Error,
};

struct Token {
  TokenKind kind;
  uint32_t begin;
  uint32_t end;
};

std::string_view token_kind_name(TokenKind kind);
// How a token kind reads in a message: "`:`", "identifier", "end of line".
std::string_view token_kind_description(TokenKind kind);

}  // namespace openplx::frontend
