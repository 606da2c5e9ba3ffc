// URDF to MJCF as a user runs it: `openplx2mjcf robot.urdf -o robot.xml` against MuJoCo's own
// `mujoco-compile robot.urdf robot.xml`, each a whole process, on bullet3's kuka_iiwa (meshes) and r2d2
// (primitives). Wall time per process (manual time) and the child's CPU time (user + system) as a counter.
// Target: ours <= 1x MuJoCo's.
#include <benchmark/benchmark.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <fcntl.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

extern char** environ;

namespace fs = std::filesystem;

namespace {

const fs::path kCorpus = fs::path(OPENPLX_CORPUS_DIR) / "urdf" / "bullet3";
const fs::path kOut = fs::temp_directory_path() / "openplx_urdf_bench";

// Runs `argv` with its output discarded; returns the child's CPU seconds, or -1 when it failed.
double run(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return -1;
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return -1;
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

// MuJoCo reads a URDF's meshes relative to the working directory unless told: the same copy the parity test
// gives it, with meshdir set and every link kept (fusestatic off, as ours).
fs::path mujoco_copy(const fs::path& urdf) {
  std::ifstream in(urdf);
  std::stringstream text;
  text << in.rdbuf();
  std::string xml = text.str();
  const size_t open_end = xml.find('>', xml.find("<robot"));
  xml.insert(open_end + 1, "<mujoco><compiler fusestatic=\"false\" strippath=\"false\" meshdir=\"" +
                               urdf.parent_path().string() + "\"/></mujoco>");
  fs::create_directories(kOut);
  const fs::path copy = kOut / (urdf.stem().string() + ".mujoco.urdf");
  std::ofstream(copy) << xml;
  return copy;
}

void measure(benchmark::State& state, const std::vector<std::string>& argv) {
  double cpu = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const double seconds = run(argv);
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (seconds < 0) {
      state.SkipWithError(("failed: " + argv[0] + " " + argv[1]).c_str());
      return;
    }
    cpu += seconds;
  }
  state.counters["cpu_ms"] = benchmark::Counter(1e3 * cpu / static_cast<double>(state.iterations()));
}

void BM_Openplx2Mjcf(benchmark::State& state, const fs::path& urdf) {
  fs::create_directories(kOut);
  measure(state, {OPENPLX2MJCF_BINARY, urdf.string(), "-o", (kOut / "ours.xml").string()});
}

void BM_MujocoCompile(benchmark::State& state, const fs::path& urdf) {
  measure(state, {MUJOCO_COMPILE_BINARY, mujoco_copy(urdf).string(), (kOut / "theirs.xml").string()});
}

}  // namespace

BENCHMARK_CAPTURE(BM_Openplx2Mjcf, kuka_iiwa, kCorpus / "kuka_iiwa" / "model.urdf")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MujocoCompile, kuka_iiwa, kCorpus / "kuka_iiwa" / "model.urdf")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Openplx2Mjcf, r2d2, kCorpus / "r2d2.urdf")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MujocoCompile, r2d2, kCorpus / "r2d2.urdf")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
