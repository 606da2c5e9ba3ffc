// The recursive-descent parser's class, shared by its two halves: parser.cpp (declarations, members, names
// and types) and parse_expressions.cpp (expressions). Internal to syntax/: include parser.h instead.
#pragma once

#include <algorithm>
#include <string>

#include "frontend/syntax/lexer.h"
#include "frontend/syntax/parser.h"

namespace openplx::frontend::parsing {

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

}  // namespace openplx::frontend::parsing
