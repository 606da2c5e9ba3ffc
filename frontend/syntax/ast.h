// The syntax tree of one OpenPLX document (../shared/spec/openplx-language.md §3). Every node carries the
// source range it was parsed from. Names are views into the SourceFile text, so the SourceManager must
// outlive the Document. Expressions live in one arena (`Document::exprs`) and refer to each other by ExprId.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "frontend/diagnostics/source.h"

namespace openplx::frontend {

using ExprId = uint32_t;

struct Ident {
  std::string_view text;  // without backticks
  SourceRange range;
  bool quoted = false;  // written as `...`
};

// `A.B.C`: a qualified name, or a dotted path on the left of an assignment.
struct QualifiedName {
  std::span<const Ident> parts;  // a view into Document::ident_pool
  SourceRange range;
};

std::string to_string(const QualifiedName& name);  // "A.B.C" (backtick names keep their backticks)

// `Name` or `Name[]`.
struct TypeRef {
  QualifiedName name;
  bool is_array = false;
  SourceRange range;
};

// `A or B with T1, T2`.
struct TypeExpr {
  std::span<const TypeRef> alternatives;  // views into Document::type_ref_pool and name_pool
  std::span<const QualifiedName> traits;
  SourceRange range;
};

enum class ExprKind : uint8_t {
  Int,         // text = digits; int_value set when it fits in 64 bits
  Real,        // text = literal; real_value
  Bool,        // bool_value
  String,      // string_value (decoded)
  PathString,  // string_value = the path as written; resolved against the file by sema
  Name,        // text = identifier
  This,
  Member,       // operands[0] . text
  Index,        // operands[0] [ operands[1] ]
  Call,         // operands[0] = callee (Name or Member), operands[1..] = arguments
  Unary,        // op, operands[0]
  Binary,       // operands[0] op operands[1]
  Array,        // [operands...]
  Initializer,  // {operands...}
  Error,        // already reported
};

struct Expr {
  ExprKind kind = ExprKind::Error;
  char op = 0;          // '+', '-', '*', '/' for Unary and Binary
  bool quoted = false;  // Name/Member written in backticks
  bool bool_value = false;
  bool multiline = false;  // String from """..."""
  SourceRange range;
  std::string_view text;
  std::optional<int64_t> int_value;
  double real_value = 0.0;
  std::string string_value;
  std::span<const ExprId> operands;  // a view into Document::operand_pool
};

struct Param {
  Ident name;
  TypeRef type;
  SourceRange range;
};

enum class MemberKind : uint8_t {
  Annotation,  // .name: value
  TraitUse,    // with Trait
  Method,      // [static] fn name(params) [-> R]
  Attribute,   // [optional] name is Type [: value | : block]
  Becomes,     // path becomes Type [: value | : block]
  Assignment,  // path: value | path: block
};

struct Member {
  MemberKind kind = MemberKind::Attribute;
  SourceRange range;
  QualifiedName path;  // attribute name (one part), becomes/assignment path, annotation name, trait name
  bool is_optional = false;
  bool is_reference =
      false;  // Attribute: `name is Type reference`, a reference to an instance made elsewhere
  bool is_static = false;
  TypeExpr type;                       // Attribute, Becomes
  std::optional<ExprId> value;         // Attribute, Becomes, Assignment, Annotation
  bool has_block = false;              // `:` followed by an indented block
  std::vector<Member> block;           // members applied to the target's instance
  std::vector<Param> params;           // Method
  std::optional<TypeRef> return_type;  // Method
};

enum class DeclKind : uint8_t { Import, Model, Trait, GlobalAttribute, Operator };

struct Decl {
  DeclKind kind = DeclKind::Model;
  SourceRange range;
  Ident name;                             // Model, Trait, GlobalAttribute
  bool is_const = false;                  // Model
  std::optional<QualifiedName> base;      // Model, Trait: `is Base`
  std::span<const QualifiedName> traits;  // Model: `is Base with T1, T2` shorthand
  bool has_body = false;
  std::vector<Member> body;            // Model, Trait
  TypeExpr type;                       // GlobalAttribute
  std::optional<ExprId> value;         // GlobalAttribute; Import: the path expression
  std::optional<QualifiedName> alias;  // Import `as a.b`
  char op = 0;                         // Operator
  std::vector<Param> params;           // Operator
  std::optional<TypeRef> return_type;  // Operator
};

// Move-only: names, types and expressions view their parts inside the pools, whose buffers a move keeps in
// place. The pools are few large allocations instead of one small one per name, which is most of the
// parser's speed.
struct Document {
  Document() = default;
  Document(Document&&) = default;
  Document& operator=(Document&&) = default;
  Document(const Document&) = delete;
  Document& operator=(const Document&) = delete;

  FileId file = kNoFile;
  std::vector<Decl> decls;
  std::vector<Expr> exprs;
  std::vector<ExprId> operand_pool;
  std::vector<Ident> ident_pool;
  std::vector<TypeRef> type_ref_pool;
  std::vector<QualifiedName> name_pool;

  const Expr& expr(ExprId id) const { return exprs[id]; }
  // The last model (not trait) declared, as the default root; nullptr when there is none.
  const Decl* last_model() const;
  const Decl* find_model(std::string_view name) const;
};

}  // namespace openplx::frontend
