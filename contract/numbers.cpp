#include "contract/numbers.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <iterator>

namespace openplx::mjcf {
namespace {

thread_local size_t non_finite_written = 0;

}  // namespace

size_t non_finite_numbers_written() {
  return non_finite_written;
}

std::string number(double value) {
  std::string out;
  append_number(out, value);
  return out;
}

void append_number(std::string& out, double value) {
  if (value == 0.0) {
    out += '0';
    return;
  }
  char buffer[kNumberChars];
  out.append(buffer, write_number(buffer, value));
}

namespace {

// A number of at most six decimals from 0.001 to 10^4 ("0.5", "-12.25"), written from its digits; nullptr
// for any other. There its shortest round trip is those decimals in fixed notation, which is never longer
// than scientific: the general algorithm costs many times more, and models are full of such numbers.
char* write_short_decimal(char* at, double value) {
  const double magnitude = std::abs(value);
  if (!(magnitude >= 1e-3 && magnitude < 1e4)) return nullptr;
  constexpr double kScales[] = {1e1, 1e2, 1e3, 1e4, 1e5, 1e6};
  for (size_t decimals = 1; decimals <= std::size(kScales); ++decimals) {
    const double scale = kScales[decimals - 1];
    const double scaled = std::round(magnitude * scale);
    // Exact division by an exact power of ten rounds as reading the decimal does: a round trip. The first
    // count that trips is the shortest, so its last decimal is not 0.
    if (scaled / scale != magnitude) continue;
    auto digits = static_cast<uint64_t>(scaled);
    const auto power = static_cast<uint64_t>(scale);
    if (value < 0) *at++ = '-';
    at = std::to_chars(at, at + 4, digits / power).ptr;  // below 10^4
    *at++ = '.';
    digits %= power;
    for (size_t d = decimals; d-- > 0; digits /= 10) at[d] = static_cast<char>('0' + digits % 10);
    return at + decimals;
  }
  return nullptr;
}

}  // namespace

char* write_number(char* at, double value) {
  if (!std::isfinite(value)) ++non_finite_written;
  if (value == 0.0) {  // also folds -0, which MuJoCo reads the same
    *at = '0';
    return at + 1;
  }
  // A whole number below 10^4 is its digits in shortest form too (fixed notation is never longer than
  // scientific there): the integer conversion skips the general algorithm.
  if (std::abs(value) < 1e4 && value == std::trunc(value))
    return std::to_chars(at, at + kNumberChars, static_cast<int>(value)).ptr;
  if (char* end = write_short_decimal(at, value)) return end;
  return std::to_chars(at, at + kNumberChars, value).ptr;
}

std::string numbers(std::initializer_list<double> values) {
  std::string out;
  for (double value : values) {
    if (!out.empty()) out += ' ';
    append_number(out, value);
  }
  return out;
}

}  // namespace openplx::mjcf
