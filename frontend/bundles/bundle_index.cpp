#include "frontend/bundles/bundle_index.h"

#include <array>
#include <cstring>

namespace openplx::frontend {
namespace {

bool is_ident_start(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
bool is_ident_char(char c) {
  return is_ident_start(c) || (c >= '0' && c <= '9');
}

bool is_keyword(std::string_view word) {
  static constexpr std::array<std::string_view, 14> kKeywords = {
      "is",    "fn",    "or",     "with",   "this",    "true",     "false",
      "trait", "const", "import", "static", "becomes", "operator", "optional"};
  for (std::string_view k : kKeywords) {
    if (word == k) return true;
  }
  return false;
}

// Characters that end a run the scanner steps over without a look: line ends, comments, strings, names in
// backticks, brackets, `>` (valid only in `->`) and what the lexer rejects outside strings and comments
// (lexer.cpp, lex_invalid).
constexpr std::array<bool, 256> kSpecial = [] {
  std::array<bool, 256> special{};
  for (int c = 0; c < 256; ++c) {
    const bool control = c < 0x20 && c != '\t' && c != '\f' && c != '\v';  // takes in '\n' and '\r'
    special[c] = control || c >= 0x7f;
  }
  for (const char c : std::string_view("#\"@$`([{)]}>!%&';<=?\\^|~"))
    special[static_cast<unsigned char>(c)] = true;
  return special;
}();

bool special(char c) {
  return kSpecial[static_cast<unsigned char>(c)];
}

class Scanner {
 public:
  Scanner(std::string_view text, size_t begin) : text_(text), pos_(begin) {}

  FileDeclarations run();

 private:
  enum class Header { Name, Other, Unsure };  // Other: `import` or `operator`, which declare no name

  char peek(size_t ahead = 0) const { return pos_ + ahead < text_.size() ? text_[pos_ + ahead] : '\0'; }
  bool at_line_end() const { return pos_ >= text_.size() || text_[pos_] == '\n' || text_[pos_] == '\r'; }
  void skip_to_line_end() {
    const char* const begin = text_.data() + pos_;
    const char* const end = text_.data() + text_.size();
    const void* lf = std::memchr(begin, '\n', static_cast<size_t>(end - begin));
    const char* line_end = lf ? static_cast<const char*>(lf) : end;
    if (const void* cr = std::memchr(begin, '\r', static_cast<size_t>(line_end - begin))) {
      line_end = static_cast<const char*>(cr);
    }
    pos_ = static_cast<size_t>(line_end - text_.data());
  }
  void skip_line_end() {
    if (peek() == '\r' && peek(1) == '\n') ++pos_;
    ++pos_;
  }
  // The first special character from `from` on, or the end (four at a time: most of a file is plain).
  size_t skip_plain(size_t from) const {
    const char* p = text_.data() + from;
    const char* const end = text_.data() + text_.size();
    for (; end - p >= 4; p += 4) {
      // Branchless on purpose: four tests combined as ints, one branch.
      if (int(special(p[0])) | int(special(p[1])) | int(special(p[2])) | int(special(p[3]))) break;
    }
    while (p != end && !special(*p)) ++p;
    return static_cast<size_t>(p - text_.data());
  }
  // At `"""`: steps over the string to its closing `"""`; false when it has none.
  bool skip_multiline_string() {
    for (size_t i = pos_ + 3; i + 2 < text_.size(); ++i) {
      if (text_[i] == '\\' && text_[i + 1] == '"') {
        ++i;
      } else if (text_[i] == '"' && text_[i + 1] == '"' && text_[i + 2] == '"') {
        pos_ = i + 3;
        return true;
      }
    }
    return false;
  }
  // At a backtick: steps over a non-empty backtick name on this line.
  bool skip_backtick_name();
  // An identifier that is not a keyword, or a non-empty backtick name (without its backticks).
  bool read_name(std::string& out);
  // A line at column 1: the name it declares, an import or operator, or a line the scan does not know.
  Header scan_header(std::string& name);
  // The rest of a line: strings, comments and brackets. False on anything the lexer would report.
  bool scan_tokens();
  // The last character of the line before its comment (after scan_tokens), or '\0'.
  char last_char(size_t line_begin) const;

  std::string_view text_;
  size_t pos_;
  int depth_ = 0;           // open brackets
  size_t content_end_ = 0;  // where the line scan_tokens read ends, before its comment
};

bool Scanner::skip_backtick_name() {
  const size_t begin = pos_++;
  while (!at_line_end() && peek() != '`') ++pos_;
  if (peek() != '`' || pos_ == begin + 1) return false;
  ++pos_;
  return true;
}

bool Scanner::read_name(std::string& out) {
  const size_t begin = pos_;
  if (peek() == '`') {
    if (!skip_backtick_name()) return false;
    out.assign(text_.substr(begin + 1, pos_ - begin - 2));
    return true;
  }
  if (!is_ident_start(peek())) return false;
  while (is_ident_char(peek())) ++pos_;
  out.assign(text_.substr(begin, pos_ - begin));
  return !is_keyword(out);
}

Scanner::Header Scanner::scan_header(std::string& name) {
  if (is_ident_start(peek())) {
    size_t end = pos_;
    while (end < text_.size() && is_ident_char(text_[end])) ++end;
    const std::string_view word = text_.substr(pos_, end - pos_);
    if (word == "import" || word == "operator") return Header::Other;
    if (word == "trait" || word == "const") {
      pos_ = end;
      if (peek() != ' ') return Header::Unsure;
      while (peek() == ' ') ++pos_;
    }
  }
  if (!read_name(name)) return Header::Unsure;
  // What the parser accepts after a declared name: `is`, `:` or the end of the line.
  while (peek() == ' ') ++pos_;
  if (peek() == ':' || peek() == '#' || at_line_end()) return Header::Name;
  if (peek() == 'i' && peek(1) == 's' && !is_ident_char(peek(2))) return Header::Name;
  return Header::Unsure;
}

bool Scanner::scan_tokens() {
  while (true) {
    pos_ = content_end_ = skip_plain(pos_);
    if (at_line_end()) return true;
    switch (text_[pos_]) {
      case '#':
        skip_to_line_end();
        return true;
      case '"':
        if (peek(1) == '"' && peek(2) == '"') {
          // A multi-line string, lines and all (they may start at column 1: a release's `.doc` texts do),
          // ended as the lexer ends it: at the first `"""` not after a backslash.
          if (!skip_multiline_string()) return false;
          break;
        }
        for (++pos_; !at_line_end() && peek() != '"'; ++pos_) {
          if (peek() != '\\') continue;
          const char next = peek(1);
          if (next != '"' && next != '\\' && next != 'n' && next != 't') return false;
          ++pos_;
        }
        if (peek() != '"') return false;
        ++pos_;
        break;
      case '@':
      case '$':
        if (peek(1) != '"') return false;
        for (pos_ += 2; !at_line_end() && peek() != '"';) ++pos_;
        if (peek() != '"') return false;
        ++pos_;
        break;
      case '`':
        if (!skip_backtick_name()) return false;
        break;
      case '(':
      case '[':
      case '{':
        ++depth_;
        ++pos_;
        break;
      case ')':
      case ']':
      case '}':
        if (depth_ == 0) return false;
        --depth_;
        ++pos_;
        break;
      case '>':
        if (text_[pos_ - 1] != '-') return false;
        ++pos_;
        break;
      default:
        return false;
    }
  }
}

char Scanner::last_char(size_t line_begin) const {
  size_t end = content_end_;
  while (end > line_begin && (text_[end - 1] == ' ' || text_[end - 1] == '\t' || text_[end - 1] == '\f' ||
                              text_[end - 1] == '\v')) {
    --end;
  }
  return end > line_begin ? text_[end - 1] : '\0';
}

FileDeclarations Scanner::run() {
  FileDeclarations result;
  bool others = false;        // imports or operators
  bool header = false;        // the logical line being read started at column 1
  bool block_open = false;    // the last declaration opened a block, so indented lines belong to it
  bool expect_block = false;  // ... and no indented line has come yet
  while (pos_ < text_.size()) {
    const size_t line_begin = pos_;
    const char* p = text_.data() + pos_;
    const char* const end = text_.data() + text_.size();
    while (p != end && *p == ' ') ++p;
    const bool tabbed = p != end && *p == '\t';
    while (p != end && (*p == ' ' || *p == '\t')) ++p;
    pos_ = static_cast<size_t>(p - text_.data());
    if (at_line_end() || peek() == '#') {  // blank and comment lines take no part in layout
      skip_to_line_end();
      if (pos_ < text_.size()) skip_line_end();
      continue;
    }
    if (tabbed) return {};
    const bool column1 = pos_ == line_begin;
    if (depth_ > 0) {
      // A continuation line at column 1 may instead be read as a new declaration after an unclosed bracket.
      if (column1) return {};
    } else if (column1) {
      if (expect_block) return {};  // `Name:` without a body
      std::string name;
      switch (scan_header(name)) {
        case Header::Name:
          result.names.push_back(std::move(name));
          break;
        case Header::Other:
          others = true;
          break;
        case Header::Unsure:
          return {};
      }
      header = true;
    } else {
      if (!block_open) return {};  // an indented line that no declaration opened
      expect_block = false;
    }
    if (!scan_tokens()) return {};
    if (depth_ == 0 && header) {
      header = false;
      block_open = expect_block = last_char(line_begin) == ':';
    }
    if (pos_ < text_.size()) skip_line_end();
  }
  if (depth_ > 0 || expect_block) return {};
  result.complete = true;
  result.lazy = !others && !result.names.empty();
  return result;
}

}  // namespace

FileDeclarations scan_declarations(std::string_view text, size_t begin) {
  return Scanner(text, begin).run();
}

}  // namespace openplx::frontend
