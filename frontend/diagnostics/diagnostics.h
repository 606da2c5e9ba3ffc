// Diagnostics are values appended to a sink; passes never throw them. The printer renders the form that
// compilers and IDEs understand: `file:line:col: error: message [code]`, then the source line and a caret.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <map>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "frontend/diagnostics/source.h"

namespace openplx::frontend {

enum class Severity : uint8_t { Note, Warning, Error };

enum class DiagCode : uint16_t {
#define X(name, code, severity) name,
#include "frontend/diagnostics/diagnostic_codes.def"
#undef X
};

std::string_view code_name(DiagCode code);
Severity default_severity(DiagCode code);
std::string_view severity_name(Severity severity);

struct Diagnostic {
  DiagCode code;
  Severity severity;
  SourceRange range;  // file == kNoFile for diagnostics about no particular place
  std::string message;
  std::vector<std::string> notes;
};

class DiagnosticSink {
 public:
  // With `strict`, warnings are reported as errors (the `--strict` flag).
  explicit DiagnosticSink(bool strict = false) : strict_(strict) {}

  // A diagnostic with the same code, place and message as an earlier one is not repeated (a type name
  // resolved for every instance of a model would otherwise warn once per instance).
  Diagnostic& report(DiagCode code, SourceRange range, std::string message);
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }
  size_t error_count() const { return error_count_; }
  bool has_errors() const { return error_count_ > 0; }
  void clear();
  // Orders the diagnostics reported since index `first` by file and position (stable), so the lexer's and
  // the parser's findings in one file read top to bottom.
  void sort_by_position(size_t first);

 private:
  bool strict_;
  size_t error_count_ = 0;
  std::vector<Diagnostic> diagnostics_;
  std::map<std::tuple<uint16_t, FileId, uint32_t, std::string>, size_t> seen_;
};

// The errors a printout shows. Past them a pass may skip work only their text would show ("did you mean"
// over every name of a file, for each of 40,000 unknown names), since no one reads it.
inline constexpr size_t kMaxPrintedErrors = 100;

// Prints every diagnostic in report order, at most `max_errors` errors (then one `too-many-errors` note).
void print_diagnostics(std::ostream& out, const SourceManager& sources, const std::vector<Diagnostic>& diags,
                       size_t max_errors = kMaxPrintedErrors);
void print_diagnostic(std::ostream& out, const SourceManager& sources, const Diagnostic& diag);

}  // namespace openplx::frontend
