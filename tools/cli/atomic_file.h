// Writes a whole file or nothing: the text goes to a temporary file beside the target, which is then
// renamed over it, so a reader never sees a partial file and a failed run leaves the old file in place.
#pragma once

#include <string>
#include <string_view>

namespace openplx::cli {

bool write_file_atomically(const std::string& path, std::string_view content, std::string& error);

}  // namespace openplx::cli
