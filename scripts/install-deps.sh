#!/usr/bin/env bash
# Installs every Debian package mfadvr needs to build, test and benchmark.
# Safe to run again: apt-get skips what is already present.
#
#   scripts/install-deps.sh              the packages of the library, command, VTK module, tests
#   scripts/install-deps.sh --paraview   also ParaView 5.11 for the plugin (the paraview preset):
#                                        paraview, paraview-dev and Open MPI's mpiexec, and
#                                        python3-paraview unpacked under build/deps (see below)
#
# python3-paraview (ParaView's Python modules, pvpython, and the wrapping files its CMake
# package needs) conflicts with python3-vtk9, which the VTK module's Python bindings need: it is
# downloaded and unpacked into build/deps/python3-paraview rather than installed. The plugin's
# tests point pvpython and pvbatch at it (docs/paraview.md).
set -euo pipefail
cd "$(dirname "$0")/.."

paraview=0
for arg in "$@"; do
  case "$arg" in
    --paraview) paraview=1 ;;
    *) echo "usage: $0 [--paraview]" >&2; exit 2 ;;
  esac
done

packages=(
  build-essential cmake ninja-build pkg-config git ccache mold
  libeigen3-dev libtbb-dev libcli11-dev nlohmann-json3-dev
  libpng-dev zlib1g-dev libzstd-dev libzfp-dev libnetcdf-dev python3-zfpy python3-scipy
  libgtest-dev libgmock-dev libbenchmark-dev
  libvtk9-dev python3-vtk9 python3-dev python3-matplotlib pybind11-dev python3-pytest
  clang libclang-rt-14-dev
  xvfb xauth
  ffmpeg
)
if [ "$paraview" = 1 ]; then
  packages+=(paraview paraview-dev openmpi-bin)
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
else
  echo "install-deps: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

if [ "$paraview" = 1 ]; then
  target=build/deps/python3-paraview
  version=$(dpkg-query -W -f='${Version}' paraview)
  stamp="$target/.version"
  if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$version" ]; then
    echo "install-deps: python3-paraview $version already unpacked in $target"
  else
    echo "install-deps: unpacking python3-paraview $version into $target"
    download=$(mktemp -d)
    (cd "$download" && apt-get download -qq "python3-paraview=$version")
    rm -rf "$target"
    mkdir -p "$target"
    dpkg-deb -x "$download"/python3-paraview_*.deb "$target"
    rm -rf "$download"
    echo "$version" > "$stamp"
  fi
fi
