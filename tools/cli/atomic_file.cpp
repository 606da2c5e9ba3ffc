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
  std::string pattern = path + ".tmpXXXXXX";
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  int fd = mkstemp(name.data());
  if (fd < 0) {
    error = std::string("cannot create a temporary file beside it: ") + std::strerror(errno);
    return false;
  }
  size_t written = 0;
  while (written < content.size()) {
    ssize_t n = ::write(fd, content.data() + written, content.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error = std::string("cannot write: ") + std::strerror(errno);
      ::close(fd);
      std::remove(name.data());
      return false;
    }
    written += static_cast<size_t>(n);
  }
  // mkstemp creates 0600; an output file should get the usual permissions.
  ::fchmod(fd, 0644);
  if (::close(fd) != 0 || std::rename(name.data(), path.c_str()) != 0) {
    error = std::string("cannot write: ") + std::strerror(errno);
    std::remove(name.data());
    return false;
  }
  return true;
}

}  // namespace openplx::cli
