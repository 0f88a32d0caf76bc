#!/usr/bin/env bash
# run_mpi_compare.sh SCENE OUT_DIR: renders SCENE (pv_scene.py) with pvbatch on 1, 2 and 4 MPI
# ranks and requires the 2- and 4-rank images to be within 40 dB PSNR of the 1-rank image.
# Exit 77 (skipped) when pvbatch or mpiexec is missing.
set -euo pipefail
scene=$1
out=$2
here=$(cd "$(dirname "$0")" && pwd)
for tool in pvbatch mpiexec xvfb-run; do
  if ! command -v "$tool" >/dev/null; then
    echo "skipped: $tool is not installed"
    exit 77
  fi
done
mkdir -p "$out"
# Open MPI refuses to start as root unless told; four ranks may outnumber the cores.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export PYTHONPATH="$here${PYTHONPATH:+:$PYTHONPATH}"
for ranks in 1 2 4; do
  start=$EPOCHREALTIME
  # A 24-bit screen, and no X display test: ParaView's per-rank probe of the display now and
  # then fails when several ranks start at once on one Xvfb, and the view then waits for
  # remote rendering that it has disabled (pvbatch --help recommends the flag for this).
  timeout 300 xvfb-run -a -s "-screen 0 1280x1024x24" \
    mpiexec --oversubscribe -np "$ranks" pvbatch --disable-xdisplay-test "$here/pv_scene.py" "$scene" \
    "$out/$scene-$ranks.png"
  awk -v s="$start" -v e="$EPOCHREALTIME" -v n="$ranks" -v c="$scene" \
    'BEGIN { printf "%s on %d rank(s): %.1f s\n", c, n, e - s }'
done
"$PVPYTHON" "$here/compare_images.py" 40 "$out/$scene-1.png" "$out/$scene-2.png" \
  "$out/$scene-4.png"
