#!/usr/bin/env bash
# A fuzzing campaign: builds the libFuzzer targets (the `fuzz` preset: clang, ASan+UBSan) and
# runs every target for SECONDS (default 300) from its seed corpus, two at a time, keeping the
# corpus that grows in build/fuzz/campaign/corpus/TARGET and any crashing input in
# build/fuzz/campaign/crashes/TARGET. Prints one line per target: runs, corpus size, findings.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET ...]
# ASAN_OPTIONS from the environment are passed on (e.g. quarantine_size_mb=1024, so that heap
# damage done by uninstrumented code is caught nearer the input that did it).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-300}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(fuzz_model_file fuzz_point_list fuzz_png fuzz_declared_size fuzz_file_loaders)
fi

cmake --preset fuzz > /dev/null
cmake --build --preset fuzz -j "$(nproc)" > /dev/null
out=build/fuzz/campaign
seeds=$out/seeds
mkdir -p "$seeds"
build/fuzz/fuzz/make_seed_corpus "$seeds/fuzz_model_file" "$seeds/fuzz_point_list"
build/fuzz/fuzz/make_png_seed_corpus "$seeds/fuzz_png"
build/fuzz/fuzz/make_reader_seed_corpus "$seeds/fuzz_file_loaders" "$seeds/fuzz_declared_size"

run() {
  local t=$1
  mkdir -p "$out/corpus/$t" "$out/crashes/$t"
  local extra=()
  [ "$t" = fuzz_file_loaders ] && extra=(-timeout=10 -max_len=8192 -detect_leaks=0)
  [ "$t" = fuzz_declared_size ] && extra=(-max_len=4096)
  set +e
  local leaks=1
  [ "$t" = fuzz_file_loaders ] && leaks=0  # VTK's legacy reader leaks on malformed files
  ASAN_OPTIONS="detect_leaks=$leaks${ASAN_OPTIONS:+:$ASAN_OPTIONS}" "build/fuzz/fuzz/$t" -max_total_time="$seconds" "${extra[@]}" \
    -artifact_prefix="$out/crashes/$t/" "$out/corpus/$t" "$seeds/$t" > "$out/$t.log" 2>&1
  local rc=$?
  set -e
  local runs
  runs=$(grep -o 'Done [0-9]* runs' "$out/$t.log" | tail -1 | grep -o '[0-9]*' || echo "?")
  printf '%-20s exit %d, %s runs in %s s, corpus %d inputs, findings %d\n' "$t" "$rc" "$runs" \
    "$seconds" "$(ls "$out/corpus/$t" | wc -l)" "$(ls "$out/crashes/$t" | wc -l)"
}

jobs=0
for t in "${targets[@]}"; do
  run "$t" &
  jobs=$((jobs + 1))
  if [ $jobs -ge 2 ]; then wait -n; jobs=$((jobs - 1)); fi
done
wait
echo "logs: $out/*.log; findings: $out/crashes/"
