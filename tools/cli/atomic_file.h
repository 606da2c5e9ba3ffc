// Writes a whole file or nothing: the text goes to a temporary file beside the target, which is then
// renamed over it, so a reader never sees a partial file and a failed run leaves the old file in place.
#pragma once

#include <functional>
#include <string>
#include <string_view>

namespace openplx::cli {

bool write_file_atomically(const std::string& path, std::string_view content, std::string& error);
// The same for text made in pieces: `produce` hands each piece to the writer it is given, in order.
using PieceWriter = std::function<void(std::string_view)>;
bool write_file_atomically(const std::string& path, const std::function<void(const PieceWriter&)>& produce,
                           std::string& error);

// The text written to a new temporary file beside `path` (named `path` + ".tmp" + 6 characters), left there
// for the caller to rename or remove: `temporary` gets its name. On failure nothing is left.
bool write_temporary_file(const std::string& path, const std::function<void(const PieceWriter&)>& produce,
                          std::string& temporary, std::string& error);

}  // namespace openplx::cli
