#include "frontend/syntax/parser.h"

#include <algorithm>
#include <charconv>
#include <string>

#include "frontend/syntax/lexer.h"

namespace openplx::frontend {
namespace {

// Where a member stands: a model or trait body allows methods, a nested block under an attribute does not.
enum class BlockContext { Body, Nested };

class Parser {
 public:
  Parser(const SourceFile& file, FileId file_id, const std::vector<Token>& tokens, DiagnosticSink& sink)
      : file_(file), file_id_(file_id), tokens_(tokens), sink_(sink) {
    doc_.file = file_id;
  }

  Document run();

 private:
  // ---- tokens
  // After too many errors every token reads as the end of the file: each loop of the parser ends there.
  const Token& cur() const { return stopped_ ? tokens_.back() : tokens_[pos_]; }
  const Token& peek_token(size_t ahead = 1) const {
    return tokens_[stopped_ ? tokens_.size() - 1 : std::min(pos_ + ahead, tokens_.size() - 1)];
  }
  TokenKind kind() const { return cur().kind; }
  bool at(TokenKind k) const { return kind() == k; }
  bool at_name() const { return at(TokenKind::Identifier) || at(TokenKind::QuotedIdentifier); }
  std::string_view text(const Token& t) const { return file_.text().substr(t.begin, t.end - t.begin); }
  void advance() {
    if (at(TokenKind::EndOfFile)) return;
    if (kind() != TokenKind::Newline && kind() != TokenKind::Indent && kind() != TokenKind::Dedent) {
      last_end_ = cur().end;
    }
    ++pos_;
  }
  bool accept(TokenKind k) {
    if (!at(k)) return false;
    advance();
    return true;
  }
  // End of the last token consumed that is not layout, so ranges stop at the last character of a construct.
  uint32_t prev_end() const { return last_end_; }
  SourceRange range_from(uint32_t begin) const { return {file_id_, begin, std::max(begin, prev_end())}; }
  SourceRange token_range(const Token& t) const { return {file_id_, t.begin, t.end}; }

  // ---- errors
  // Reports once per line: after the first error the parser is in panic mode until it resynchronises,
  // and tokens the lexer already reported are not reported again.
  void error(DiagCode code, SourceRange range, std::string message) {
    if (panic_ || stopped_) return;
    panic_ = true;
    if (cur().kind == TokenKind::Error) return;  // a consequence of a lexical error already reported
    const Diagnostic& d = sink_.report(code, range, std::move(message));
    if (d.severity != Severity::Error || ++errors_ < kMaxErrorsPerFile) return;
    sink_.report(DiagCode::TooManyErrors, {file_id_, range.end, range.end},
                 "too many errors in this file: stopping after " + std::to_string(kMaxErrorsPerFile) +
                     "; the rest of it was not read");
    stopped_ = true;
  }
  void error_here(std::string expected) {
    error(DiagCode::UnexpectedToken, here(), "expected " + expected + ", found " + describe(cur()));
  }
  // Where to point at the current token; at the end of a line, just after its last real token rather
  // than after a trailing comment.
  SourceRange here() const {
    const bool layout =
        at(TokenKind::Newline) || at(TokenKind::EndOfFile) || at(TokenKind::Dedent) || at(TokenKind::Indent);
    return layout && pos_ > 0 ? SourceRange{file_id_, last_end_, last_end_} : token_range(cur());
  }
  std::string describe(const Token& t) const {
    switch (t.kind) {
      case TokenKind::Identifier:
      case TokenKind::QuotedIdentifier:
      case TokenKind::Int:
      case TokenKind::Real:
        return std::string(token_kind_description(t.kind)) + " `" + std::string(text(t)) + "`";
      default:
        return std::string(token_kind_description(t.kind));
    }
  }
  bool expect(TokenKind k, std::string_view what) {
    if (accept(k)) return true;
    error_here(std::string(what));
    return false;
  }
  // Skips the rest of the logical line (and any block hanging off it); leaves panic mode.
  void sync_line();
  void skip_block();  // at INDENT: skips to after the matching DEDENT
  bool expect_line_end();

  // ---- nesting guard
  bool enter_nesting(SourceRange where) {
    if (++depth_ <= kMaxNesting) return true;
    error(DiagCode::NestingTooDeep, where,
          "nesting is deeper than " + std::to_string(kMaxNesting) + " levels; flatten the model");
    return false;
  }
  void leave_nesting() { --depth_; }

  // ---- declarations
  void parse_top_decl();
  void parse_import();
  void parse_trait();
  void parse_operator();
  void parse_model_or_global();
  // After a declaration head: `:` NEWLINE block, or NEWLINE (with the missing-colon leniency).
  bool parse_decl_body(Decl& decl, bool colon_seen, uint32_t colon_begin);
  void parse_block(std::vector<Member>& out, BlockContext context);
  void parse_member(std::vector<Member>& out, BlockContext context);
  void parse_annotation(std::vector<Member>& out);
  void parse_method(std::vector<Member>& out, BlockContext context);
  void parse_member_tail(Member& member, bool allow_plain_end);
  Ident parse_ident();
  QualifiedName parse_qualified_name();
  QualifiedName parse_single_name();
  TypeRef parse_type_ref();
  TypeExpr parse_type_expr();
  std::vector<Param> parse_params();

  // ---- expressions
  // Adds an expression whose operands are scratch_[first...]; they move to the document's pool. Operand
  // lists nest like the parse, so a stack of scratch entries is enough.
  ExprId add_expr(Expr expr, size_t first_operand = SIZE_MAX) {
    uint32_t offset = static_cast<uint32_t>(doc_.operand_pool.size());
    uint32_t count = 0;
    if (first_operand != SIZE_MAX) {
      count = static_cast<uint32_t>(scratch_.size() - first_operand);
      doc_.operand_pool.insert(doc_.operand_pool.end(),
                               scratch_.begin() + static_cast<std::ptrdiff_t>(first_operand), scratch_.end());
      scratch_.resize(first_operand);
    }
    // Chains like `1 + 1 + ...` or `a.b.c...` parse without recursion but still build deep trees; bound
    // their height too, since every later pass walks trees recursively.
    uint32_t height = 1;
    for (uint32_t i = 0; i < count; ++i) {
      height = std::max(height, heights_[doc_.operand_pool[offset + i]] + 1u);
    }
    if (height > static_cast<uint32_t>(kMaxNesting)) {
      error(DiagCode::NestingTooDeep, expr.range,
            "expression is nested deeper than " + std::to_string(kMaxNesting) + " levels; split it");
      while (!at(TokenKind::Newline) && !at(TokenKind::EndOfFile)) advance();
      height = 1;
      expr.kind = ExprKind::Error;
    }
    doc_.exprs.push_back(std::move(expr));
    operand_spans_.push_back({offset, count});
    heights_.push_back(height);
    return static_cast<ExprId>(doc_.exprs.size() - 1);
  }
  // Operand i of an expression while parsing (the spans are set when the parse is done).
  ExprId operand(ExprId id, size_t i) const { return doc_.operand_pool[operand_spans_[id].first + i]; }
  ExprId add_expr_with(Expr expr, std::initializer_list<ExprId> operands) {
    const size_t first = scratch_.size();
    scratch_.insert(scratch_.end(), operands);
    return add_expr(std::move(expr), first);
  }
  ExprId error_expr(uint32_t begin) {
    Expr e;
    e.kind = ExprKind::Error;
    e.range = {file_id_, begin, std::max(begin, prev_end())};
    return add_expr(std::move(e));
  }
  ExprId parse_expr();
  ExprId parse_additive();
  ExprId parse_multiplicative();
  ExprId parse_unary();
  ExprId parse_postfix();
  ExprId parse_primary();
  ExprId parse_literal();
  ExprId parse_list(ExprKind kind, TokenKind close, std::string_view close_text);
  ExprId parse_call(ExprId callee);
  ExprId binary(char op, ExprId lhs, ExprId rhs);

  const SourceFile& file_;
  FileId file_id_;
  const std::vector<Token>& tokens_;
  DiagnosticSink& sink_;
  Document doc_;
  std::vector<ExprId> scratch_;
  std::vector<std::pair<uint32_t, uint32_t>> operand_spans_;  // per expression: pool offset and count
  std::vector<uint32_t> heights_;                             // per expression: height of its tree
  size_t pos_ = 0;
  uint32_t last_end_ = 0;
  int depth_ = 0;
  bool panic_ = false;
  uint32_t errors_ = 0;
  bool stopped_ = false;  // too many errors: the rest of the file is not read
};

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

}  // namespace

Document parse(const SourceFile& file, FileId file_id, const std::vector<Token>& tokens,
               DiagnosticSink& sink) {
  return Parser(file, file_id, tokens, sink).run();
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
