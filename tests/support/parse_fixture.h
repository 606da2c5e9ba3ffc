// Test support: parse OpenPLX text held in memory, and a fixture that fails a test when a diagnostic was
// produced and not checked (so no test passes while the parser quietly complains).
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "frontend/diagnostics/diagnostics.h"
#include "frontend/diagnostics/source.h"
#include "frontend/syntax/ast.h"
#include "frontend/syntax/lexer.h"
#include "frontend/syntax/parser.h"

namespace openplx::testing {

namespace fe = openplx::frontend;

// Owns the sources and the sink; every diagnostic must be claimed by expect_diag() (or accept_all_diags()).
class DiagnosticTest : public ::testing::Test {
 protected:
  // Checks that a diagnostic with `code` sits at line:col and marks it checked. Returns its message.
  std::string expect_diag(fe::DiagCode code, uint32_t line, uint32_t col) {
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
  size_t count(fe::DiagCode code) const {
    size_t n = 0;
    for (const fe::Diagnostic& d : sink_.diagnostics()) n += d.code == code;
    return n;
  }
  // Marks every diagnostic checked (for tests that assert only "no crash, some error").
  void accept_all_diags() { checked_.assign(sink_.diagnostics().size(), true); }

  std::string all_diags() const {
    std::string out;
    for (const fe::Diagnostic& d : sink_.diagnostics()) {
      fe::LineCol pos =
          d.range.file == fe::kNoFile ? fe::LineCol{} : sources_.file(d.range.file).line_col(d.range.begin);
      out += "  " + std::to_string(pos.line) + ':' + std::to_string(pos.col) + ' ' +
             std::string(fe::code_name(d.code)) + ": " + d.message + '\n';
    }
    return out;
  }

  void TearDown() override {
    checked_.resize(sink_.diagnostics().size(), false);
    for (size_t i = 0; i < checked_.size(); ++i) {
      if (!checked_[i]) {
        ADD_FAILURE() << "unchecked diagnostics:\n" << all_diags();
        return;
      }
    }
  }

  // Like expect_diag, for a diagnostic in any file whose message contains `text`.
  std::string expect_diag_containing(fe::DiagCode code, const std::string& text) {
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

  fe::SourceManager sources_;
  fe::DiagnosticSink sink_;
  std::vector<bool> checked_;
};

class ParseTest : public DiagnosticTest {
 protected:
  // Lexes and parses `text` as the file `path`; diagnostics collect in sink().
  const fe::Document& parse(const std::string& text, const std::string& path = "test.openplx") {
    file_ = sources_.add(path, text);
    doc_ = fe::parse_file(sources_, file_, sink_);
    return doc_;
  }
  std::vector<fe::Token> lex(const std::string& text, const std::string& path = "test.openplx") {
    file_ = sources_.add(path, text);
    const size_t first = sink_.diagnostics().size();
    auto tokens = fe::lex(sources_.file(file_), file_, sink_);
    sink_.sort_by_position(first);
    return tokens;
  }

  fe::FileId file_ = fe::kNoFile;
  fe::Document doc_;
};

}  // namespace openplx::testing
