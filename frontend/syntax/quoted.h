// A string as a double-quoted literal with \" \\ \n \t \r escapes: how dumps and messages show text.
#pragma once

#include <string>
#include <string_view>

namespace openplx::frontend {

// Appends `text` as a double-quoted string with escapes; plain runs are copied whole.
inline void append_quoted(std::string& out, std::string_view text) {
  out += '"';
  while (!text.empty()) {
    const size_t special = text.find_first_of("\"\\\n\t\r");
    out.append(text.substr(0, special));
    if (special == std::string_view::npos) break;
    switch (text[special]) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        out += "\\r";
        break;
    }
    text.remove_prefix(special + 1);
  }
  out += '"';
}

inline std::string quoted(std::string_view text) {
  std::string out;
  out.reserve(text.size() + 2);
  append_quoted(out, text);
  return out;
}

}  // namespace openplx::frontend
