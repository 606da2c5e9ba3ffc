// The parser, expressions (declarations are parsed in parser.cpp; the class is in parser_class.h).
#include <charconv>
#include <string>

#include "frontend/syntax/parser_class.h"

namespace openplx::frontend::parsing {

// ---- expressions: postfix binds tightest, then unary `-`, then `* /`, then `+ -`; all left-associative.

ExprId Parser::parse_expr() {
  const uint32_t begin = cur().begin;
  if (!enter_nesting(token_range(cur()))) {
    leave_nesting();
    // Skip to the end of the logical line so the callers unwind without further messages.
    while (!at(TokenKind::Newline) && !at(TokenKind::EndOfFile)) advance();
    return error_expr(begin);
  }
  ExprId result = parse_additive();
  leave_nesting();
  return result;
}

ExprId Parser::binary(char op, ExprId lhs, ExprId rhs) {
  Expr e;
  e.kind = ExprKind::Binary;
  e.op = op;
  e.range = {file_id_, doc_.expr(lhs).range.begin, doc_.expr(rhs).range.end};
  return add_expr_with(std::move(e), {lhs, rhs});
}

ExprId Parser::parse_additive() {
  ExprId lhs = parse_multiplicative();
  while (!panic_ && (at(TokenKind::Plus) || at(TokenKind::Minus))) {
    const char op = at(TokenKind::Plus) ? '+' : '-';
    advance();
    lhs = binary(op, lhs, parse_multiplicative());
  }
  return lhs;
}

ExprId Parser::parse_multiplicative() {
  ExprId lhs = parse_unary();
  while (!panic_ && (at(TokenKind::Star) || at(TokenKind::Slash))) {
    const char op = at(TokenKind::Star) ? '*' : '/';
    advance();
    lhs = binary(op, lhs, parse_unary());
  }
  return lhs;
}

ExprId Parser::parse_unary() {
  if (!at(TokenKind::Minus)) return parse_postfix();
  const uint32_t begin = cur().begin;
  advance();
  if (!enter_nesting(range_from(begin))) {
    leave_nesting();
    while (!at(TokenKind::Newline) && !at(TokenKind::EndOfFile)) advance();
    return error_expr(begin);
  }
  ExprId operand = parse_unary();
  leave_nesting();
  Expr e;
  e.kind = ExprKind::Unary;
  e.op = '-';
  e.range = {file_id_, begin, doc_.expr(operand).range.end};
  return add_expr_with(std::move(e), {operand});
}

ExprId Parser::parse_call(ExprId callee) {
  const uint32_t begin = doc_.expr(callee).range.begin;
  const size_t first = scratch_.size();
  scratch_.push_back(callee);
  advance();  // `(`
  if (!at(TokenKind::RParen)) {
    do {
      ExprId arg = parse_expr();
      scratch_.push_back(arg);
    } while (!panic_ && accept(TokenKind::Comma));
  }
  if (!panic_) expect(TokenKind::RParen, "`,` or `)` in the argument list");
  Expr e;
  e.kind = ExprKind::Call;
  e.range = range_from(begin);
  return add_expr(std::move(e), first);
}

ExprId Parser::parse_postfix() {
  ExprId result = parse_primary();
  while (!panic_) {
    if (at(TokenKind::Dot)) {
      advance();
      if (!at_name()) {
        error_here("a member name after `.`");
        return error_expr(doc_.expr(result).range.begin);
      }
      Ident name = parse_ident();
      Expr e;
      e.kind = ExprKind::Member;
      e.text = name.text;
      e.quoted = name.quoted;
      e.range = {file_id_, doc_.expr(result).range.begin, name.range.end};
      result = add_expr_with(std::move(e), {result});
    } else if (at(TokenKind::LParen) &&
               (doc_.expr(result).kind == ExprKind::Name || doc_.expr(result).kind == ExprKind::Member)) {
      result = parse_call(result);
    } else if (at(TokenKind::LBracket) && cur().begin == doc_.expr(result).range.end) {
      // `links[0]`: indexing, written directly after its operand (a `[` after a space starts no index).
      advance();
      ExprId index = parse_expr();
      if (!panic_) expect(TokenKind::RBracket, "`]` after the index");
      Expr e;
      e.kind = ExprKind::Index;
      e.range = range_from(doc_.expr(result).range.begin);
      result = add_expr_with(std::move(e), {result, index});
    } else {
      return result;
    }
  }
  return result;
}

ExprId Parser::parse_primary() {
  const uint32_t begin = cur().begin;
  switch (kind()) {
    case TokenKind::Int:
    case TokenKind::Real:
    case TokenKind::String:
    case TokenKind::MultilineString:
    case TokenKind::PathString:
    case TokenKind::KwTrue:
    case TokenKind::KwFalse:
      return parse_literal();
    case TokenKind::DollarPathString:
      error(DiagCode::DollarPathOutsideImport, token_range(cur()),
            "`$\"...\"` paths are only allowed in `import`; write @\"...\"");
      advance();
      return error_expr(begin);
    case TokenKind::KwThis: {
      advance();
      Expr e;
      e.kind = ExprKind::This;
      e.range = range_from(begin);
      return add_expr(std::move(e));
    }
    case TokenKind::Identifier:
    case TokenKind::QuotedIdentifier: {
      Ident name = parse_ident();
      Expr e;
      e.kind = ExprKind::Name;
      e.text = name.text;
      e.quoted = name.quoted;
      e.range = name.range;
      return add_expr(std::move(e));
    }
    case TokenKind::LParen: {
      advance();
      ExprId inner = parse_expr();
      if (!panic_) expect(TokenKind::RParen, "`)`");
      // The parentheses belong to the expression as written, so ranges built from it cover them.
      if (!panic_) doc_.exprs[inner].range = range_from(begin);
      return inner;
    }
    case TokenKind::LBracket:
      return parse_list(ExprKind::Array, TokenKind::RBracket, "`,` or `]`");
    case TokenKind::LBrace:
      return parse_list(ExprKind::Initializer, TokenKind::RBrace, "`,` or `}`");
    default:
      error_here("an expression");
      return error_expr(begin);
  }
}

ExprId Parser::parse_list(ExprKind list_kind, TokenKind close, std::string_view close_text) {
  const uint32_t begin = cur().begin;
  advance();  // opening bracket
  Expr e;
  e.kind = list_kind;
  const size_t first = scratch_.size();
  if (!at(close)) {
    do {
      ExprId element = parse_expr();
      scratch_.push_back(element);
    } while (!panic_ && accept(TokenKind::Comma));
  }
  if (!panic_) expect(close, close_text);
  e.range = range_from(begin);
  return add_expr(std::move(e), first);
}

ExprId Parser::parse_literal() {
  const Token& t = cur();
  Expr e;
  e.kind = ExprKind::Int;
  e.range = token_range(t);
  e.text = text(t);
  switch (t.kind) {
    case TokenKind::Int: {
      int64_t value = 0;
      auto [ptr, ec] = std::from_chars(e.text.data(), e.text.data() + e.text.size(), value);
      if (ec == std::errc() && ptr == e.text.data() + e.text.size()) e.int_value = value;
      // Too long for Int: also read as a Real, in case the attribute wants one (sema decides).
      auto as_real = std::from_chars(e.text.data(), e.text.data() + e.text.size(), e.real_value);
      if (!e.int_value && as_real.ec == std::errc::result_out_of_range) {
        sink_.report(
            DiagCode::NumberOutOfRange, e.range,
            "number `" + std::string(e.text.substr(0, 20)) + "...` is out of the range of a 64-bit float");
      }
      break;
    }
    case TokenKind::Real: {
      e.kind = ExprKind::Real;
      auto result = std::from_chars(e.text.data(), e.text.data() + e.text.size(), e.real_value);
      if (result.ec == std::errc::result_out_of_range) {
        // Too small rounds to zero, as in every IEEE parser; too large has no value to round to.
        if (e.text.find("e-") != std::string_view::npos || e.text.find("E-") != std::string_view::npos) {
          e.real_value = 0.0;
        } else {
          sink_.report(DiagCode::NumberOutOfRange, e.range,
                       "real number `" + std::string(e.text) + "` is out of the range of a 64-bit float");
        }
      }
      break;
    }
    case TokenKind::KwTrue:
    case TokenKind::KwFalse:
      e.kind = ExprKind::Bool;
      e.bool_value = t.kind == TokenKind::KwTrue;
      break;
    case TokenKind::PathString:
    case TokenKind::DollarPathString:
      e.kind = ExprKind::PathString;
      e.quoted = t.kind == TokenKind::DollarPathString;
      e.string_value = decode_string(t.kind, e.text);
      break;
    default:
      e.kind = ExprKind::String;
      e.multiline = t.kind == TokenKind::MultilineString;
      e.string_value = decode_string(t.kind, e.text);
      break;
  }
  advance();
  return add_expr(std::move(e));
}

}  // namespace openplx::frontend::parsing
