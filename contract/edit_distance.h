// Levenshtein distance, for "did you mean" suggestions.
#pragma once

#include <cstddef>
#include <string_view>

namespace openplx {

size_t edit_distance(std::string_view a, std::string_view b);

}  // namespace openplx
