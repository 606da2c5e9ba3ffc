#include "frontend/syntax/token.h"

namespace openplx::frontend {

std::string_view token_kind_name(TokenKind kind) {
  switch (kind) {
    case TokenKind::Newline:
      return "NEWLINE";
    case TokenKind::Indent:
      return "INDENT";
    case TokenKind::Dedent:
      return "DEDENT";
    case TokenKind::EndOfFile:
      return "EOF";
    case TokenKind::Identifier:
      return "IDENT";
    case TokenKind::QuotedIdentifier:
      return "QUOTED_IDENT";
    case TokenKind::Int:
      return "INT";
    case TokenKind::Real:
      return "REAL";
    case TokenKind::String:
      return "STRING";
    case TokenKind::MultilineString:
      return "MLSTRING";
    case TokenKind::PathString:
      return "PATH";
    case TokenKind::DollarPathString:
      return "DOLLAR_PATH";
    case TokenKind::KwIs:
      return "is";
    case TokenKind::KwBecomes:
      return "becomes";
    case TokenKind::KwWith:
      return "with";
    case TokenKind::KwTrait:
      return "trait";
    case TokenKind::KwConst:
      return "const";
    case TokenKind::KwImport:
      return "import";
    case TokenKind::KwFn:
      return "fn";
    case TokenKind::KwStatic:
      return "static";
    case TokenKind::KwOperator:
      return "operator";
    case TokenKind::KwThis:
      return "this";
    case TokenKind::KwTrue:
      return "true";
    case TokenKind::KwFalse:
      return "false";
    case TokenKind::KwOr:
      return "or";
    case TokenKind::KwOptional:
      return "optional";
    case TokenKind::Colon:
      return ":";
    case TokenKind::Dot:
      return ".";
    case TokenKind::Comma:
      return ",";
    case TokenKind::LParen:
      return "(";
    case TokenKind::RParen:
      return ")";
    case TokenKind::LBracket:
      return "[";
    case TokenKind::RBracket:
      return "]";
    case TokenKind::LBrace:
      return "{";
    case TokenKind::RBrace:
      return "}";
    case TokenKind::Arrow:
      return "->";
    case TokenKind::Plus:
      return "+";
    case TokenKind::Minus:
      return "-";
    case TokenKind::Star:
      return "*";
    case TokenKind::Slash:
      return "/";
    case TokenKind::Error:
      return "ERROR";
  }
  return "?";
}

std::string_view token_kind_description(TokenKind kind) {
  switch (kind) {
    case TokenKind::Newline:
      return "end of line";
    case TokenKind::Indent:
      return "indented block";
    case TokenKind::Dedent:
      return "end of block";
    case TokenKind::EndOfFile:
      return "end of file";
    case TokenKind::Identifier:
    case TokenKind::QuotedIdentifier:
      return "identifier";
    case TokenKind::Int:
      return "integer";
    case TokenKind::Real:
      return "real number";
    case TokenKind::String:
      return "string";
    case TokenKind::MultilineString:
      return "multi-line string";
    case TokenKind::PathString:
      return "path string";
    case TokenKind::DollarPathString:
      return "`$` path string";
    case TokenKind::Error:
      return "invalid text";
    default:
      break;
  }
  // Keywords and punctuation read as themselves.
  switch (kind) {
#define OPENPLX_QUOTED(k, text) \
  case TokenKind::k:            \
    return "`" text "`";
    OPENPLX_QUOTED(KwIs, "is")
    OPENPLX_QUOTED(KwBecomes, "becomes")
    OPENPLX_QUOTED(KwWith, "with")
    OPENPLX_QUOTED(KwTrait, "trait")
    OPENPLX_QUOTED(KwConst, "const")
    OPENPLX_QUOTED(KwImport, "import")
    OPENPLX_QUOTED(KwFn, "fn")
    OPENPLX_QUOTED(KwStatic, "static")
    OPENPLX_QUOTED(KwOperator, "operator")
    OPENPLX_QUOTED(KwThis, "this")
    OPENPLX_QUOTED(KwTrue, "true")
    OPENPLX_QUOTED(KwFalse, "false")
    OPENPLX_QUOTED(KwOr, "or")
    OPENPLX_QUOTED(KwOptional, "optional")
    OPENPLX_QUOTED(Colon, ":")
    OPENPLX_QUOTED(Dot, ".")
    OPENPLX_QUOTED(Comma, ",")
    OPENPLX_QUOTED(LParen, "(")
    OPENPLX_QUOTED(RParen, ")")
    OPENPLX_QUOTED(LBracket, "[")
    OPENPLX_QUOTED(RBracket, "]")
    OPENPLX_QUOTED(LBrace, "{")
    OPENPLX_QUOTED(RBrace, "}")
    OPENPLX_QUOTED(Arrow, "->")
    OPENPLX_QUOTED(Plus, "+")
    OPENPLX_QUOTED(Minus, "-")
    OPENPLX_QUOTED(Star, "*")
    OPENPLX_QUOTED(Slash, "/")
#undef OPENPLX_QUOTED
    default:
      break;
  }
  return "token";
}

}  // namespace openplx::frontend
