#include "frontend/syntax/lexer.h"

#include <algorithm>
#include <optional>
#include <string>

namespace openplx::frontend {
namespace {

bool is_ident_start(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
bool is_digit(char c) {
  return c >= '0' && c <= '9';
}
bool is_ident_char(char c) {
  return is_ident_start(c) || is_digit(c);
}
bool is_line_end(char c) {
  return c == '\n' || c == '\r';
}
bool is_closing_bracket(char c) {
  return c == ')' || c == ']' || c == '}';
}

// Binary files are refused whole: a NUL byte where at least a tenth of the first 64 KiB is not UTF-8 text
// (control characters other than layout, bytes no UTF-8 sequence holds). A stray NUL in a text file is an
// invalid character like any other. Returns the offset of the first NUL of a file refused.
std::optional<uint32_t> binary_file_at(std::string_view text, uint32_t begin) {
  const size_t nul = text.find('\0', begin);
  if (nul == std::string_view::npos) return std::nullopt;
  const std::string_view sample = text.substr(begin, 64 * 1024);
  size_t not_text = 0;
  for (size_t i = 0; i < sample.size();) {
    const auto u = static_cast<unsigned char>(sample[i]);
    if (u < 0x80) {
      not_text += (u < 0x20 && u != '\n' && u != '\r' && u != '\t' && u != '\f' && u != '\v') || u == 0x7f;
      ++i;
      continue;
    }
    // A UTF-8 lead byte and its continuation bytes, or one byte that is not text.
    const size_t length = u >= 0xC2 && u <= 0xDF   ? 2
                          : u >= 0xE0 && u <= 0xEF ? 3
                          : u >= 0xF0 && u <= 0xF4 ? 4
                                                   : 0;
    size_t k = 1;
    while (length && k < length && i + k < sample.size() &&
           (static_cast<unsigned char>(sample[i + k]) & 0xC0) == 0x80)
      ++k;
    if (length && k == length) {
      i += length;
    } else {
      ++not_text;
      ++i;
    }
  }
  if (not_text * 10 < sample.size()) return std::nullopt;
  return static_cast<uint32_t>(nul);
}

TokenKind keyword_kind(std::string_view word) {
  switch (word.size()) {
    case 2:
      if (word == "is") return TokenKind::KwIs;
      if (word == "fn") return TokenKind::KwFn;
      if (word == "or") return TokenKind::KwOr;
      break;
    case 4:
      if (word == "with") return TokenKind::KwWith;
      if (word == "this") return TokenKind::KwThis;
      if (word == "true") return TokenKind::KwTrue;
      break;
    case 5:
      if (word == "trait") return TokenKind::KwTrait;
      if (word == "const") return TokenKind::KwConst;
      if (word == "false") return TokenKind::KwFalse;
      break;
    case 6:
      if (word == "import") return TokenKind::KwImport;
      if (word == "static") return TokenKind::KwStatic;
      break;
    case 7:
      if (word == "becomes") return TokenKind::KwBecomes;
      break;
    case 8:
      if (word == "operator") return TokenKind::KwOperator;
      if (word == "optional") return TokenKind::KwOptional;
      break;
    default:
      break;
  }
  return TokenKind::Identifier;
}

class Lexer {
 public:
  Lexer(const SourceFile& file, FileId file_id, DiagnosticSink& sink)
      : text_(file.text()), file_(file_id), sink_(sink), pos_(file.content_begin()) {}

  std::vector<Token> run();

 private:
  struct OpenBracket {
    char kind;
    uint32_t offset;
    uint32_t line_indent;  // indentation of the line that opened it
  };

  char peek(uint32_t ahead = 0) const { return pos_ + ahead < text_.size() ? text_[pos_ + ahead] : '\0'; }
  bool at_end() const { return pos_ >= text_.size(); }
  void emit(TokenKind kind, uint32_t begin, uint32_t end) { tokens_.push_back({kind, begin, end}); }
  void error(DiagCode code, uint32_t begin, uint32_t end, std::string message) {
    const Diagnostic& d = sink_.report(code, {file_, begin, end}, std::move(message));
    if (d.severity == Severity::Error) stopped_ = ++errors_ >= kMaxErrorsPerFile;
  }
  bool last_is_layout() const {
    if (tokens_.empty()) return true;
    TokenKind kind = tokens_.back().kind;
    return kind == TokenKind::Newline || kind == TokenKind::Indent || kind == TokenKind::Dedent;
  }
  void skip_line_end() {
    if (peek() == '\r' && peek(1) == '\n') ++pos_;
    ++pos_;
  }

  // Reads the indentation of a fresh line. Returns false for blank and comment-only lines (consumed).
  bool start_line();
  uint32_t recover_tab_column(uint32_t column) const;
  // True when the last token cannot end an expression (`,`, an opening bracket, an operator, `.`).
  bool expression_continues() const {
    if (tokens_.empty()) return false;
    switch (tokens_.back().kind) {
      case TokenKind::Comma:
      case TokenKind::LParen:
      case TokenKind::LBracket:
      case TokenKind::LBrace:
      case TokenKind::Plus:
      case TokenKind::Minus:
      case TokenKind::Star:
      case TokenKind::Slash:
      case TokenKind::Dot:
        return true;
      default:
        return false;
    }
  }
  void apply_indentation(uint32_t column, uint32_t at, bool tabbed);
  void lex_token();
  void lex_number();
  void lex_quoted_identifier();
  void lex_string();
  void lex_multiline_string();
  void lex_path_string(TokenKind kind);
  void lex_bracket(char c, TokenKind kind);
  void lex_closing_bracket(char c, TokenKind kind);
  void lex_invalid();
  // Reports the outermost open bracket and forgets all of them. The zero-width Error token at `at` tells
  // the parser that the expression it is reading was cut short by an error already reported.
  void report_unclosed_bracket(uint32_t at) {
    const OpenBracket& open = brackets_.front();
    error(DiagCode::UnclosedBracket, open.offset, open.offset + 1,
          std::string("`") + open.kind + "` is never closed");
    brackets_.clear();
    emit(TokenKind::Error, at, at);
  }

  std::string_view text_;
  FileId file_;
  DiagnosticSink& sink_;
  uint32_t pos_;
  std::vector<Token> tokens_;
  std::vector<uint32_t> indents_{0};
  std::vector<bool> tab_opened_{false};  // per open column: opened by a tab-indented line
  std::vector<OpenBracket> brackets_;
  uint32_t line_indent_ = 0;
  bool at_line_start_ = true;
  uint32_t errors_ = 0;
  bool stopped_ = false;  // too many errors: the rest of the file is not read
};

std::vector<Token> Lexer::run() {
  if (const std::optional<uint32_t> nul = binary_file_at(text_, pos_)) {
    error(DiagCode::InvalidCharacter, *nul, *nul + 1,
          "this file is not text (a NUL byte here, and much of its start is not UTF-8 text); an OpenPLX "
          "file is UTF-8 text, and none of this one was read");
    emit(TokenKind::EndOfFile, *nul, *nul);
    return std::move(tokens_);
  }
  // Enough for most files; a huge one grows the vector as it goes (a reservation for a 100 MB file of
  // garbage that stops after a hundred errors would hold memory for nothing).
  tokens_.reserve(std::min<size_t>(text_.size() / 4, 1 << 20) + 16);
  while (!at_end() && !stopped_) {
    if (at_line_start_) {
      at_line_start_ = false;
      if (!start_line()) continue;
    }
    lex_token();
  }
  uint32_t end = static_cast<uint32_t>(text_.size());
  if (stopped_) {
    end = pos_;
    sink_.report(DiagCode::TooManyErrors, {file_, end, end},
                 "too many errors in this file: stopping after " + std::to_string(kMaxErrorsPerFile) +
                     "; the rest of it was not read");
    brackets_.clear();
  }
  if (!brackets_.empty()) report_unclosed_bracket(end);
  if (!last_is_layout()) emit(TokenKind::Newline, end, end);
  while (indents_.size() > 1) {
    indents_.pop_back();
    tab_opened_.pop_back();
    emit(TokenKind::Dedent, end, end);
  }
  emit(TokenKind::EndOfFile, end, end);
  return std::move(tokens_);
}

bool Lexer::start_line() {
  const uint32_t line_begin = pos_;
  uint32_t column = 0;
  uint32_t first_tab = UINT32_MAX;
  while (!at_end() && (peek() == ' ' || peek() == '\t')) {
    if (peek() == '\t') {
      if (first_tab == UINT32_MAX) first_tab = pos_;
      column = (column / 8 + 1) * 8;  // as a terminal would show it
    } else {
      ++column;
    }
    ++pos_;
  }
  const char c = peek();
  if (at_end() || is_line_end(c) || c == '#') {  // blank and comment lines take no part in layout
    while (!at_end() && !is_line_end(peek())) ++pos_;
    if (!at_end()) skip_line_end();
    at_line_start_ = true;
    return false;
  }
  if (!brackets_.empty()) {
    // Inside brackets a line continues the expression. The one exception: a line that falls back to (or
    // before) the column of the line that opened the bracket, after a line that ended on a complete
    // operand, starts something new; the bracket was most likely never closed.
    if (column > brackets_.front().line_indent || is_closing_bracket(c) || expression_continues())
      return true;
    report_unclosed_bracket(line_begin);
    if (!last_is_layout()) emit(TokenKind::Newline, line_begin, line_begin);
  }
  const bool tabbed = first_tab != UINT32_MAX;
  if (tabbed) {
    error(DiagCode::TabIndentation, first_tab, first_tab + 1,
          "tabs are not allowed for indentation; use spaces");
    column = recover_tab_column(column);
  }
  apply_indentation(column, pos_, tabbed);
  line_indent_ = column;
  return true;
}

uint32_t Lexer::recover_tab_column(uint32_t column) const {
  // A tab's width is anyone's guess: trust it only where it lands on an open column or opens the block
  // that the previous line asks for; otherwise keep the line in the current block.
  for (uint32_t open : indents_) {
    if (open == column) return column;
  }
  const bool opens_block = tokens_.size() >= 2 && tokens_.back().kind == TokenKind::Newline &&
                           tokens_[tokens_.size() - 2].kind == TokenKind::Colon;
  return column > indents_.back() && opens_block ? column : indents_.back();
}

void Lexer::apply_indentation(uint32_t column, uint32_t at, bool tabbed) {
  if (column > indents_.back()) {
    indents_.push_back(column);
    tab_opened_.push_back(tabbed);
    emit(TokenKind::Indent, at, at);
    return;
  }
  while (column < indents_.back()) {
    const uint32_t outer = indents_[indents_.size() - 2];
    if (tab_opened_.back() && column > outer) {
      // A block opened by a tab-indented line takes the column of its first space-indented line.
      indents_.back() = column;
      tab_opened_.back() = false;
      return;
    }
    if (outer < column && outer > 0) {
      // Shallower than a nested block yet deeper than the line that opened it, as an official release writes
      // (Sensors/Library/LIDARs/SICK/TIM150.openplx 0.20.2, column 12 in a block at 13 opened at 9). AGX
      // takes the line into the block; so do we, and the block goes on at the line's column. A top-level
      // declaration's own block keeps the spec's rule (§2.3, an error): its case 4 is exactly that.
      sink_.report(DiagCode::MisalignedIndent, {file_, at, at + 1},
                   "line is indented less than its block (column " + std::to_string(indents_.back() + 1) +
                       ") but deeper than the line that opened it (column " + std::to_string(outer + 1) +
                       "); taken as part of the block, which continues at column " +
                       std::to_string(column + 1));
      indents_.back() = column;
      return;
    }
    if (outer < column) {
      error(DiagCode::InconsistentDedent, at, at + 1,
            "Inconsistent indentation: column " + std::to_string(column + 1) +
                " does not match any enclosing block (expected column " + std::to_string(outer + 1) + " or " +
                std::to_string(indents_.back() + 1) + ")");
      return;  // keep the line in the innermost block: the fewest follow-on errors
    }
    indents_.pop_back();
    tab_opened_.pop_back();
    emit(TokenKind::Dedent, at, at);
  }
}

void Lexer::lex_token() {
  const char c = peek();
  const uint32_t begin = pos_;
  switch (c) {
    case ' ':
    case '\t':
    case '\f':
    case '\v':
      ++pos_;
      return;
    case '\n':
    case '\r':
      if (brackets_.empty() && !last_is_layout()) emit(TokenKind::Newline, begin, begin + 1);
      skip_line_end();
      at_line_start_ = true;
      return;
    case '#':
      while (!at_end() && !is_line_end(peek())) ++pos_;
      return;
    case '`':
      lex_quoted_identifier();
      return;
    case '"':
      if (peek(1) == '"' && peek(2) == '"') {
        lex_multiline_string();
      } else {
        lex_string();
      }
      return;
    case '@':
      lex_path_string(TokenKind::PathString);
      return;
    case '$':
      lex_path_string(TokenKind::DollarPathString);
      return;
    case ':':
      ++pos_;
      emit(TokenKind::Colon, begin, pos_);
      return;
    case '.':
      ++pos_;
      emit(TokenKind::Dot, begin, pos_);
      return;
    case ',':
      ++pos_;
      emit(TokenKind::Comma, begin, pos_);
      return;
    case '+':
      ++pos_;
      emit(TokenKind::Plus, begin, pos_);
      return;
    case '*':
      ++pos_;
      emit(TokenKind::Star, begin, pos_);
      return;
    case '/':
      ++pos_;
      emit(TokenKind::Slash, begin, pos_);
      return;
    case '-':
      if (peek(1) == '>') {
        pos_ += 2;
        emit(TokenKind::Arrow, begin, pos_);
      } else {
        ++pos_;
        emit(TokenKind::Minus, begin, pos_);
      }
      return;
    case '(':
      lex_bracket(c, TokenKind::LParen);
      return;
    case '[':
      lex_bracket(c, TokenKind::LBracket);
      return;
    case '{':
      lex_bracket(c, TokenKind::LBrace);
      return;
    case ')':
      lex_closing_bracket(c, TokenKind::RParen);
      return;
    case ']':
      lex_closing_bracket(c, TokenKind::RBracket);
      return;
    case '}':
      lex_closing_bracket(c, TokenKind::RBrace);
      return;
    default:
      break;
  }
  if (is_ident_start(c)) {
    while (!at_end() && is_ident_char(peek())) ++pos_;
    emit(keyword_kind(text_.substr(begin, pos_ - begin)), begin, pos_);
  } else if (is_digit(c)) {
    lex_number();
  } else {
    lex_invalid();
  }
}

void Lexer::lex_number() {
  const uint32_t begin = pos_;
  bool real = false;
  bool bad = false;
  while (is_digit(peek())) ++pos_;
  if (peek() == '.') {
    if (is_digit(peek(1))) {
      real = true;
      ++pos_;
      while (is_digit(peek())) ++pos_;
    } else {
      ++pos_;
      error(DiagCode::MalformedNumber, begin, pos_, "malformed number: digits must follow the decimal point");
      bad = true;
    }
  }
  if (!bad && (peek() == 'e' || peek() == 'E')) {
    uint32_t digits = 1 + ((peek(1) == '+' || peek(1) == '-') ? 1 : 0);
    if (is_digit(peek(digits))) {
      real = true;
      pos_ += digits;
      while (is_digit(peek())) ++pos_;
    } else {
      pos_ += digits;
      error(DiagCode::MalformedNumber, begin, pos_, "malformed number: the exponent has no digits");
      bad = true;
    }
  }
  if (!bad && (is_ident_char(peek()) || peek() == '.')) {
    while (is_ident_char(peek()) || peek() == '.') ++pos_;
    error(DiagCode::MalformedNumber, begin, pos_,
          "malformed number `" + std::string(text_.substr(begin, pos_ - begin)) + "`");
    bad = true;
  }
  emit(bad ? TokenKind::Error : (real ? TokenKind::Real : TokenKind::Int), begin, pos_);
}

void Lexer::lex_quoted_identifier() {
  const uint32_t begin = pos_++;
  while (!at_end() && peek() != '`' && !is_line_end(peek())) ++pos_;
  if (peek() != '`') {
    error(DiagCode::UnterminatedBacktick, begin, begin + 1, "unterminated backtick identifier");
    emit(TokenKind::Error, begin, pos_);
    return;
  }
  ++pos_;
  if (pos_ - begin == 2) {
    error(DiagCode::UnterminatedBacktick, begin, pos_, "empty backtick identifier");
    emit(TokenKind::Error, begin, pos_);
    return;
  }
  emit(TokenKind::QuotedIdentifier, begin, pos_);
}

void Lexer::lex_string() {
  const uint32_t begin = pos_++;
  while (!at_end() && peek() != '"' && !is_line_end(peek())) {
    if (peek() == '\\') {
      char next = peek(1);
      if (next == '"' || next == '\\' || next == 'n' || next == 't') {
        pos_ += 2;
        continue;
      }
      if (pos_ + 1 >= text_.size() || is_line_end(next)) break;  // reported as unterminated below
      error(DiagCode::InvalidEscape, pos_, pos_ + 2,
            "invalid escape sequence in string; the escapes are \\\", \\\\, \\n and \\t");
    }
    ++pos_;
  }
  if (peek() != '"') {
    error(DiagCode::UnterminatedString, begin, begin + 1,
          "unterminated string: missing closing `\"` on this line");
    emit(TokenKind::String, begin, pos_);
    return;
  }
  ++pos_;
  emit(TokenKind::String, begin, pos_);
}

void Lexer::lex_multiline_string() {
  const uint32_t begin = pos_;
  pos_ += 3;
  while (!at_end()) {
    if (peek() == '\\' && peek(1) == '"') {
      pos_ += 2;  // `\"` keeps a quote inside, as the published docs write `\"name\"`
      continue;
    }
    if (peek() == '"' && peek(1) == '"' && peek(2) == '"') {
      pos_ += 3;
      emit(TokenKind::MultilineString, begin, pos_);
      return;
    }
    ++pos_;
  }
  error(DiagCode::UnterminatedMultilineString, begin, begin + 3,
        "unterminated multi-line string: missing `\"\"\"`");
  emit(TokenKind::MultilineString, begin, pos_);
}

void Lexer::lex_path_string(TokenKind kind) {
  const uint32_t begin = pos_++;
  if (peek() != '"') {
    error(DiagCode::MalformedPathString, begin, begin + 1,
          std::string("`") + text_[begin] + "` must be followed by a quoted path, as in @\"mesh.obj\"");
    emit(TokenKind::Error, begin, pos_);
    return;
  }
  ++pos_;
  while (!at_end() && peek() != '"' && !is_line_end(peek())) ++pos_;
  if (peek() != '"') {
    error(DiagCode::UnterminatedString, begin, begin + 2, "unterminated path string: missing closing `\"`");
    emit(kind, begin, pos_);
    return;
  }
  ++pos_;
  emit(kind, begin, pos_);
}

void Lexer::lex_bracket(char c, TokenKind kind) {
  brackets_.push_back({c, pos_, line_indent_});
  ++pos_;
  emit(kind, pos_ - 1, pos_);
}

void Lexer::lex_closing_bracket(char c, TokenKind kind) {
  const uint32_t begin = pos_++;
  if (brackets_.empty()) {
    error(DiagCode::UnmatchedBracket, begin, pos_,
          std::string("`") + c + "` has no matching opening bracket");
    emit(TokenKind::Error, begin, pos_);
    return;
  }
  brackets_.pop_back();  // a mismatched kind is left to the parser, which says what it expected
  emit(kind, begin, pos_);
}

void Lexer::lex_invalid() {
  const uint32_t begin = pos_;
  // One diagnostic for a run of invalid bytes: binary garbage should not print thousands of lines.
  auto invalid = [](char c) {
    auto u = static_cast<unsigned char>(c);
    if (u >= 0x80) return true;
    if (u < 0x20) return c != '\n' && c != '\r' && c != '\t' && c != '\f' && c != '\v';
    return c == '!' || c == '%' || c == '&' || c == '\'' || c == ';' || c == '<' || c == '=' || c == '>' ||
           c == '?' || c == '\\' || c == '^' || c == '|' || c == '~' || u == 0x7f;
  };
  auto first = static_cast<unsigned char>(text_[begin]);
  if (first >= 0x80) {
    // A name with non-ASCII letters is one mistake, however many letters it has.
    while (!at_end() && (static_cast<unsigned char>(peek()) >= 0x80 || is_ident_char(peek()))) ++pos_;
  } else {
    while (!at_end() && invalid(peek())) ++pos_;
  }
  if (pos_ == begin) ++pos_;
  std::string message =
      first >= 0x20 && first < 0x7f
          ? std::string("invalid character `") + text_[begin] + "`"
          : (first >= 0x80 ? "invalid character: names are ASCII; write other names in backticks"
                           : "invalid control character");
  error(DiagCode::InvalidCharacter, begin, pos_, std::move(message));
  emit(TokenKind::Error, begin, pos_);
}

}  // namespace

std::vector<Token> lex(const SourceFile& file, FileId file_id, DiagnosticSink& sink) {
  return Lexer(file, file_id, sink).run();
}

std::string decode_string(TokenKind kind, std::string_view text) {
  std::string out;
  switch (kind) {
    case TokenKind::String: {
      std::string_view body = text.substr(1);
      if (!body.empty() && body.back() == '"') body.remove_suffix(1);
      out.reserve(body.size());
      for (size_t i = 0; i < body.size(); ++i) {
        if (body[i] == '\\' && i + 1 < body.size()) {
          char next = body[++i];
          out += next == 'n' ? '\n' : next == 't' ? '\t' : next;
        } else {
          out += body[i];
        }
      }
      return out;
    }
    case TokenKind::MultilineString: {
      std::string_view body = text.substr(3);
      if (body.size() >= 3 && body.substr(body.size() - 3) == "\"\"\"") body.remove_suffix(3);
      out.reserve(body.size());
      for (size_t i = 0; i < body.size(); ++i) {
        if (body[i] == '\\' && i + 1 < body.size() && body[i + 1] == '"') ++i;
        if (body[i] == '\r') {
          if (i + 1 < body.size() && body[i + 1] == '\n') ++i;
          out += '\n';  // the value of a CRLF file is the same as of its LF twin
          continue;
        }
        out += body[i];
      }
      return out;
    }
    case TokenKind::PathString:
    case TokenKind::DollarPathString: {
      std::string_view body = text.substr(2);
      if (!body.empty() && body.back() == '"') body.remove_suffix(1);
      return std::string(body);
    }
    default:
      return std::string(text);
  }
}

}  // namespace openplx::frontend
