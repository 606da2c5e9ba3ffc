// Source files and positions. A SourceManager owns the text of every file read in a run; everything else
// refers to text by FileId and byte offsets, so tokens and AST names can be string_views into it.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace openplx::frontend {

using FileId = uint32_t;
inline constexpr FileId kNoFile = UINT32_MAX;

// Half-open byte range [begin, end) in one file.
struct SourceRange {
  FileId file = kNoFile;
  uint32_t begin = 0;
  uint32_t end = 0;
};

// 1-based line and column; the column counts bytes from the start of the line.
struct LineCol {
  uint32_t line = 1;
  uint32_t col = 1;
};

class SourceFile {
 public:
  SourceFile(std::string path, std::string text);
  // A text that outlives the file (the bundles this build carries, embedded_bundles.h), not copied.
  struct Static {};
  SourceFile(std::string path, std::string_view text, Static);

  const std::string& path() const { return path_; }
  std::string_view text() const { return text_; }
  // Offset of the first byte after a leading UTF-8 byte-order mark (0 or 3).
  uint32_t content_begin() const { return content_begin_; }
  LineCol line_col(uint32_t offset) const;
  // The line holding `offset`, without its line terminator.
  std::string_view line_text(uint32_t line) const;
  uint32_t line_count() const { return static_cast<uint32_t>(line_starts().size()); }

 private:
  // Found on first use: only files with a diagnostic (or a dump) need them.
  const std::vector<uint32_t>& line_starts() const;

  std::string path_;
  std::string owned_;
  std::string_view text_;  // owned_, or a static text
  uint32_t content_begin_ = 0;
  mutable std::once_flag lines_found_;
  mutable std::vector<uint32_t> line_starts_;  // line terminators: LF, CRLF or a lone CR
};

class SourceManager {
 public:
  // Reads a file from disk. Returns nullopt and sets `error` when it cannot be read.
  std::optional<FileId> load(const std::string& path, std::string& error);
  FileId add(std::string path, std::string text);
  // A file whose text lives as long as the program (the embedded bundles): viewed, not copied.
  FileId add_static(std::string path, std::string_view text);
  const SourceFile& file(FileId id) const { return *files_.at(id); }
  size_t size() const { return files_.size(); }

  // Generated text (a URDF import) whose line k came from byte `origins[k-1]` of file `origin`: positions in
  // it are reported at the origin, where the user can act on them.
  void set_origin(FileId generated, FileId origin, std::vector<uint32_t> origins);
  // `range` itself, or the place in an origin file that its generated line came from.
  SourceRange user_range(SourceRange range) const;

 private:
  struct Origin {
    FileId file;
    std::vector<uint32_t> offsets;
  };
  std::vector<std::unique_ptr<SourceFile>> files_;  // stable addresses: views point into them
  std::vector<Origin> origins_;                     // by FileId; file == kNoFile when not generated
};

}  // namespace openplx::frontend
