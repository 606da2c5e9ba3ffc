// "Did you mean" for signal names: the known names closest to a misspelt one.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace openplx::runtime {

// Up to five candidates within a small edit distance of `name` (or ending with its last path segment),
// closest first, as text to append to an error message: "; did you mean `a` or `b`?" ("" when none).
std::string suggestion_text(std::string_view name, const std::vector<std::string>& candidates);

}  // namespace openplx::runtime
