// Every file a run writes (openplx2mjcf's MJCF, manifest, mesh folder and depfile; openplx-sim's CSV), as
// one set: each is written to a temporary file beside its target, and only when the whole run succeeded are
// they all renamed into place. A failure anywhere, before or during the renames, leaves no new file and every
// file that was there before as it was. Checked first: no output is a file the run read (by device and inode,
// not by name) and no two outputs are the same file.
#pragma once

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "tools/cli/atomic_file.h"

namespace openplx::cli {

// Why `outputs` cannot be written over `inputs` (the files the run read), or "" when they can: an output
// that is one of the inputs, or the same file as another output. `which` names each output for the message
// ("-o", "--depfile", ...); `bad` gets the offending output's path, where the error is reported.
struct NamedOutput {
  std::string path;
  std::string which;
};
std::string outputs_clash(const std::vector<NamedOutput>& outputs, const std::vector<std::string>& inputs,
                          std::string& bad);

class OutputSet {
 public:
  OutputSet() = default;
  ~OutputSet();  // without commit(): every temporary and every folder made here is removed
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  // A folder the outputs go in, made now when missing (and removed again if the set is not committed).
  bool folder(const std::filesystem::path& path, std::string& error);
  // `path`'s content, written now to a temporary file beside it. The error names `path`'s problem.
  bool stage(const std::filesystem::path& path, std::string_view content, std::string& error);
  bool stage(const std::filesystem::path& path, const std::function<void(const PieceWriter&)>& produce,
             std::string& error);
  // For text written as a run goes (openplx-sim's CSV rows): `stream` opened on a new temporary file beside
  // `path`, to be closed by the caller before commit().
  bool stage_stream(const std::filesystem::path& path, std::ofstream& stream, std::string& error);
  // Every staged file renamed over its target; if one rename fails, the ones done are undone (the old files
  // put back, new ones removed) and `error` says which failed.
  bool commit(std::string& error);

 private:
  struct Staged {
    std::filesystem::path target, temporary, backup;  // backup: a hard link to the old target, if any
    bool renamed = false;
  };
  void undo();
  std::vector<Staged> staged_;
  std::vector<std::filesystem::path> folders_made_;
  bool committed_ = false;
};

}  // namespace openplx::cli
