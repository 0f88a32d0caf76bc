#!/usr/bin/env bash
# Time in empty space, measured by replay (docs/benchmarks.md, "Time in empty space").
#   bench/empty_space_replay.sh [-n RUNS] MODEL.mfa [render options]
# A release build of the committed HEAD with bench/empty_space_replay.patch (built once under
# build/replay, rebuilt when HEAD changes) records, in a render's first frame, where each ray's
# march ahead through empty space stopped and every jump over empty space its integration made;
# with MFADVR_REPLAY set, the later frames replay them instead of reading the flags. The script
# renders the same frames in four ways, alternated RUNS times (default 7), and prints the
# medians of the frames after the first:
#   plain     the renderer as it is
#   way-in    the march ahead replayed
#   replayed  the march ahead and the integration's jumps replayed: no time in empty space left
#   computed  as replayed, but each replayed jump of the integration is computed as well
# Time in empty space = plain - replayed; the integration's jumps = way-in - replayed; of these,
# computing the jumps themselves = computed - replayed. Every way must give the same image
# (checked). Render options default to --shade --size 1000x1000 (the script sets --frames, -o).
# Needs patch(1) and the release build's dependencies (scripts/install-deps.sh).
set -euo pipefail
runs=7
if [[ ${1:-} == -n ]]; then
  runs=$2
  shift 2
fi
if [[ $# -lt 1 || ! -f $1 ]]; then
  echo "usage: bench/empty_space_replay.sh [-n RUNS] MODEL.mfa [render options]" >&2
  echo "  (the model file must exist)" >&2
  exit 2
fi
[[ $runs =~ ^[1-9][0-9]*$ ]] || { echo "RUNS must be a positive integer: $runs" >&2; exit 2; }
model=$(realpath "$1")
shift
options=("$@")
[[ ${#options[@]} -gt 0 ]] || options=(--shade --size 1000x1000)

root=$(cd "$(dirname "$0")/.." && pwd)
work=$root/build/replay
head=$(git -C "$root" rev-parse HEAD)
if [[ ! -f $work/stamp || $(cat "$work/stamp") != "$head" ]]; then
  echo "building the replay build of $head in $work (minutes)" >&2
  fresh=$(mktemp -d)
  git -C "$root" archive HEAD | tar -x -C "$fresh"
  # patch, not git apply: inside this repository's tree, git apply would skip the files.
  patch -s -p1 -d "$fresh" <"$root/bench/empty_space_replay.patch" ||
    { echo "bench/empty_space_replay.patch no longer applies to HEAD: update it" >&2; exit 1; }
  grep -q MFADVR_EMPTY_SPACE_REPLAY "$fresh/src/core/render/RayCaster.h"
  # Only the files that changed are copied, so that the build stays incremental.
  mkdir -p "$work/src"
  (cd "$fresh" && find . -type f) | while read -r f; do
    cmp -s "$fresh/$f" "$work/src/$f" || { mkdir -p "$(dirname "$work/src/$f")" && cp "$fresh/$f" "$work/src/$f"; }
  done
  rm -rf "$fresh"
  cmake -S "$work/src" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_CXX_FLAGS=-DMFADVR_EMPTY_SPACE_REPLAY -DMFADVR_BUILD_TESTS=OFF \
    -DMFADVR_BUILD_BENCH=OFF >"$work/configure.log"
  cmake --build "$work/build" --target mfadvr -j"$(nproc)" >"$work/build.log"
  echo "$head" >"$work/stamp"
fi
bin=$work/build/src/app/mfadvr
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

declare -A mode=([plain]="" [way-in]=1 [replayed]=2 [computed]=4) times
ways=(plain way-in replayed computed)
for ((i = 1; i <= runs; ++i)); do
  for w in "${ways[@]}"; do
    log=$(MFADVR_REPLAY=${mode[$w]} LD_LIBRARY_PATH=$work/build/lib "$bin" render "$model" \
      "${options[@]}" --frames 4 -o "$out/$w.png" 2>&1) || { echo "$log" >&2; exit 1; }
    [[ $i -gt 1 || $w != replayed ]] || grep -h "^replay:" <<<"$log" >&2 || true
    t=$(grep -o "render [0-9.]* s" <<<"$log" | awk '{print $2}')
    [[ -n $t ]] || { echo "$log" >&2; echo "no frame time in the render's report" >&2; exit 1; }
    times[$w]="${times[$w]:-} $t"
  done
  for w in "${ways[@]:1}"; do
    cmp -s "$out/plain.png" "$out/$w.png" ||
      { echo "run $i: the $w image differs from the plain one" >&2; exit 1; }
  done
done
median() { tr ' ' '\n' <<<"$1" | grep . | sort -n | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
declare -A m
for w in "${ways[@]}"; do
  m[$w]=$(median "${times[$w]}")
  printf "%-9s %s s (median of %d:%s)\n" "$w" "${m[$w]}" "$runs" "${times[$w]}"
done
awk -v p="${m[plain]}" -v i="${m[way-in]}" -v r="${m[replayed]}" -v c="${m[computed]}" 'BEGIN {
  printf "time in empty space %.3f s of %.3f s (%.0f %%): the way in %.3f s, the integration'"'"'s jumps %.3f s (computing them %.3f s)\n",
    p - r, p, 100 * (p - r) / p, p - i, i - r, c - r }'
echo "images identical"
