#!/usr/bin/env bash
# run_mpi_compare.sh SCENE OUT_DIR [views]: renders SCENE with pvbatch on 1, 2 and 4 MPI ranks
# and requires the 2- and 4-rank images to be within 40 dB PSNR of the 1-rank image. SCENE is
# one of pv_scene.py's (one camera), or with `views` a comma-separated list of pv_views.py's (24
# cameras each, all scenes in one pvbatch run per rank count, compared view by view). Exit 77
# (skipped) when pvbatch, mpiexec or xvfb-run is missing.
set -euo pipefail
scene=$1
out=$2
mode=${3:-}
here=$(cd "$(dirname "$0")" && pwd)
PV_TOOLS="pvbatch mpiexec xvfb-run"
source "$here/pv_test_env.sh"
mkdir -p "$out"
script=pv_scene.py
if [ "$mode" = views ]; then script=pv_views.py; fi
for ranks in 1 2 4; do
  if [ "$mode" = views ]; then
    outputs=("$out" "$ranks")
  else
    outputs=("$out/$scene-$ranks.png")
  fi
  start=$EPOCHREALTIME
  timeout 600 xvfb-run -a "${screen[@]}" mpiexec --oversubscribe -np "$ranks" \
    pvbatch --disable-xdisplay-test "$here/$script" "$scene" "${outputs[@]}"
  awk -v s="$start" -v e="$EPOCHREALTIME" -v n="$ranks" -v c="$scene" \
    'BEGIN { printf "%s on %d rank(s): %.1f s\n", c, n, e - s }'
done
if [ "$mode" = views ]; then
  "$PVPYTHON" "$here/compare_images.py" --scene-views 40 "$out" "$scene" 1,2,4
else
  "$PVPYTHON" "$here/compare_images.py" 40 "$out/$scene-1.png" "$out/$scene-2.png" \
    "$out/$scene-4.png"
fi
