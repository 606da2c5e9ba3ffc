#include "tests/support/eval_fixture.h"

#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <string_view>

#include "frontend/evaluation/value_format.h"
#include "frontend/pipeline.h"

namespace openplx::testing {

EvalTest::EvalTest() = default;
EvalTest::~EvalTest() = default;

void EvalTest::TearDown() {
  DiagnosticTest::TearDown();
  evaluator_.reset();
  program_.reset();
}

std::string EvalTest::write(const std::string& relative, const std::string& text) {
  const std::filesystem::path path = dir_ / relative;
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
  return path.generic_string();
}

bool EvalTest::load(const std::string& text, const char* model) {
  return load_file(write("main.openplx", text), model);
}

bool EvalTest::load_file(const std::string& path, const char* model,
                         const std::vector<std::string>& bundle_dirs) {
  fe::LoadRequest request{path, model ? std::optional<std::string>(model) : std::nullopt, bundle_dirs,
                          std::nullopt};
  fe::Evaluation evaluation = fe::evaluate_file(request, sources_, sink_);
  program_ = std::move(evaluation.program);
  evaluator_ = std::move(evaluation.evaluator);
  root_ = evaluation.root;
  if (root_ == fe::kNoObject) return false;
  return !sink_.has_errors();
}

fe::ObjectId EvalTest::object(const std::string& path) {
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

const fe::Slot* EvalTest::slot(const std::string& path, fe::ObjectId* holder) {
  const size_t dot = path.rfind('.');
  fe::ObjectId owner = dot == std::string::npos ? root_ : object(path.substr(0, dot));
  if (owner == fe::kNoObject) return nullptr;
  const std::string name = dot == std::string::npos ? path : path.substr(dot + 1);
  evaluator_->value(owner, name);
  if (holder) *holder = owner;
  return evaluator_->graph().at(owner).find(name);
}

std::string EvalTest::value(const std::string& path) {
  const fe::Slot* s = slot(path);
  return s ? fe::format_value(*evaluator_, s->value, s->owns) : "<missing>";
}

double EvalTest::real(const std::string& path) {
  const fe::Slot* s = slot(path);
  return s && s->value.is_number() ? s->value.as_real() : std::nan("");
}

std::string EvalTest::values() {
  std::ostringstream out;
  fe::dump_values(out, *evaluator_, root_);
  return out.str();
}

}  // namespace openplx::testing
