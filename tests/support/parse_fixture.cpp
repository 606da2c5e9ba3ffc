#include "tests/support/parse_fixture.h"

#include "frontend/syntax/lexer.h"
#include "frontend/syntax/parser.h"

namespace openplx::testing {

std::string DiagnosticTest::expect_diag(fe::DiagCode code, uint32_t line, uint32_t col) {
  for (size_t i = 0; i < sink_.diagnostics().size(); ++i) {
    const fe::Diagnostic& d = sink_.diagnostics()[i];
    if (checked_.size() <= i) checked_.resize(sink_.diagnostics().size(), false);
    if (checked_[i] || d.code != code) continue;
    if (d.range.file == fe::kNoFile) continue;
    fe::LineCol pos = sources_.file(d.range.file).line_col(d.range.begin);
    if (pos.line == line && pos.col == col) {
      checked_[i] = true;
      return d.message;
    }
  }
  ADD_FAILURE() << "no unchecked diagnostic [" << fe::code_name(code) << "] at " << line << ':' << col
                << "; have:\n"
                << all_diags();
  return {};
}

std::string DiagnosticTest::expect_diag_containing(fe::DiagCode code, const std::string& text) {
  for (size_t i = 0; i < sink_.diagnostics().size(); ++i) {
    const fe::Diagnostic& d = sink_.diagnostics()[i];
    if (checked_.size() <= i) checked_.resize(sink_.diagnostics().size(), false);
    if (checked_[i] || d.code != code || d.message.find(text) == std::string::npos) continue;
    checked_[i] = true;
    return d.message;
  }
  ADD_FAILURE() << "no unchecked diagnostic [" << fe::code_name(code) << "] containing \"" << text
                << "\"; have:\n"
                << all_diags();
  return {};
}

size_t DiagnosticTest::count(fe::DiagCode code) const {
  size_t n = 0;
  for (const fe::Diagnostic& d : sink_.diagnostics()) n += d.code == code;
  return n;
}

std::string DiagnosticTest::all_diags() const {
  std::string out;
  for (const fe::Diagnostic& d : sink_.diagnostics()) {
    fe::LineCol pos =
        d.range.file == fe::kNoFile ? fe::LineCol{} : sources_.file(d.range.file).line_col(d.range.begin);
    out += "  " + std::to_string(pos.line) + ':' + std::to_string(pos.col) + ' ' +
           std::string(fe::code_name(d.code)) + ": " + d.message + '\n';
  }
  return out;
}

void DiagnosticTest::TearDown() {
  checked_.resize(sink_.diagnostics().size(), false);
  for (size_t i = 0; i < checked_.size(); ++i) {
    if (!checked_[i]) {
      ADD_FAILURE() << "unchecked diagnostics:\n" << all_diags();
      return;
    }
  }
}

const fe::Document& ParseTest::parse(const std::string& text, const std::string& path) {
  file_ = sources_.add(path, text);
  doc_ = fe::parse_file(sources_, file_, sink_);
  return doc_;
}

std::vector<fe::Token> ParseTest::lex(const std::string& text, const std::string& path) {
  file_ = sources_.add(path, text);
  const size_t first = sink_.diagnostics().size();
  auto tokens = fe::lex(sources_.file(file_), file_, sink_);
  sink_.sort_by_position(first);
  return tokens;
}

}  // namespace openplx::testing
