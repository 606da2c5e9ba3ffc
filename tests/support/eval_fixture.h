// Test support: write OpenPLX files into the test's own scratch folder, load one with the project's bundles,
// instantiate its root model and evaluate every attribute; then read values by path. Diagnostics must be
// claimed as in ParseTest.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "frontend/evaluation/evaluator.h"
#include "frontend/semantics/program.h"
#include "tests/support/parse_fixture.h"
#include "tests/support/scratch_dir.h"

namespace openplx::testing {

class EvalTest : public DiagnosticTest {
 protected:
  EvalTest();
  ~EvalTest() override;
  void TearDown() override;

  // Writes `text` to `relative` under the test folder; returns the absolute path.
  std::string write(const std::string& relative, const std::string& text);

  // Loads `text` as main.openplx (root: `model`, else the last model). True when no error was reported.
  bool load(const std::string& text, const char* model = nullptr);
  bool load_file(const std::string& path, const char* model = nullptr,
                 const std::vector<std::string>& bundle_dirs = {});

  // The object at a dotted path from the root ("" = the root), or kNoObject.
  fe::ObjectId object(const std::string& path);
  // The slot at a dotted path, with the object holding it.
  const fe::Slot* slot(const std::string& path, fe::ObjectId* holder = nullptr);
  // The value at a dotted path as --dump=values prints it ("7.0", "{1.0, 2.0, 3.0}", "-> inner"), or
  // "<missing>".
  std::string value(const std::string& path);
  // The number at a dotted path; NaN when there is none.
  double real(const std::string& path);
  // Every value from the root, as --dump=values prints them.
  std::string values();
  std::string dir() const { return dir_.generic_string(); }

  ScratchDir scratch_;  // removed with the fixture, after TearDown
  std::filesystem::path dir_ = scratch_.path();
  std::unique_ptr<fe::Program> program_;
  std::unique_ptr<fe::Evaluator> evaluator_;
  fe::ObjectId root_ = fe::kNoObject;
};

}  // namespace openplx::testing
