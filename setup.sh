#!/usr/bin/env bash
# Installs what tpf needs from Debian 12's packages (idempotent, silent when all is present).
# Run as root (or with sudo). Used by the README's two commands and by .ci/run.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev liburdfdom-dev libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev
  nlohmann-json3-dev libceres-dev zlib1g-dev
  liborocos-kdl-dev libkdl-parser-dev   # peer for tests and benchmarks only
  clang libclang-rt-14-dev              # fuzzers and sanitizer build (reliability)
  python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest   # the Python module
  python3-matplotlib                    # examples/python (plots)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
