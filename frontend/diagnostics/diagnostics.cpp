#include "frontend/diagnostics/diagnostics.h"

#include <algorithm>
#include <array>
#include <ostream>

namespace openplx::frontend {
namespace {

struct CodeInfo {
  std::string_view name;
  Severity severity;
};

constexpr std::array kCodes = {
#define X(name, code, severity) CodeInfo{code, Severity::severity},
#include "frontend/diagnostics/diagnostic_codes.def"
#undef X
};

}  // namespace

std::string_view code_name(DiagCode code) {
  return kCodes[static_cast<size_t>(code)].name;
}
Severity default_severity(DiagCode code) {
  return kCodes[static_cast<size_t>(code)].severity;
}

std::string_view severity_name(Severity severity) {
  switch (severity) {
    case Severity::Note:
      return "note";
    case Severity::Warning:
      return "warning";
    case Severity::Error:
      return "error";
  }
  return "error";
}

Diagnostic& DiagnosticSink::report(DiagCode code, SourceRange range, std::string message) {
  auto key = std::make_tuple(static_cast<uint16_t>(code), range.file, range.begin, message);
  if (auto it = seen_.find(key); it != seen_.end()) return diagnostics_[it->second];
  seen_.emplace(std::move(key), diagnostics_.size());
  Severity severity = default_severity(code);
  if (strict_ && severity == Severity::Warning) severity = Severity::Error;
  if (severity == Severity::Error) ++error_count_;
  diagnostics_.push_back(Diagnostic{code, severity, range, std::move(message), {}});
  return diagnostics_.back();
}

void DiagnosticSink::clear() {
  diagnostics_.clear();
  seen_.clear();
  error_count_ = 0;
}

void DiagnosticSink::sort_by_position(size_t first) {
  if (first >= diagnostics_.size()) return;
  std::stable_sort(diagnostics_.begin() + static_cast<std::ptrdiff_t>(first), diagnostics_.end(),
                   [](const Diagnostic& a, const Diagnostic& b) {
                     if (a.range.file != b.range.file) return a.range.file < b.range.file;
                     return a.range.begin < b.range.begin;
                   });
  for (size_t i = first; i < diagnostics_.size(); ++i) {  // positions in the vector changed
    const Diagnostic& d = diagnostics_[i];
    seen_[std::make_tuple(static_cast<uint16_t>(d.code), d.range.file, d.range.begin, d.message)] = i;
  }
}

void print_diagnostic(std::ostream& out, const SourceManager& sources, const Diagnostic& diag) {
  const bool located = diag.range.file != kNoFile && diag.range.file < sources.size();
  const SourceRange range = located ? sources.user_range(diag.range) : diag.range;
  if (located) {
    const SourceFile& file = sources.file(range.file);
    LineCol pos = file.line_col(range.begin);
    out << file.path() << ':' << pos.line << ':' << pos.col << ": ";
  }
  out << severity_name(diag.severity) << ": " << diag.message << " [" << code_name(diag.code) << "]\n";
  if (located) {
    const SourceFile& file = sources.file(range.file);
    LineCol pos = file.line_col(range.begin);
    std::string_view line = file.line_text(pos.line);
    out << "  " << line << "\n  ";
    // Keep tabs under tabs so the caret lines up whatever the terminal's tab width.
    for (uint32_t i = 0; i + 1 < pos.col && i < line.size(); ++i) out << (line[i] == '\t' ? '\t' : ' ');
    out << "^\n";
  }
  for (const std::string& note : diag.notes) out << "note: " << note << '\n';
}

void print_diagnostics(std::ostream& out, const SourceManager& sources, const std::vector<Diagnostic>& diags,
                       size_t max_errors) {
  size_t errors = 0;
  for (const Diagnostic& diag : diags) {
    if (diag.severity == Severity::Error && ++errors > max_errors) {
      out << "note: too many errors, stopping after " << max_errors << " ["
          << code_name(DiagCode::TooManyErrors) << "]\n";
      return;
    }
    print_diagnostic(out, sources, diag);
  }
}

}  // namespace openplx::frontend
