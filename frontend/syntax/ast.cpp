#include "frontend/syntax/ast.h"

namespace openplx::frontend {

std::string to_string(const QualifiedName& name) {
  std::string out;
  for (const Ident& part : name.parts) {
    if (!out.empty()) out += '.';
    if (part.quoted) {
      out += '`';
      out += part.text;
      out += '`';
    } else {
      out += part.text;
    }
  }
  return out;
}

const Decl* Document::last_model() const {
  for (auto it = decls.rbegin(); it != decls.rend(); ++it) {
    if (it->kind == DeclKind::Model) return &*it;
  }
  return nullptr;
}

const Decl* Document::find_model(std::string_view name) const {
  for (const Decl& decl : decls) {
    if (decl.kind == DeclKind::Model && decl.name.text == name) return &decl;
  }
  return nullptr;
}

}  // namespace openplx::frontend
