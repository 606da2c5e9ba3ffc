// A string as a double-quoted literal with \" \\ \n \t \r escapes: how dumps and messages show text.
#pragma once

#include <string>
#include <string_view>

namespace openplx::frontend {

inline std::string quoted(std::string_view text) {
  std::string out = "\"";
  for (char c : text) {
    switch (c) {
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
      case '\r':
        out += "\\r";
        break;
      default:
        out += c;
    }
  }
  return out + "\"";
}

}  // namespace openplx::frontend
