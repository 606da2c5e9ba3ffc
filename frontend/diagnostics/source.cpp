#include "frontend/diagnostics/source.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <limits>

namespace openplx::frontend {

SourceFile::SourceFile(std::string path, std::string text)
    : path_(std::move(path)), owned_(std::move(text)), text_(owned_) {
  if (text_.starts_with("\xEF\xBB\xBF")) content_begin_ = 3;
}

SourceFile::SourceFile(std::string path, std::string_view text, Static)
    : path_(std::move(path)), text_(text) {
  if (text_.starts_with("\xEF\xBB\xBF")) content_begin_ = 3;
}

const std::vector<uint32_t>& SourceFile::line_starts() const {
  std::call_once(lines_found_, [this] {
    line_starts_.push_back(content_begin_);
    for (uint32_t i = content_begin_; i < text_.size(); ++i) {
      if (text_[i] == '\n') {
        line_starts_.push_back(i + 1);
      } else if (text_[i] == '\r') {
        if (i + 1 < text_.size() && text_[i + 1] == '\n') ++i;
        line_starts_.push_back(i + 1);
      }
    }
  });
  return line_starts_;
}

LineCol SourceFile::line_col(uint32_t offset) const {
  const std::vector<uint32_t>& starts = line_starts();
  auto it = std::upper_bound(starts.begin(), starts.end(), offset);
  size_t index = it == starts.begin() ? 0 : static_cast<size_t>(it - starts.begin()) - 1;
  uint32_t start = starts[index];
  return {static_cast<uint32_t>(index + 1), offset >= start ? offset - start + 1 : 1};
}

std::string_view SourceFile::line_text(uint32_t line) const {
  const std::vector<uint32_t>& starts = line_starts();
  if (line == 0 || line > starts.size()) return {};
  uint32_t begin = starts[line - 1];
  uint32_t end = line < starts.size() ? starts[line] : static_cast<uint32_t>(text_.size());
  std::string_view view(text_.data() + begin, end - begin);
  while (!view.empty() && (view.back() == '\n' || view.back() == '\r')) view.remove_suffix(1);
  return view;
}

namespace {

bool is_directory(const std::string& path) {
  struct stat st;
  return stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

// Appends everything left to read of `fd` to `text`; false on a read error.
bool read_rest(int fd, std::string& text) {
  char chunk[1 << 16];
  while (true) {
    const ssize_t got = ::read(fd, chunk, sizeof chunk);
    if (got == 0) return true;
    if (got < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    text.append(chunk, static_cast<size_t>(got));
  }
}

}  // namespace

std::optional<FileId> SourceManager::load(const std::string& path, std::string& error) {
  // One open, one fstat and one read of the size it gives (plain POSIX: a stdio stream per file costs more
  // than most bundle files it would read); pipes and the like are read to their end. A folder is told apart
  // whether or not it can be opened.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  struct stat st;
  if (fd < 0 || fstat(fd, &st) != 0 || S_ISDIR(st.st_mode)) {
    const bool folder = fd >= 0 ? S_ISDIR(st.st_mode) : is_directory(path);
    if (fd >= 0) ::close(fd);
    error = folder ? "is a directory, not a file" : "cannot open file";
    return std::nullopt;
  }
  std::string text;
  bool ok = true;
  if (S_ISREG(st.st_mode) && st.st_size > 0) {
    text.resize(static_cast<size_t>(st.st_size));
    size_t have = 0;
    while (ok && have < text.size()) {
      const ssize_t got = ::read(fd, text.data() + have, text.size() - have);
      if (got > 0) {
        have += static_cast<size_t>(got);
      } else if (got == 0) {
        break;  // it shrank since fstat
      } else if (errno != EINTR) {
        ok = false;
      }
    }
    text.resize(have);
  } else {
    ok = read_rest(fd, text);  // a pipe, or a file that gives no size (/proc)
  }
  ::close(fd);
  if (!ok) {
    error = "cannot read file";
    return std::nullopt;
  }
  // Offsets are 32-bit; a 4 GiB model is not a model.
  if (text.size() >= std::numeric_limits<uint32_t>::max()) {
    error = "file is larger than 4 GiB";
    return std::nullopt;
  }
  return add(path, std::move(text));
}

FileId SourceManager::add(std::string path, std::string text) {
  files_.push_back(std::make_unique<SourceFile>(std::move(path), std::move(text)));
  return static_cast<FileId>(files_.size() - 1);
}

FileId SourceManager::add_static(std::string path, std::string_view text) {
  files_.push_back(std::make_unique<SourceFile>(std::move(path), text, SourceFile::Static{}));
  return static_cast<FileId>(files_.size() - 1);
}

void SourceManager::set_origin(FileId generated, FileId origin, std::vector<uint32_t> offsets) {
  if (origins_.size() <= generated) origins_.resize(generated + 1, Origin{kNoFile, {}});
  origins_[generated] = {origin, std::move(offsets)};
}

SourceRange SourceManager::user_range(SourceRange range) const {
  if (range.file >= origins_.size() || origins_[range.file].file == kNoFile) return range;
  const Origin& origin = origins_[range.file];
  const uint32_t line = file(range.file).line_col(range.begin).line;
  if (line == 0 || line > origin.offsets.size()) return range;
  const uint32_t at = origin.offsets[line - 1];
  return {origin.file, at, at + 1};
}

}  // namespace openplx::frontend
