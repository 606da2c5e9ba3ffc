#!/usr/bin/env bash
# Installs the Debian packages the build needs, only those missing. Used by ./run.sh, ./test.sh, tools/fuzz.sh.
#   tools/install-deps.sh            what ./run.sh builds and runs: the converter, openplx-sim, their modules
#   tools/install-deps.sh --tests    also the test suite's and benchmarks' (GoogleTest, Google Benchmark,
#                                    clang-format, GNU time, Python's jsonschema), Node and the pinned
#                                    mujoco-js, ajv and ajv-cli, Xvfb, GLFW
#   tools/install-deps.sh --fuzz     also clang and its sanitizer runtime (libFuzzer), and GoogleTest: the
#                                    fuzz targets are built in the sanitizer build, with the tests
set -euo pipefail
cd "$(dirname "$0")/.."

# libmujoco-samples: mujoco-testspeed (./run.sh), mujoco-compile and mujoco-simulate (benchmarks, tests).
packages=(cmake make g++ pkg-config
  libmujoco-dev libqhull-dev libmujoco-samples libeigen3-dev liburdfdom-dev libtinyxml2-dev libassimp-dev
  nlohmann-json3-dev)
tests=0
for arg in "$@"; do
  case "$arg" in
    --fuzz) packages+=(clang libclang-rt-14-dev libgtest-dev) ;;
    --tests) tests=1 ;;
  esac
done
if [[ $tests -eq 1 ]]; then
  packages+=(libgtest-dev libbenchmark-dev clang-format time)
  # The depfile's readers (tests/tools/depfile_readers_test.cpp: GNU Make and Ninja read it back), and
  # script(1) for a pseudo-terminal (tests/tools/check_progress_test.cpp).
  packages+=(make ninja-build bsdutils)
  command -v node >/dev/null || packages+=(nodejs)
  command -v npm >/dev/null || packages+=(npm)
  # A virtual X server and screen grabs for the samples' screenshots in mujoco-simulate (viewer_screenshots).
  packages+=(xvfb x11-apps imagemagick xdotool)
  # Python's JSON Schema validator, one of the three the manifest schema is checked in (tests/mjcf).
  packages+=(python3-jsonschema)
  # An OpenGL window for MuJoCo's offscreen renderer in the render tests (tests/render, on that Xvfb).
  packages+=(libglfw3-dev)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
install_packages() {
  echo "Installing missing packages: ${missing[*]}"
  local sudo_cmd=()
  if [[ $(id -u) -ne 0 ]]; then
    command -v sudo >/dev/null || { echo "error: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
    sudo_cmd=(sudo)
  fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
}
[[ ${#missing[@]} -eq 0 ]] || install_packages

# mujoco-js, ajv and ajv-cli, exactly as tests/current_mujoco/package-lock.json pins them (npm's registry; not
# at build time); again when any of them is missing.
node_modules_missing=0
for module in mujoco-js ajv ajv-cli; do
  [[ -f tests/current_mujoco/node_modules/$module/package.json ]] || node_modules_missing=1
done
if [[ $tests -eq 1 && $node_modules_missing -eq 1 ]]; then
  echo "Installing mujoco-js, ajv and ajv-cli for tests/current_mujoco"
  (cd tests/current_mujoco && npm ci --no-audit --no-fund --loglevel=error)
fi
