#!/usr/bin/env bash
# Installs the dependencies, builds, and runs the whole test suite: the release build, then the
# AddressSanitizer + UndefinedBehaviorSanitizer build of the same tests, then short libFuzzer
# runs of the file parsers, then the ParaView plugin (built against Debian's ParaView 5.11, its
# tests under pvpython and MPI pvbatch). Exits non-zero on the first failure.
set -euo pipefail
cd "$(dirname "$0")/.."

jobs=$(nproc)
# Each stage's wall time, printed as it ends and again, with the total, at the end.
stages=()
stage_name=""
stage_start=0
run_start=$SECONDS
end_stage() {
  if [ -n "$stage_name" ]; then
    local took=$((SECONDS - stage_start))
    stages+=("$(printf '%4d min %02d s  %s' $((took / 60)) $((took % 60)) "$stage_name")")
    printf '== %s: %d min %02d s\n' "$stage_name" $((took / 60)) $((took % 60))
  fi
}
step() {
  end_stage
  stage_name="$*"
  stage_start=$SECONDS
  printf '\n== %s\n' "$*"
}

step "Debian packages (install-deps.sh --paraview)"
./scripts/install-deps.sh --paraview

step "release: build"
# The CUDA kernels are compiled once, as PTX for compute 7.5: the check that they compile (their
# tests skip without a GPU), in a third of the time of the four targets a release build makes.
# The plain configure after the tests returns the build to those (CMakeLists.txt), so that the
# next build of the release preset (demo.sh, pack-gpu-check.sh) makes GPU code as usual.
MFADVR_CUDA_ARCHITECTURES=75-virtual cmake --preset release
MFADVR_CUDA_ARCHITECTURES=75-virtual cmake --build --preset release -j "$jobs"
step "release: tests"
ctest --preset release -j "$jobs"
cmake --preset release >/dev/null

step "asan+ubsan: build"
cmake --preset asan
cmake --build --preset asan -j "$jobs"
step "asan+ubsan: tests"
# Two whole studies (a quick paper evaluation, a query study: 61 s and 38 s under the sanitizers,
# code every other test reaches too) run in the release stage only. The CUDA backend is built in
# the release stage only (the asan preset leaves it out; its tests skip without a GPU).
# A failing test is run once more before the stage fails (--repeat until-pass:2): LeakSanitizer's
# tracer now and then dies of a signal at a VTK program's exit ("Tracer caught signal 11"),
# outside our code; a test that fails twice fails the stage, and the log keeps both runs.
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --preset asan -j "$jobs" --repeat until-pass:2 \
    -E '^(CliEval\.QuickTablesWithoutVtkOrPlots|PaperEvaluation\.QueryStudyAloneWritesItsCsvAndReport)$'


step "fuzz: build"
cmake --preset fuzz
cmake --build --preset fuzz -j "$jobs"
step "fuzz: the parsers (libFuzzer, 20 s each)"
# Each fuzzer runs on one core for its time, so two at once do the same fuzzing in half the wall
# time.
ctest --preset fuzz -j "$jobs"

step "ParaView plugin: build"
cmake --preset paraview
cmake --build --preset paraview -j "$jobs"
step "ParaView plugin: tests (pvpython, pvbatch on 1, 2 and 4 MPI ranks)"
ctest --preset paraview

end_stage
stage_name=""
total=$((SECONDS - run_start))
printf '\n== all tests passed in %d min %02d s:\n' $((total / 60)) $((total % 60))
printf '%s\n' "${stages[@]}"
