#!/usr/bin/env bash
# run_client_server.sh OUT_DIR: renders the encode scene (pv_scene.py) with pvbatch on 1 rank,
# then from pvpython connected to a pvserver running on 2 MPI ranks, and requires the two
# images to be within 40 dB PSNR. Exit 77 (skipped) when a tool is missing.
set -euo pipefail
out=$1
here=$(cd "$(dirname "$0")" && pwd)
for tool in pvbatch pvserver mpiexec xvfb-run; do
  if ! command -v "$tool" >/dev/null; then
    echo "skipped: $tool is not installed"
    exit 77
  fi
done
mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export PYTHONPATH="$here${PYTHONPATH:+:$PYTHONPATH}"
screen=(-s "-screen 0 1280x1024x24")
timeout 300 xvfb-run -a "${screen[@]}" mpiexec -np 1 pvbatch --disable-xdisplay-test \
  "$here/pv_scene.py" encode "$out/cs-batch.png"

port=$((20000 + RANDOM % 20000))
log="$out/pvserver.log"
timeout 300 xvfb-run -a "${screen[@]}" mpiexec --oversubscribe -np 2 pvserver \
  --server-port="$port" --disable-xdisplay-test >"$log" 2>&1 &
server=$!
trap 'kill "$server" 2>/dev/null || true; pkill -f "server-port=$port" 2>/dev/null || true' EXIT
for _ in $(seq 60); do
  grep -q "Accepting connection" "$log" && break
  sleep 0.5
done
grep -q "Accepting connection" "$log" || { cat "$log"; echo "pvserver did not start"; exit 1; }
MFADVR_PV_SERVER="localhost:$port" timeout 300 xvfb-run -a "${screen[@]}" "$PVPYTHON" \
  "$here/pv_scene.py" encode "$out/cs-client.png"
"$PVPYTHON" "$here/compare_images.py" 40 "$out/cs-batch.png" "$out/cs-client.png"
