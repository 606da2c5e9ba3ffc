// Numbers as MJCF and the signal manifest write them: locale-independent, shortest round trip, the same
// bytes on every run. The emitter's XML and the manifest writer use them, and the runtime's messages.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <string>

namespace openplx::mjcf {

// Shortest text that reads back as the same double ("0.5", "1e-07", "-0"); never locale-dependent.
std::string number(double value);
// Appends number(value) to `out`, with no string of its own.
void append_number(std::string& out, double value);
// Writes number(value) at `at`, which has room for kNumberChars, and returns the end of what it wrote.
inline constexpr size_t kNumberChars = 32;  // the longest double ("-1.7976931348623157e+308") is 24
char* write_number(char* at, double value);
// Numbers separated by single spaces ("0 0 1.5"), as MJCF writes vectors.
std::string numbers(std::initializer_list<double> values);
// How many NaNs and infinities write_number has written on this thread: none may reach an MJCF (MuJoCo
// reads them, then fails or blows up), so the emitter counts them as a backstop behind the value checks.
size_t non_finite_numbers_written();

}  // namespace openplx::mjcf
