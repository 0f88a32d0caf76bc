#!/usr/bin/env bash
# Installs the dependencies, builds, and runs the whole test suite: the release build, then the
# AddressSanitizer + UndefinedBehaviorSanitizer build of the same tests, then short libFuzzer
# runs of the file parsers, then the ParaView plugin (built against Debian's ParaView 5.11, its
# tests under pvpython and MPI pvbatch). Exits non-zero on the first failure.
set -euo pipefail
cd "$(dirname "$0")/.."

./scripts/install-deps.sh --paraview

jobs=$(nproc)
step() { printf '\n== %s\n' "$*"; }

step "release build + tests"
cmake --preset release
cmake --build --preset release -j "$jobs"
ctest --preset release -j "$jobs"

step "asan+ubsan build + tests"
cmake --preset asan
cmake --build --preset asan -j "$jobs"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --preset asan -j "$jobs"

step "fuzzing the parsers (libFuzzer, 20 s each)"
cmake --preset fuzz
cmake --build --preset fuzz -j "$jobs"
ctest --preset fuzz

step "ParaView plugin build + tests (pvpython, pvbatch on 1, 2 and 4 MPI ranks)"
cmake --preset paraview
cmake --build --preset paraview -j "$jobs"
ctest --preset paraview

step "all tests passed"
