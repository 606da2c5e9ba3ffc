// The parser, declarations: files, imports, models, traits, operators, members, annotations, methods, names
// and types. Expressions are parsed in parse_expressions.cpp; the class is in parser_class.h.
#include "frontend/syntax/parser.h"

#include <string>

#include "frontend/syntax/lexer.h"
#include "frontend/syntax/parser_class.h"

namespace openplx::frontend {
namespace parsing {

Document Parser::run() {
  doc_.exprs.reserve(tokens_.size() / 3);
  doc_.operand_pool.reserve(tokens_.size() / 4);
  // Each pooled ident, type reference and trait name consumes at least one identifier token, so these
  // capacities are never exceeded and the spans taken into the pools stay valid.
  size_t names = 1;
  for (const Token& t : tokens_) {
    names += t.kind == TokenKind::Identifier || t.kind == TokenKind::QuotedIdentifier;
  }
  doc_.ident_pool.reserve(names);
  doc_.type_ref_pool.reserve(names);
  doc_.name_pool.reserve(names);
  while (!at(TokenKind::EndOfFile)) {
    switch (kind()) {
      case TokenKind::Newline:
      case TokenKind::Dedent:
        advance();
        continue;
      case TokenKind::Indent:
        error(DiagCode::UnexpectedToken, token_range(cur()),
              "unexpected indentation: top-level declarations start in column 1");
        skip_block();
        panic_ = false;
        continue;
      default:
        parse_top_decl();
    }
  }
  for (size_t i = 0; i < doc_.exprs.size(); ++i) {
    doc_.exprs[i].operands = {doc_.operand_pool.data() + operand_spans_[i].first, operand_spans_[i].second};
  }
  return std::move(doc_);
}

void Parser::skip_block() {
  int level = 0;
  do {
    if (at(TokenKind::Indent)) ++level;
    if (at(TokenKind::Dedent)) --level;
    if (at(TokenKind::EndOfFile)) return;
    advance();
  } while (level > 0);
}

void Parser::sync_line() {
  while (!at(TokenKind::Newline) && !at(TokenKind::Dedent) && !at(TokenKind::EndOfFile)) {
    if (at(TokenKind::Indent)) {
      skip_block();
    } else {
      advance();
    }
  }
  if (accept(TokenKind::Newline) && at(TokenKind::Indent)) skip_block();  // the block of the broken line
  panic_ = false;
}

bool Parser::expect_line_end() {
  if (accept(TokenKind::Newline) || at(TokenKind::EndOfFile) || at(TokenKind::Dedent)) return true;
  error_here("end of line");
  return false;
}

void Parser::parse_top_decl() {
  switch (kind()) {
    case TokenKind::KwImport:
      parse_import();
      break;
    case TokenKind::KwTrait:
      parse_trait();
      break;
    case TokenKind::KwOperator:
      parse_operator();
      break;
    case TokenKind::KwConst:
    case TokenKind::Identifier:
    case TokenKind::QuotedIdentifier:
      parse_model_or_global();
      break;
    case TokenKind::KwFn:
    case TokenKind::KwStatic:
    case TokenKind::KwWith:
    case TokenKind::KwOptional:
    case TokenKind::Dot:
      error(DiagCode::MisplacedDeclaration, token_range(cur()),
            "`" + std::string(text(cur())) + "` is only allowed inside a model or trait body");
      break;
    default:
      error_here("a model, trait, import, operator or global attribute declaration");
  }
  if (panic_) sync_line();
}

void Parser::parse_import() {
  Decl decl;
  decl.kind = DeclKind::Import;
  const uint32_t begin = cur().begin;
  advance();
  if (!at(TokenKind::PathString) && !at(TokenKind::DollarPathString)) {
    error_here("a path string such as @\"model.urdf\" after `import`");
    return;
  }
  decl.value = parse_literal();
  if (at(TokenKind::Identifier) && text(cur()) == "as") {
    advance();
    if (!at_name()) {
      error_here("a name after `as`");
      return;
    }
    decl.alias = parse_qualified_name();
  }
  decl.range = range_from(begin);
  if (!expect_line_end()) return;
  doc_.decls.push_back(std::move(decl));
}

void Parser::parse_trait() {
  Decl decl;
  decl.kind = DeclKind::Trait;
  const uint32_t begin = cur().begin;
  advance();
  if (!at_name()) {
    error_here("a trait name");
    return;
  }
  decl.name = parse_ident();
  if (accept(TokenKind::KwIs)) {
    if (!at_name()) {
      error_here("the name of the trait it extends");
      return;
    }
    decl.base = parse_qualified_name();
  }
  if (at(TokenKind::KwWith)) {
    error(DiagCode::MisplacedDeclaration, token_range(cur()), "a trait cannot use `with`");
    return;
  }
  const uint32_t colon = here().begin;
  const bool colon_seen = accept(TokenKind::Colon);
  if (!parse_decl_body(decl, colon_seen, colon)) return;
  decl.range = range_from(begin);
  doc_.decls.push_back(std::move(decl));
}

void Parser::parse_operator() {
  Decl decl;
  decl.kind = DeclKind::Operator;
  const uint32_t begin = cur().begin;
  advance();
  switch (kind()) {
    case TokenKind::Plus:
      decl.op = '+';
      break;
    case TokenKind::Minus:
      decl.op = '-';
      break;
    case TokenKind::Star:
      decl.op = '*';
      break;
    case TokenKind::Slash:
      decl.op = '/';
      break;
    default:
      error_here("one of `+`, `-`, `*`, `/` after `operator`");
      return;
  }
  advance();
  if (!expect(TokenKind::LParen, "`(`")) return;
  decl.params = parse_params();
  if (panic_ || !expect(TokenKind::RParen, "`)`")) return;
  if (accept(TokenKind::Arrow)) decl.return_type = parse_type_ref();
  if (panic_) return;
  decl.range = range_from(begin);
  if (!expect_line_end()) return;
  doc_.decls.push_back(std::move(decl));
}

void Parser::parse_model_or_global() {
  Decl decl;
  decl.kind = DeclKind::Model;
  const uint32_t begin = cur().begin;
  const Token const_token = cur();
  decl.is_const = accept(TokenKind::KwConst);
  if (!at_name()) {
    error_here(decl.is_const ? "a model name after `const`" : "a declaration");
    return;
  }
  decl.name = parse_ident();
  if (accept(TokenKind::KwIs)) {
    TypeExpr type = parse_type_expr();
    if (panic_) return;
    const uint32_t colon = here().begin;
    if (accept(TokenKind::Colon) && !at(TokenKind::Newline) && !at(TokenKind::EndOfFile)) {
      // `Name is T: expression` on one line: a global attribute.
      if (decl.is_const) {
        error(DiagCode::MisplacedDeclaration, token_range(const_token),
              "`const` applies to models, not to the global attribute `" + std::string(decl.name.text) + "`");
        return;
      }
      decl.kind = DeclKind::GlobalAttribute;
      decl.type = std::move(type);
      decl.value = parse_expr();
      if (panic_) return;
      decl.range = range_from(begin);
      if (!expect_line_end()) return;
      doc_.decls.push_back(std::move(decl));
      return;
    }
    const bool colon_seen = pos_ > 0 && tokens_[pos_ - 1].kind == TokenKind::Colon;
    if (type.alternatives.size() != 1 || type.alternatives[0].is_array) {
      error(DiagCode::InvalidModelBase, type.range,
            "a model extends exactly one model; `or` and `[]` belong in attribute types");
      return;
    }
    decl.base = type.alternatives[0].name;
    decl.traits = type.traits;
    if (!parse_decl_body(decl, colon_seen, colon)) return;
  } else {
    const uint32_t colon = here().begin;
    const bool colon_seen = accept(TokenKind::Colon);
    if (!colon_seen && !at(TokenKind::Newline) && !at(TokenKind::EndOfFile)) {
      error(DiagCode::ExpectedIs, here(), "Expected an is keyword");
      return;
    }
    if (!parse_decl_body(decl, colon_seen, colon)) return;
  }
  decl.range = range_from(begin);
  doc_.decls.push_back(std::move(decl));
}

bool Parser::parse_decl_body(Decl& decl, bool colon_seen, uint32_t colon_begin) {
  if (!expect_line_end()) return false;
  if (at(TokenKind::Indent)) {
    if (!colon_seen) {
      sink_.report(DiagCode::MissingColon, {file_id_, colon_begin, colon_begin},
                   "missing `:` after the declaration of `" + std::string(decl.name.text) +
                       "`; the indented block below is taken as its body");
    }
    decl.has_body = true;
    parse_block(decl.body, BlockContext::Body);
    return true;
  }
  if (colon_seen) {
    error(DiagCode::ExpectedIndentedBlock, {file_id_, colon_begin, colon_begin + 1},
          "Expected indented block");
    panic_ = false;
    return false;
  }
  return true;
}

void Parser::parse_block(std::vector<Member>& out, BlockContext context) {
  const Token indent = cur();
  if (!enter_nesting(token_range(indent))) {
    skip_block();
    leave_nesting();
    panic_ = false;
    return;
  }
  advance();  // INDENT
  while (!at(TokenKind::Dedent) && !at(TokenKind::EndOfFile)) {
    if (accept(TokenKind::Newline)) continue;
    if (at(TokenKind::Indent)) {
      // A line deeper than its block after a member that opened none (seen in official bundles): keep it
      // in this block.
      sink_.report(DiagCode::UnexpectedIndent, token_range(cur()),
                   "line is indented deeper than its block but the line before opens no block; "
                   "taken as part of the enclosing block");
      parse_block(out, context);
      continue;
    }
    parse_member(out, context);
    if (panic_) sync_line();
  }
  accept(TokenKind::Dedent);
  leave_nesting();
}

void Parser::parse_member(std::vector<Member>& out, BlockContext context) {
  const uint32_t begin = cur().begin;
  switch (kind()) {
    case TokenKind::Dot:
      parse_annotation(out);
      return;
    case TokenKind::KwWith: {
      advance();
      if (!at_name()) {
        error_here("a trait name after `with`");
        return;
      }
      Member member;
      member.kind = MemberKind::TraitUse;
      member.path = parse_qualified_name();
      member.range = range_from(begin);
      if (!expect_line_end()) return;
      out.push_back(std::move(member));
      return;
    }
    case TokenKind::KwStatic:
    case TokenKind::KwFn:
      parse_method(out, context);
      return;
    case TokenKind::KwOperator:
    case TokenKind::KwImport:
    case TokenKind::KwTrait:
    case TokenKind::KwConst:
      error(DiagCode::MisplacedDeclaration, token_range(cur()),
            "`" + std::string(text(cur())) + "` declarations are only allowed at the top level");
      return;
    default:
      break;
  }
  Member member;
  member.kind = MemberKind::Attribute;
  member.is_optional = accept(TokenKind::KwOptional);
  if (!at_name()) {
    error_here(member.is_optional ? "an attribute name after `optional`" : "a member declaration");
    return;
  }
  member.path = parse_qualified_name();
  if (panic_) return;
  if (accept(TokenKind::KwIs)) {
    member.kind = MemberKind::Attribute;
    member.type = parse_type_expr();
    if (panic_) return;
    // `reference`: the attribute refers to an instance made elsewhere (a contextual word, not reserved).
    if (at(TokenKind::Identifier) && text(cur()) == "reference") {
      advance();
      member.is_reference = true;
    }
    parse_member_tail(member, true);
    if (panic_) return;
    if (member.path.parts.size() > 1) {
      // `marshalling.angle is RealField`: declares `angle` inside `marshalling`, as the nested block
      // `marshalling:` / `angle is RealField` would.
      member.range = range_from(begin);
      Member inner = std::move(member);
      const QualifiedName path = inner.path;
      inner.path = {path.parts.subspan(path.parts.size() - 1), path.parts.back().range};
      for (size_t k = path.parts.size() - 1; k-- > 0;) {
        Member outer;
        outer.kind = MemberKind::Assignment;
        outer.range = inner.range;
        outer.path = {path.parts.subspan(k, 1), path.parts[k].range};
        outer.has_block = true;
        outer.block.push_back(std::move(inner));
        inner = std::move(outer);
      }
      out.push_back(std::move(inner));
      return;
    }
  } else if (member.is_optional) {
    error_here("`is` after the optional attribute's name");
    return;
  } else if (accept(TokenKind::KwBecomes)) {
    member.kind = MemberKind::Becomes;
    member.type = parse_type_expr();
    if (panic_) return;
    parse_member_tail(member, true);
  } else if (at(TokenKind::Colon)) {
    member.kind = MemberKind::Assignment;
    parse_member_tail(member, false);
  } else {
    error(DiagCode::ExpectedIs, here(), "Expected an is keyword");
    return;
  }
  if (panic_) return;
  member.range = range_from(begin);
  out.push_back(std::move(member));
}

void Parser::parse_member_tail(Member& member, bool allow_plain_end) {
  if (at(TokenKind::Colon)) {
    const Token colon = cur();
    advance();
    if (at(TokenKind::Newline) || at(TokenKind::EndOfFile) || at(TokenKind::Dedent)) {
      accept(TokenKind::Newline);
      if (!at(TokenKind::Indent)) {
        error(DiagCode::ExpectedIndentedBlock, token_range(colon), "Expected indented block");
        panic_ = false;  // the line itself is complete; keep the member and go on with the next line
        return;
      }
      member.has_block = true;
      parse_block(member.block, BlockContext::Nested);
      return;
    }
    member.value = parse_expr();
    if (panic_) return;
    expect_line_end();
    return;
  }
  if (!allow_plain_end) {
    error_here("`:`");
    return;
  }
  const uint32_t missing_colon = here().begin;
  if (!expect_line_end()) return;
  if (at(TokenKind::Indent)) {
    sink_.report(DiagCode::MissingColon, {file_id_, missing_colon, missing_colon},
                 "missing `:` after `" + std::string(member.path.parts.back().text) +
                     "`; the indented block below is taken as its block");
    member.has_block = true;
    parse_block(member.block, BlockContext::Nested);
  }
}

void Parser::parse_annotation(std::vector<Member>& out) {
  const uint32_t begin = cur().begin;
  advance();  // `.`
  Member member;
  member.kind = MemberKind::Annotation;
  if (!at_name()) {
    error_here("an annotation name after `.`");
    return;
  }
  member.path = parse_single_name();
  if (!expect(TokenKind::Colon, "`:` after the annotation name")) return;
  const ExprId value = parse_expr();
  if (panic_) return;
  const Expr& e = doc_.expr(value);
  const Expr* literal = &e;
  if (e.kind == ExprKind::Unary && e.op == '-') literal = &doc_.expr(operand(value, 0));
  const bool numeric = literal->kind == ExprKind::Int || literal->kind == ExprKind::Real;
  const bool constant =
      literal == &e ? (numeric || e.kind == ExprKind::String || e.kind == ExprKind::Bool) : numeric;
  if (!constant) {
    error(DiagCode::AnnotationNotConstant, e.range,
          "annotation value must be a constant: a string, a number, `true` or `false`");
    return;
  }
  member.value = value;
  member.range = range_from(begin);
  if (!expect_line_end()) return;
  out.push_back(std::move(member));
}

void Parser::parse_method(std::vector<Member>& out, BlockContext context) {
  const uint32_t begin = cur().begin;
  Member member;
  member.kind = MemberKind::Method;
  member.is_static = accept(TokenKind::KwStatic);
  if (!expect(TokenKind::KwFn, "`fn` after `static`")) return;
  if (context == BlockContext::Nested) {
    error(DiagCode::MisplacedDeclaration, range_from(begin),
          "methods are declared in model and trait bodies, not in an attribute's block");
    return;
  }
  if (!at_name()) {
    error_here("a method name after `fn`");
    return;
  }
  member.path = parse_single_name();
  if (!expect(TokenKind::LParen, "`(`")) return;
  member.params = parse_params();
  if (panic_ || !expect(TokenKind::RParen, "`)`")) return;
  if (accept(TokenKind::Arrow)) member.return_type = parse_type_ref();
  if (panic_) return;
  member.range = range_from(begin);
  if (!expect_line_end()) return;
  out.push_back(std::move(member));
}

Ident Parser::parse_ident() {
  const Token& t = cur();
  Ident ident;
  ident.range = token_range(t);
  ident.quoted = t.kind == TokenKind::QuotedIdentifier;
  ident.text = ident.quoted ? file_.text().substr(t.begin + 1, t.end - t.begin - 2) : text(t);
  advance();
  return ident;
}

QualifiedName Parser::parse_single_name() {
  const size_t first = doc_.ident_pool.size();
  doc_.ident_pool.push_back(parse_ident());
  return {{doc_.ident_pool.data() + first, 1}, doc_.ident_pool.back().range};
}

QualifiedName Parser::parse_qualified_name() {
  const size_t first = doc_.ident_pool.size();
  const uint32_t begin = cur().begin;
  doc_.ident_pool.push_back(parse_ident());
  while (at(TokenKind::Dot) &&
         (peek_token().kind == TokenKind::Identifier || peek_token().kind == TokenKind::QuotedIdentifier)) {
    advance();
    doc_.ident_pool.push_back(parse_ident());
  }
  QualifiedName name{{doc_.ident_pool.data() + first, doc_.ident_pool.size() - first}, range_from(begin)};
  if (at(TokenKind::Dot)) {
    advance();
    error_here("a name after `.`");
  }
  return name;
}

TypeRef Parser::parse_type_ref() {
  TypeRef ref;
  const uint32_t begin = cur().begin;
  if (!at_name()) {
    error_here("a type name");
    return ref;
  }
  ref.name = parse_qualified_name();
  if (at(TokenKind::LBracket) && peek_token().kind == TokenKind::RBracket) {
    advance();
    advance();
    ref.is_array = true;
  }
  ref.range = range_from(begin);
  return ref;
}

TypeExpr Parser::parse_type_expr() {
  TypeExpr type;
  const uint32_t begin = cur().begin;
  std::vector<TypeRef>& refs = doc_.type_ref_pool;
  const size_t first_ref = refs.size();
  refs.push_back(parse_type_ref());
  while (!panic_ && accept(TokenKind::KwOr)) refs.push_back(parse_type_ref());
  type.alternatives = {refs.data() + first_ref, refs.size() - first_ref};
  if (!panic_ && accept(TokenKind::KwWith)) {
    std::vector<QualifiedName>& names = doc_.name_pool;
    const size_t first_name = names.size();
    do {
      if (!at_name()) {
        error_here("a trait name after `with`");
        break;
      }
      names.push_back(parse_qualified_name());
    } while (!panic_ && accept(TokenKind::Comma));
    type.traits = {names.data() + first_name, names.size() - first_name};
  }
  type.range = range_from(begin);
  return type;
}

std::vector<Param> Parser::parse_params() {
  std::vector<Param> params;
  if (at(TokenKind::RParen)) return params;
  do {
    Param param;
    const uint32_t begin = cur().begin;
    if (!at_name()) {
      error_here("a parameter name");
      return params;
    }
    param.name = parse_ident();
    if (!expect(TokenKind::Colon, "`:` after the parameter name")) return params;
    param.type = parse_type_ref();
    if (panic_) return params;
    param.range = range_from(begin);
    params.push_back(std::move(param));
  } while (accept(TokenKind::Comma));
  return params;
}

}  // namespace parsing

Document parse(const SourceFile& file, FileId file_id, const std::vector<Token>& tokens,
               DiagnosticSink& sink) {
  return parsing::Parser(file, file_id, tokens, sink).run();
}

Document parse_file(const SourceManager& sources, FileId file_id, DiagnosticSink& sink) {
  const SourceFile& file = sources.file(file_id);
  const size_t first = sink.diagnostics().size();
  std::vector<Token> tokens = lex(file, file_id, sink);
  Document doc = parse(file, file_id, tokens, sink);
  sink.sort_by_position(first);
  return doc;
}

}  // namespace openplx::frontend
