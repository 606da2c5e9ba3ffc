#!/usr/bin/env bash
# Installs the Debian packages the build needs, only those missing. Used by ./run.sh and ./test.sh.
#   tools/install-deps.sh            build and test dependencies
#   tools/install-deps.sh --fuzz     also clang and its sanitizer runtime (libFuzzer)
set -euo pipefail

packages=(cmake make g++ pkg-config clang-format
  libmujoco-dev libqhull-dev libmujoco-samples libeigen3-dev liburdfdom-dev libtinyxml2-dev
  libgtest-dev libbenchmark-dev nlohmann-json3-dev)
if [[ "${1:-}" == "--fuzz" ]]; then
  packages+=(clang libclang-rt-14-dev)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "Installing missing packages: ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "error: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
