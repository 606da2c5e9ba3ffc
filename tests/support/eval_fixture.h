// Test support: write OpenPLX files into the test's own scratch folder, load one with the project's bundles,
// instantiate its root model and evaluate every attribute; then read values by path. Diagnostics must be
// claimed as in ParseTest.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "frontend/bundles/bundles.h"
#include "frontend/evaluation/evaluator.h"
#include "frontend/evaluation/value_format.h"
#include "frontend/pipeline.h"
#include "frontend/semantics/program.h"
#include "tests/support/parse_fixture.h"
#include "tests/support/scratch_dir.h"

namespace openplx::testing {

class EvalTest : public DiagnosticTest {
 protected:
  void TearDown() override {
    DiagnosticTest::TearDown();
    evaluator_.reset();
    program_.reset();
  }

  // Writes `text` to `relative` under the test folder; returns the absolute path.
  std::string write(const std::string& relative, const std::string& text) {
    const std::filesystem::path path = dir_ / relative;
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
    return path.generic_string();
  }

  // Loads `text` as main.openplx (root: `model`, else the last model). True when no error was reported.
  bool load(const std::string& text, const char* model = nullptr) {
    return load_file(write("main.openplx", text), model);
  }
  bool load_file(const std::string& path, const char* model = nullptr,
                 const std::vector<std::string>& bundle_dirs = {}) {
    fe::LoadRequest request{path, model ? std::optional<std::string>(model) : std::nullopt, bundle_dirs,
                            std::nullopt};
    fe::Evaluation evaluation = fe::evaluate_file(request, sources_, sink_);
    program_ = std::move(evaluation.program);
    evaluator_ = std::move(evaluation.evaluator);
    root_ = evaluation.root;
    if (root_ == fe::kNoObject) return false;
    return !sink_.has_errors();
  }

  // The object at a dotted path from the root ("" = the root), or kNoObject.
  fe::ObjectId object(const std::string& path) {
    fe::ObjectId current = root_;
    size_t start = 0;
    while (current != fe::kNoObject && start < path.size()) {
      size_t end = path.find('.', start);
      if (end == std::string::npos) end = path.size();
      const fe::Value* v = evaluator_->value(current, std::string_view(path).substr(start, end - start));
      current = v && v->kind == fe::Value::Kind::Object ? v->object : fe::kNoObject;
      start = end + 1;
    }
    return current;
  }
  // The slot at a dotted path, with the object holding it.
  const fe::Slot* slot(const std::string& path, fe::ObjectId* holder = nullptr) {
    const size_t dot = path.rfind('.');
    fe::ObjectId owner = dot == std::string::npos ? root_ : object(path.substr(0, dot));
    if (owner == fe::kNoObject) return nullptr;
    const std::string name = dot == std::string::npos ? path : path.substr(dot + 1);
    evaluator_->value(owner, name);
    if (holder) *holder = owner;
    return evaluator_->graph().at(owner).find(name);
  }
  // The value at a dotted path as --dump=values prints it ("7.0", "{1.0, 2.0, 3.0}", "-> inner"), or
  // "<missing>".
  std::string value(const std::string& path) {
    const fe::Slot* s = slot(path);
    return s ? fe::format_value(*evaluator_, s->value, s->owns) : "<missing>";
  }
  double real(const std::string& path) {
    const fe::Slot* s = slot(path);
    return s && s->value.is_number() ? s->value.as_real() : std::nan("");
  }
  std::string values() {
    std::ostringstream out;
    fe::dump_values(out, *evaluator_, root_);
    return out.str();
  }
  std::string dir() const { return dir_.generic_string(); }

  ScratchDir scratch_;  // removed with the fixture, after TearDown
  std::filesystem::path dir_ = scratch_.path();
  std::unique_ptr<fe::Program> program_;
  std::unique_ptr<fe::Evaluator> evaluator_;
  fe::ObjectId root_ = fe::kNoObject;
};

}  // namespace openplx::testing
