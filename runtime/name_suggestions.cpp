#include "runtime/name_suggestions.h"

#include <algorithm>
#include <utility>

#include "contract/edit_distance.h"

namespace openplx::runtime {
namespace {

std::string_view last_segment(std::string_view path) {
  const size_t dot = path.rfind('.');
  return dot == std::string_view::npos ? path : path.substr(dot + 1);
}

}  // namespace

std::string suggestion_text(std::string_view name, const std::vector<std::string>& candidates) {
  const size_t limit = std::max<size_t>(2, name.size() / 3);
  std::vector<std::pair<size_t, std::string>> close;
  for (const std::string& candidate : candidates) {
    size_t distance = edit_distance(name, candidate);
    if (distance > limit && last_segment(candidate) == last_segment(name)) distance = limit;
    if (distance <= limit) close.emplace_back(distance, candidate);
  }
  std::sort(close.begin(), close.end());
  if (close.size() > 5) close.resize(5);
  if (close.empty()) return "";
  std::string text = "; did you mean ";
  for (size_t k = 0; k < close.size(); ++k) {
    if (k > 0) text += k + 1 == close.size() ? " or " : ", ";
    text += "`" + close[k].second + "`";
  }
  return text + "?";
}

}  // namespace openplx::runtime
