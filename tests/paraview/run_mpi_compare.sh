#!/usr/bin/env bash
# run_mpi_compare.sh SCENE OUT_DIR: renders SCENE (pv_scene.py) with pvbatch on 1, 2 and 4 MPI
# ranks and requires the 2- and 4-rank images to be within 40 dB PSNR of the 1-rank image.
# Exit 77 (skipped) when pvbatch, mpiexec or xvfb-run is missing.
set -euo pipefail
scene=$1
out=$2
here=$(cd "$(dirname "$0")" && pwd)
PV_TOOLS="pvbatch mpiexec xvfb-run"
source "$here/pv_test_env.sh"
mkdir -p "$out"
for ranks in 1 2 4; do
  start=$EPOCHREALTIME
  timeout 300 xvfb-run -a "${screen[@]}" mpiexec --oversubscribe -np "$ranks" \
    pvbatch --disable-xdisplay-test "$here/pv_scene.py" "$scene" "$out/$scene-$ranks.png"
  awk -v s="$start" -v e="$EPOCHREALTIME" -v n="$ranks" -v c="$scene" \
    'BEGIN { printf "%s on %d rank(s): %.1f s\n", c, n, e - s }'
done
"$PVPYTHON" "$here/compare_images.py" 40 "$out/$scene-1.png" "$out/$scene-2.png" \
  "$out/$scene-4.png"
