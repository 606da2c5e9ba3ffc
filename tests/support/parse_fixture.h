// Test support: parse OpenPLX text held in memory, and a fixture that fails a test when a diagnostic was
// produced and not checked (so no test passes while the parser quietly complains).
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "frontend/diagnostics/diagnostics.h"
#include "frontend/diagnostics/source.h"
#include "frontend/syntax/ast.h"
#include "frontend/syntax/token.h"

namespace openplx::testing {

namespace fe = openplx::frontend;

// Owns the sources and the sink; every diagnostic must be claimed by expect_diag() (or accept_all_diags()).
class DiagnosticTest : public ::testing::Test {
 protected:
  // Checks that a diagnostic with `code` sits at line:col and marks it checked. Returns its message.
  std::string expect_diag(fe::DiagCode code, uint32_t line, uint32_t col);
  // Like expect_diag, for a diagnostic in any file whose message contains `text`.
  std::string expect_diag_containing(fe::DiagCode code, const std::string& text);
  size_t count(fe::DiagCode code) const;
  // Marks every diagnostic checked (for tests that assert only "no crash, some error").
  void accept_all_diags() { checked_.assign(sink_.diagnostics().size(), true); }

  std::string all_diags() const;

  void TearDown() override;

  fe::SourceManager sources_;
  fe::DiagnosticSink sink_;
  std::vector<bool> checked_;
};

class ParseTest : public DiagnosticTest {
 protected:
  // Lexes and parses `text` as the file `path`; diagnostics collect in sink().
  const fe::Document& parse(const std::string& text, const std::string& path = "test.openplx");
  std::vector<fe::Token> lex(const std::string& text, const std::string& path = "test.openplx");

  fe::FileId file_ = fe::kNoFile;
  fe::Document doc_;
};

}  // namespace openplx::testing
