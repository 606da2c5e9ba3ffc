#include "mjcf_emitter/mesh_input_file.h"

#include <linux/magic.h>
#include <sys/stat.h>
#include <sys/vfs.h>

#include <cerrno>
#include <system_error>
#include <utility>

namespace openplx::mjcf {
namespace {

// File systems whose files the kernel makes up as they are read: a regular file there is no mesh.
const char* kernel_file_system(const std::string& path) {
  static const std::pair<unsigned long, const char*> kKernel[] = {
      {PROC_SUPER_MAGIC, "proc"},       {SYSFS_MAGIC, "sysfs"},
      {DEBUGFS_MAGIC, "debugfs"},       {TRACEFS_MAGIC, "tracefs"},
      {SECURITYFS_MAGIC, "securityfs"}, {CGROUP_SUPER_MAGIC, "cgroup"},
      {CGROUP2_SUPER_MAGIC, "cgroup2"}, {BPF_FS_MAGIC, "bpf"},
      {EFIVARFS_MAGIC, "efivarfs"},     {PSTOREFS_MAGIC, "pstore"}};
  struct statfs fs {};
  if (::statfs(path.c_str(), &fs) != 0) return nullptr;
  for (const auto& [magic, name] : kKernel)
    if (static_cast<unsigned long>(fs.f_type) == magic) return name;
  return nullptr;
}

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "no regular file";
}

}  // namespace

std::string mesh_input_file_problem(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    return "cannot be read (" + std::generic_category().message(errno) + ")";
  if (!S_ISREG(st.st_mode)) return std::string("is ") + kind_of(st.st_mode) + ", not a regular file";
  if (const char* fs = kernel_file_system(path))
    return std::string("lies in a kernel file system (") + fs + "), not on a disk";
  if (static_cast<uintmax_t>(st.st_size) > kMaxMeshFileBytes)
    return "is " + std::to_string(st.st_size) + " bytes, more than the " +
           std::to_string(kMaxMeshFileBytes >> 20) + " MiB a mesh file may be";
  return {};
}

}  // namespace openplx::mjcf
