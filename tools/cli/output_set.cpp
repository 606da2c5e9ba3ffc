#include "tools/cli/output_set.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>

namespace openplx::cli {
namespace {

namespace fs = std::filesystem;

struct Identity {
  dev_t device;
  ino_t inode;
  bool operator==(const Identity&) const = default;
};

// stat() follows links: an output that is a symbolic link to an input counts as that input.
std::optional<Identity> identity(const fs::path& path) {
  struct stat s;
  if (::stat(path.c_str(), &s) != 0) return std::nullopt;
  return Identity{s.st_dev, s.st_ino};
}

// The same place by name once `..`, `.` and links in its folders are resolved, for outputs not there yet.
fs::path place(const fs::path& path) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
  return ec ? fs::absolute(path, ec).lexically_normal() : p;
}

std::string errno_text(int e) {
  return std::strerror(e);
}

}  // namespace

std::string outputs_clash(const std::vector<NamedOutput>& outputs, const std::vector<std::string>& inputs,
                          std::string& bad) {
  std::vector<std::pair<Identity, std::string>> read;
  for (const std::string& input : inputs) {
    if (auto id = identity(input)) read.emplace_back(*id, input);
  }
  for (size_t k = 0; k < outputs.size(); ++k) {
    const NamedOutput& out = outputs[k];
    const std::optional<Identity> id = identity(out.path);
    if (id) {
      for (const auto& [input_id, input] : read) {
        if (input_id != *id) continue;
        bad = out.path;
        return "refusing to write " + out.which + " over a file this run read (" + input +
               "): it would be lost; choose another name";
      }
    }
    for (size_t j = 0; j < k; ++j) {
      const NamedOutput& other = outputs[j];
      const std::optional<Identity> other_id = identity(other.path);
      if (place(out.path) == place(other.path) || (id && other_id && *id == *other_id)) {
        bad = out.path;
        return "refusing to write " + out.which + " here: " + other.which + " writes this file too (" +
               other.path + "); give each output its own name";
      }
    }
  }
  return "";
}

OutputSet::~OutputSet() {
  if (!committed_) undo();
}

bool OutputSet::folder(const fs::path& path, std::string& error) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) return true;
  if (!fs::create_directory(path, ec)) {
    error = "cannot create the folder " + path.string() + ": " + ec.message();
    return false;
  }
  folders_made_.push_back(path);
  return true;
}

bool OutputSet::stage(const fs::path& path, std::string_view content, std::string& error) {
  return stage(
      path, [content](const PieceWriter& write) { write(content); }, error);
}

bool OutputSet::stage(const fs::path& path, const std::function<void(const PieceWriter&)>& produce,
                      std::string& error) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {  // found now rather than at the rename, after others were renamed
    error = "is a directory";
    return false;
  }
  std::string temporary;
  if (!write_temporary_file(path.string(), produce, temporary, error)) return false;
  staged_.push_back({path, temporary, {}, false});
  return true;
}

bool OutputSet::stage_stream(const fs::path& path, std::ofstream& stream, std::string& error) {
  if (!stage(
          path, [](const PieceWriter&) {}, error))
    return false;
  stream.open(staged_.back().temporary, std::ios::binary | std::ios::trunc);
  if (!stream) {
    error = "cannot write its temporary file";
    return false;
  }
  return true;
}

bool OutputSet::commit(std::string& error) {
  // A hard link to each old file first, so that a rename failing halfway can put the old ones back.
  for (Staged& s : staged_) {
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(s.target, ec))) continue;
    s.backup = s.temporary.string() + ".old";
    // Without hard links (some file systems) a failed rename cannot put this old file back.
    if (::link(s.target.c_str(), s.backup.c_str()) != 0) s.backup.clear();
  }
  for (Staged& s : staged_) {
    if (std::rename(s.temporary.c_str(), s.target.c_str()) != 0) {
      error = "cannot write " + s.target.string() + ": " + errno_text(errno);
      undo();
      committed_ = true;  // undone already
      return false;
    }
    s.renamed = true;
  }
  for (Staged& s : staged_) {
    if (s.backup.empty()) continue;
    std::error_code ec;
    fs::remove(s.backup, ec);
  }
  committed_ = true;
  return true;
}

void OutputSet::undo() {
  for (auto it = staged_.rbegin(); it != staged_.rend(); ++it) {
    std::error_code ec;
    if (it->renamed) {
      if (!it->backup.empty()) {
        fs::rename(it->backup, it->target, ec);
      } else {
        fs::remove(it->target, ec);
      }
    } else {
      fs::remove(it->temporary, ec);
      if (!it->backup.empty()) fs::remove(it->backup, ec);
    }
  }
  staged_.clear();
  for (auto it = folders_made_.rbegin(); it != folders_made_.rend(); ++it) {
    std::error_code ec;
    fs::remove(*it, ec);  // only if empty: nothing of anyone else's goes
  }
  folders_made_.clear();
}

}  // namespace openplx::cli
