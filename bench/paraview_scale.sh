#!/usr/bin/env bash
# ParaView scale figures (docs/benchmarks.md): the MFA plugin encodes and renders an N^3
# Wavelet (degree 2, one control point per sample) on 1 and 2 MPI ranks.
#   bench/paraview_scale.sh [N=512] [IMAGE=800] [RANKS="1 2"] [RAW]
# RAW: an N^3 uint8 raw volume (bench/make_large_volume.py N) instead of the float Wavelet.
# MFADVR_VOLUME_READER=1: RAW is any volume file, read by MFA Volume Reader (each rank its piece).
# MFADVR_PLUGIN: another build of the plugin (default: the paraview preset's).
# MFADVR_PASS_INPUT_VALUES=1: the encoder's PassInputValues on (the output holds the input's
# samples, not the model evaluated on the grid).
# MPIEXEC_FLAGS: options for mpiexec (default "--bind-to none"; "" for Open MPI's binding).
# Needs the paraview preset built (scripts/install-deps.sh --paraview first).
set -euo pipefail
raw=${4:+$(realpath "$4")}  # before the cd: relative to the caller
if [ -n "$raw" ] && [ ! -f "$raw" ]; then
  echo "paraview_scale.sh: $4: no such file (bench/make_large_volume.py N writes one)" >&2
  exit 1
fi
cd "$(dirname "$0")/.."
n=${1:-512}
size=${2:-800}
ranks=${3:-"1 2"}
export MFADVR_PLUGIN=${MFADVR_PLUGIN:-$PWD/build/paraview/lib/paraview-plugins/MFADVR/MFADVR.so}
export MFADVR_PARAVIEW_PYTHONPATH=$PWD/build/deps/python3-paraview/usr/lib/python3/dist-packages
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Open MPI binds each rank to one core when there are at most two ranks, which leaves a rank's
# TBB threads (the encoder, the ray caster) one core; unbound, they use every core.
MPIEXEC_FLAGS=${MPIEXEC_FLAGS---bind-to none}
for r in $ranks; do
  start=$EPOCHREALTIME
  # shellcheck disable=SC2086  # MPIEXEC_FLAGS: words for mpiexec
  xvfb-run -a -s "-screen 0 1280x1024x24" mpiexec --oversubscribe $MPIEXEC_FLAGS -np "$r" \
    pvbatch --symmetric --disable-xdisplay-test bench/paraview_scale.py "$n" "$size" ${raw:+"$raw"} 2>&1 |
    grep -E "rank [0-9]+ of|Error" || true
  awk -v s="$start" -v e="$EPOCHREALTIME" -v r="$r" \
    'BEGIN { printf "%d rank(s): %.1f s in all (start-up included)\n", r, e - s }'
done
