#include "frontend/syntax/ast_dump.h"

#include <ostream>

#include "frontend/syntax/quoted.h"

namespace openplx::frontend {
namespace {

std::string name_text(std::string_view text, bool quoted) {
  return quoted ? "`" + std::string(text) + "`" : std::string(text);
}

void append_expr(std::string& out, const Document& doc, ExprId id) {
  const Expr& e = doc.expr(id);
  auto list = [&](size_t first, const char* open, const char* close) {
    out += open;
    for (size_t i = first; i < e.operands.size(); ++i) {
      if (i > first) out += ", ";
      append_expr(out, doc, e.operands[i]);
    }
    out += close;
  };
  switch (e.kind) {
    case ExprKind::Int:
    case ExprKind::Real:
      out += e.text;
      break;
    case ExprKind::Bool:
      out += e.bool_value ? "true" : "false";
      break;
    case ExprKind::String:
      out += quoted(e.string_value);
      break;
    case ExprKind::PathString:
      out += (e.quoted ? "$" : "@") + quoted(e.string_value);
      break;
    case ExprKind::Name:
      out += name_text(e.text, e.quoted);
      break;
    case ExprKind::This:
      out += "this";
      break;
    case ExprKind::Member:
      append_expr(out, doc, e.operands[0]);
      out += '.';
      out += name_text(e.text, e.quoted);
      break;
    case ExprKind::Index:
      append_expr(out, doc, e.operands[0]);
      out += '[';
      append_expr(out, doc, e.operands[1]);
      out += ']';
      break;
    case ExprKind::Call:
      append_expr(out, doc, e.operands[0]);
      list(1, "(", ")");
      break;
    case ExprKind::Unary:
      out += "(-";
      append_expr(out, doc, e.operands[0]);
      out += ')';
      break;
    case ExprKind::Binary:
      out += '(';
      append_expr(out, doc, e.operands[0]);
      out += ' ';
      out += e.op;
      out += ' ';
      append_expr(out, doc, e.operands[1]);
      out += ')';
      break;
    case ExprKind::Array:
      list(0, "[", "]");
      break;
    case ExprKind::Initializer:
      list(0, "{", "}");
      break;
    case ExprKind::Error:
      out += "<error>";
      break;
  }
}

class AstDumper {
 public:
  AstDumper(std::ostream& out, const SourceFile& file, const Document& doc)
      : out_(out), file_(file), doc_(doc) {}

  void decl(const Decl& d) {
    std::string line;
    switch (d.kind) {
      case DeclKind::Import:
        line = "import " + expr_to_string(doc_, *d.value);
        if (d.alias) line += " as " + to_string(*d.alias);
        break;
      case DeclKind::Model:
      case DeclKind::Trait:
        line = d.kind == DeclKind::Trait ? "trait " : (d.is_const ? "const model " : "model ");
        line += name_text(d.name.text, d.name.quoted);
        if (d.base) line += " is " + to_string(*d.base);
        for (size_t i = 0; i < d.traits.size(); ++i) line += (i ? ", " : " with ") + to_string(d.traits[i]);
        break;
      case DeclKind::GlobalAttribute:
        line = "global " + name_text(d.name.text, d.name.quoted) + " is " + type(d.type) + " = " +
               expr_to_string(doc_, *d.value);
        break;
      case DeclKind::Operator:
        line = std::string("operator ") + d.op + params(d.params);
        if (d.return_type) line += " -> " + type_ref(*d.return_type);
        break;
    }
    emit(0, line, d.range);
    for (const Member& m : d.body) member(1, m);
  }

 private:
  void member(int depth, const Member& m) {
    std::string line;
    switch (m.kind) {
      case MemberKind::Annotation:
        line = "annotation " + to_string(m.path);
        break;
      case MemberKind::TraitUse:
        line = "with " + to_string(m.path);
        break;
      case MemberKind::Method:
        line = std::string(m.is_static ? "static fn " : "fn ") + to_string(m.path) + params(m.params);
        if (m.return_type) line += " -> " + type_ref(*m.return_type);
        break;
      case MemberKind::Attribute:
        line = std::string(m.is_optional ? "optional attr " : "attr ") + to_string(m.path) + " is " +
               type(m.type) + (m.is_reference ? " reference" : "");
        break;
      case MemberKind::Becomes:
        line = "becomes " + to_string(m.path) + " -> " + type(m.type);
        break;
      case MemberKind::Assignment:
        line = "assign " + to_string(m.path);
        break;
    }
    if (m.value) line += " = " + expr_to_string(doc_, *m.value);
    if (m.has_block) line += " {block}";
    emit(depth, line, m.range);
    for (const Member& child : m.block) member(depth + 1, child);
  }

  std::string type_ref(const TypeRef& t) { return to_string(t.name) + (t.is_array ? "[]" : ""); }
  std::string type(const TypeExpr& t) {
    std::string out;
    for (size_t i = 0; i < t.alternatives.size(); ++i) out += (i ? " or " : "") + type_ref(t.alternatives[i]);
    for (size_t i = 0; i < t.traits.size(); ++i) out += (i ? ", " : " with ") + to_string(t.traits[i]);
    return out;
  }
  std::string params(const std::vector<Param>& ps) {
    std::string out = "(";
    for (size_t i = 0; i < ps.size(); ++i) {
      out += (i ? ", " : "") + name_text(ps[i].name.text, ps[i].name.quoted) + ": " + type_ref(ps[i].type);
    }
    return out + ")";
  }
  void emit(int depth, const std::string& line, SourceRange range) {
    LineCol b = file_.line_col(range.begin);
    LineCol e = file_.line_col(range.end);
    out_ << std::string(static_cast<size_t>(depth) * 2, ' ') << line << " @" << b.line << ':' << b.col << '-'
         << e.line << ':' << e.col << '\n';
  }

  std::ostream& out_;
  const SourceFile& file_;
  const Document& doc_;
};

}  // namespace

std::string expr_to_string(const Document& doc, ExprId id) {
  std::string out;
  append_expr(out, doc, id);
  return out;
}

void dump_tokens(std::ostream& out, const SourceFile& file, const std::vector<Token>& tokens) {
  for (const Token& t : tokens) {
    LineCol pos = file.line_col(t.begin);
    out << pos.line << ':' << pos.col << ' ' << token_kind_name(t.kind);
    switch (t.kind) {
      case TokenKind::Newline:
      case TokenKind::Indent:
      case TokenKind::Dedent:
      case TokenKind::EndOfFile:
        break;
      default:
        out << ' ' << quoted(file.text().substr(t.begin, t.end - t.begin));
    }
    out << '\n';
  }
}

void dump_ast(std::ostream& out, const SourceFile& file, const Document& doc) {
  AstDumper dumper(out, file, doc);
  for (const Decl& d : doc.decls) dumper.decl(d);
}

}  // namespace openplx::frontend
