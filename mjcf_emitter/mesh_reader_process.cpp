#include "mjcf_emitter/mesh_reader_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <system_error>
#include <utility>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
#define OPENPLX_READER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define OPENPLX_READER_ASAN 1
#endif
#endif
#ifdef OPENPLX_READER_ASAN
#include <sanitizer/asan_interface.h>
#include <sanitizer/common_interface_defs.h>
#endif

namespace openplx::mjcf {
namespace {

// A child whose AddressSanitizer caught a bad access exits with this: only instrumented code (ours, not the
// system's assimp) is caught so, so the parent aborts and the test or fuzzer that ran it reports it.
[[maybe_unused]] constexpr int kSanitizerExit = 86;

const char* signal_name(int s) {
  static const std::pair<int, const char*> kNames[] = {
      {SIGSEGV, "SIGSEGV"}, {SIGBUS, "SIGBUS"}, {SIGABRT, "SIGABRT"}, {SIGFPE, "SIGFPE"},  {SIGILL, "SIGILL"},
      {SIGTRAP, "SIGTRAP"}, {SIGSYS, "SIGSYS"}, {SIGKILL, "SIGKILL"}, {SIGPIPE, "SIGPIPE"}};
  for (const auto& [number, name] : kNames)
    if (number == s) return name;
  return nullptr;
}

#ifdef OPENPLX_READER_ASAN
void on_sanitizer_death() {
  if (__asan_report_present()) ::_exit(kSanitizerExit);
}
#endif

// A field of /proc/<pid>/statm in bytes: 0 the address space mapped, 1 the memory resident.
uint64_t statm_bytes(const std::string& pid, int field) {
  char text[128] = {};
  const int fd = ::open(("/proc/" + pid + "/statm").c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0;
  const ssize_t n = ::read(fd, text, sizeof(text) - 1);
  ::close(fd);
  if (n <= 0) return 0;
  char* at = text;
  uint64_t pages = 0;
  for (int k = 0; k <= field; ++k) pages = std::strtoull(at, &at, 10);
  return pages * static_cast<uint64_t>(::sysconf(_SC_PAGESIZE));
}

// Lowers the soft limit of `resource` to `value` (the hard one stays: it may not be raised again).
void lower_limit(int resource, uint64_t value) {
  rlimit limit{};
  if (::getrlimit(resource, &limit) != 0) return;
  if (limit.rlim_max != RLIM_INFINITY) value = std::min<uint64_t>(value, limit.rlim_max);
  if (limit.rlim_cur != RLIM_INFINITY && limit.rlim_cur <= value) return;
  limit.rlim_cur = value;
  ::setrlimit(resource, &limit);
}

// The child's set-up: the parent's handlers (a fuzzer's, a sanitizer's, the user program's) would catch
// the reader's crash and report it as their own; the default ones end the child, which the parent reports.
void enter_child(const MeshReaderLimits& limits) {
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  for (int s : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTRAP, SIGSYS, SIGXCPU, SIGXFSZ, SIGPIPE, SIGALRM,
                SIGTERM, SIGINT, SIGHUP, SIGUSR1, SIGUSR2})
    ::sigaction(s, &default_action, nullptr);
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  lower_limit(RLIMIT_CORE, 0);  // a crash writes no core file
  lower_limit(RLIMIT_CPU, limits.seconds);
#ifdef OPENPLX_READER_ASAN
  __sanitizer_set_death_callback(on_sanitizer_death);
#else
  // Above what is mapped already: the child inherits the parent's mappings.
  if (const uint64_t mapped = statm_bytes("self", 0))
    lower_limit(RLIMIT_AS, mapped + (limits.memory_mib << 20));
#endif
  // The converter may be writing the MJCF to stdout: nothing a reader prints may land in it.
  if (const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC); null >= 0) {
    ::dup2(null, STDOUT_FILENO);
    ::close(null);
  }
}

std::string failure_of(int status, const MeshReaderLimits& limits) {
  if (WIFSIGNALED(status)) {
    const int s = WTERMSIG(status);
    if (s == SIGXCPU)
      return "the mesh reader took longer than " + std::to_string(limits.seconds) + " s of CPU time on it";
    const char* name = signal_name(s);
    return "the mesh reader crashed on it (signal " + std::to_string(s) +
           (name ? std::string(", ") + name : "") + ")";
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) != 0) {
#ifdef OPENPLX_READER_ASAN
    if (WEXITSTATUS(status) == kSanitizerExit) {
      std::fputs("the mesh reader's child process hit an AddressSanitizer report (above)\n", stderr);
      std::abort();
    }
#endif
    return "the mesh reader failed on it (exit status " + std::to_string(WEXITSTATUS(status)) + ")";
  }
  return {};
}

void write_all(int fd, const void* data, size_t size) {
  const char* at = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, at, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) ::_exit(3);  // the parent is gone or stopped listening
    at += n;
    size -= static_cast<size_t>(n);
  }
}

// The answer on the pipe: 'M' or 'P', two counts, then the mesh's floats and indices, or the problem text.
void write_answer(int fd, char kind, uint64_t first, uint64_t second) {
  char header[17];
  header[0] = kind;
  std::memcpy(header + 1, &first, 8);
  std::memcpy(header + 9, &second, 8);
  write_all(fd, header, sizeof(header));
}

std::string decode_answer(const std::string& bytes, TriangleMesh& mesh, const MeshReaderLimits& limits) {
  if (bytes.empty()) return "the mesh reader ended without an answer";
  if (bytes.size() < 17) return "the mesh reader's answer is cut short";
  uint64_t first = 0, second = 0;
  std::memcpy(&first, bytes.data() + 1, 8);
  std::memcpy(&second, bytes.data() + 9, 8);
  const uint64_t body = bytes.size() - 17;
  if (bytes[0] == 'P' && first == body) {
    const std::string problem = bytes.substr(17);
    if (problem == OPENPLX_MESH_OUT_OF_MEMORY)
      return "the mesh reader needed more than " + std::to_string(limits.memory_mib) + " MiB for it";
    return problem.empty() ? "the mesh reader gave no reason" : problem;
  }
  if (bytes[0] != 'M' || first > body / 4 || second > body / 4 || 4 * (first + second) != body ||
      first % 3 != 0 || second % 3 != 0)
    return "the mesh reader's answer is damaged";
  mesh.vertices.resize(first);
  mesh.faces.resize(second);
  std::memcpy(mesh.vertices.data(), bytes.data() + 17, 4 * first);
  std::memcpy(mesh.faces.data(), bytes.data() + 17 + 4 * first, 4 * second);
  for (uint32_t index : mesh.faces) {
    if (index >= first / 3) {
      mesh = TriangleMesh{};
      return "the mesh reader's answer names vertex " + std::to_string(index) + " of " +
             std::to_string(first / 3);
    }
  }
  return {};
}

}  // namespace

ChildRun run_in_child(const std::function<void(int fd)>& work, const MeshReaderLimits& limits) {
  ChildRun run;
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    run.failure = "the mesh reader cannot start (no pipe: " + std::generic_category().message(errno) + ")";
    return run;
  }
  ::fcntl(fds[0], F_SETPIPE_SZ, 1 << 20);  // fewer turns for a large mesh; a smaller pipe is only slower
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    enter_child(limits);
    try {
      work(fds[1]);
    } catch (...) {  // never back into the parent's code: the child would go on converting
      ::_exit(4);
    }
    ::_exit(0);  // no exit handlers, no flushing of the parent's buffered output
  }
  ::close(fds[1]);
  if (pid < 0) {
    ::close(fds[0]);
    run.failure = "the mesh reader cannot start (no process: " + std::generic_category().message(errno) + ")";
    return run;
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(limits.seconds);
  const uint64_t most = limits.memory_mib << 20;
  std::vector<char> chunk(1 << 16);
  bool timed_out = false, too_long = false, too_big = false;
#ifdef OPENPLX_READER_ASAN
  // No address-space limit under the sanitizer: the child's resident memory is watched instead.
  const uint64_t start_resident = statm_bytes(std::to_string(pid), 1);
  constexpr long long kTick = 50;
#else
  constexpr long long kTick = INT_MAX;
#endif
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
#ifdef OPENPLX_READER_ASAN
    if (statm_bytes(std::to_string(pid), 1) > start_resident + (limits.memory_mib << 20)) {
      too_big = true;
      break;
    }
#endif
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), kTick)));
    if (ready <= 0) continue;  // interrupted, or the deadline is checked again
    const ssize_t n = ::read(fds[0], chunk.data(), chunk.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // the child closed its end: it is done
    run.output.append(chunk.data(), static_cast<size_t>(n));
    if (run.output.size() > most) {
      too_long = true;
      break;
    }
  }
  ::close(fds[0]);
  if (timed_out || too_long || too_big) ::kill(pid, SIGKILL);
  int status = 0;
  pid_t waited;
  do waited = ::waitpid(pid, &status, 0);
  while (waited < 0 && errno == EINTR);
  if (timed_out) {
    run.failure = "the mesh reader took longer than " + std::to_string(limits.seconds) + " s on it";
  } else if (too_big) {
    run.failure = "the mesh reader needed more than " + std::to_string(limits.memory_mib) + " MiB for it";
  } else if (too_long) {
    run.failure = "the mesh reader answered with more than " + std::to_string(limits.memory_mib) + " MiB";
  } else if (waited == pid) {  // else the program reaps its children itself (SIGCHLD ignored): the answer
    run.failure = failure_of(status, limits);  // read decides
  }
  return run;
}

std::string read_mesh_in_child(OpenplxReadMeshFunction read, const std::string& path, TriangleMesh& mesh,
                               const MeshReaderLimits& limits) {
  mesh = TriangleMesh{};
  const ChildRun run = run_in_child(
      [&](int fd) {
        const OpenplxMeshSink sink{
            &fd,
            [](void* context, const float* vertices, size_t vertex_floats, const uint32_t* faces,
               size_t indices) {
              const int out = *static_cast<int*>(context);
              write_answer(out, 'M', vertex_floats, indices);
              write_all(out, vertices, 4 * vertex_floats);
              write_all(out, faces, 4 * indices);
            },
            [](void* context, const char* message, size_t size) {
              const int out = *static_cast<int*>(context);
              write_answer(out, 'P', size, 0);
              write_all(out, message, size);
            },
        };
        read(path.c_str(), &sink);
      },
      limits);
  if (!run.failure.empty()) return run.failure;
  return decode_answer(run.output, mesh, limits);
}

std::string read_mesh_in_process(OpenplxReadMeshFunction read, const std::string& path, TriangleMesh& mesh) {
  struct Result {
    TriangleMesh* mesh;
    char kind = 0;  // as on the pipe: 'M' a mesh, 'P' a problem
    std::string problem;
  } result{&mesh, 0, {}};
  const OpenplxMeshSink sink{
      &result,
      [](void* context, const float* vertices, size_t vertex_floats, const uint32_t* faces, size_t indices) {
        auto& r = *static_cast<Result*>(context);
        r.mesh->vertices.assign(vertices, vertices + vertex_floats);
        r.mesh->faces.assign(faces, faces + indices);
        r.kind = 'M';
      },
      [](void* context, const char* message, size_t size) {
        auto& r = *static_cast<Result*>(context);
        r.problem.assign(message, size);
        r.kind = 'P';
      },
  };
  mesh = TriangleMesh{};
  read(path.c_str(), &sink);
  if (result.kind == 'M') return {};
  if (result.kind == 0) return "the mesh reader ended without an answer";
  if (result.problem == OPENPLX_MESH_OUT_OF_MEMORY) return "the mesh reader ran out of memory on it";
  return result.problem.empty() ? "the mesh reader gave no reason" : result.problem;
}

}  // namespace openplx::mjcf
