#include "tools/cli/atomic_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace openplx::cli {

bool write_file_atomically(const std::string& path, std::string_view content, std::string& error) {
  return write_file_atomically(
      path, [content](const PieceWriter& write) { write(content); }, error);
}

bool write_file_atomically(const std::string& path, const std::function<void(const PieceWriter&)>& produce,
                           std::string& error) {
  std::string temporary;
  if (!write_temporary_file(path, produce, temporary, error)) return false;
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    error = std::string("cannot write: ") + std::strerror(errno);
    std::remove(temporary.c_str());
    return false;
  }
  return true;
}

bool write_temporary_file(const std::string& path, const std::function<void(const PieceWriter&)>& produce,
                          std::string& temporary, std::string& error) {
  std::string pattern = path + ".tmpXXXXXX";
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  int fd = mkstemp(name.data());
  if (fd < 0) {
    error = std::string("cannot create a temporary file beside it: ") + std::strerror(errno);
    return false;
  }
  int failure = 0;  // the first write's errno; later pieces are skipped
  produce([&](std::string_view piece) {
    size_t written = 0;
    while (!failure && written < piece.size()) {
      ssize_t n = ::write(fd, piece.data() + written, piece.size() - written);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        failure = n < 0 ? errno : EIO;
        break;
      }
      written += static_cast<size_t>(n);
    }
  });
  // mkstemp creates 0600; an output file should get the usual permissions.
  if (!failure) ::fchmod(fd, 0644);
  if (::close(fd) != 0 && !failure) failure = errno;
  if (failure) {
    error = std::string("cannot write: ") + std::strerror(failure);
    std::remove(name.data());
    return false;
  }
  temporary = name.data();
  return true;
}

}  // namespace openplx::cli
