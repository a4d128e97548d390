#!/usr/bin/env bash
# Installs the Debian packages lang2manip builds with, only those that are missing.
# Uses sudo when not root. Works on Debian 12 and Ubuntu 22.04/24.04.
# With --fuzz, also what `make fuzz` needs: clang, its libFuzzer and sanitizer runtimes
# (libclang-rt-dev, the distribution's default version) and llvm-symbolizer (llvm) for stack
# traces. With --browser, also what the viewer's browser tests need: Debian's chromium.
# Node.js and npm (the web viewer's build) come from Debian unless an npm is already installed
# (e.g. NodeSource's nodejs, which bundles npm and conflicts with Debian's npm package).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev liburdfdom-dev libassimp-dev libcoin-dev libpugixml-dev libyaml-cpp-dev
  nlohmann-json3-dev libcli11-dev libcpp-httplib-dev libssl-dev
  liborocos-kdl-dev libfcl-dev libccd-dev libompl-dev
  libgtest-dev libgmock-dev libbenchmark-dev
)
if ! command -v npm >/dev/null || ! command -v node >/dev/null; then
  packages+=(nodejs npm)
fi
if [ "${1:-}" = "--fuzz" ]; then
  packages+=(clang libclang-rt-dev llvm)
fi
if [ "${1:-}" = "--browser" ]; then
  packages+=(chromium)
fi

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "lang2manip: installing missing Debian packages: ${missing[*]}"
sudo_command=()
if [ "$(id -u)" -ne 0 ]; then
  if ! command -v sudo >/dev/null; then
    echo "lang2manip: need root or sudo to install: ${missing[*]}" >&2
    exit 1
  fi
  sudo_command=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_command[@]}" apt-get update -qq
"${sudo_command[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
