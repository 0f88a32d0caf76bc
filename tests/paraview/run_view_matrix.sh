#!/usr/bin/env bash
# run_view_matrix.sh SCENE OUT_DIR: renders SCENE (pv_views.py) from 24 cameras with pvbatch on
# 1, 2 and 4 MPI ranks and requires every 2- and 4-rank image to be within 40 dB PSNR of the
# 1-rank image of the same view. Exit 77 (skipped) when pvbatch, mpiexec or xvfb-run is missing.
set -euo pipefail
scene=$1
out=$2
here=$(cd "$(dirname "$0")" && pwd)
PV_TOOLS="pvbatch mpiexec xvfb-run"
source "$here/pv_test_env.sh"
mkdir -p "$out"
for ranks in 1 2 4; do
  start=$EPOCHREALTIME
  timeout 600 xvfb-run -a "${screen[@]}" mpiexec --oversubscribe -np "$ranks" \
    pvbatch --disable-xdisplay-test "$here/pv_views.py" "$scene" "$out/$scene-$ranks"
  awk -v s="$start" -v e="$EPOCHREALTIME" -v n="$ranks" -v c="$scene" \
    'BEGIN { printf "%s, 24 views on %d rank(s): %.1f s\n", c, n, e - s }'
done
"$PVPYTHON" "$here/compare_images.py" --views 40 "$out/$scene-1" "$out/$scene-2" "$out/$scene-4"
