#!/usr/bin/env bash
# run_client_server.sh OUT_DIR: renders the encode scene (pv_scene.py) with pvbatch on 1 rank,
# then from pvpython connected to a pvserver running on 2 MPI ranks, and requires the two
# images to be within 40 dB PSNR. Exit 77 (skipped) when a tool is missing.
set -euo pipefail
out=$1
here=$(cd "$(dirname "$0")" && pwd)
PV_TOOLS="pvbatch pvserver mpiexec xvfb-run"
source "$here/pv_test_env.sh"
mkdir -p "$out"
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
