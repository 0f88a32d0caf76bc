#!/usr/bin/env bash
# Large volumes, measured: for each size N, a generated N^3 uint8 volume (Marschner-Lobb,
# bench/make_large_volume.py, written to DIR once) is encoded with the defaults and with
# `--coding float32`, and the float32 model is rendered once (1000x1000, shaded); wall time and
# peak memory (/usr/bin/time) of each step, and the encoder's own peak-memory line.
#
#   bench/large_volumes.sh [DIR] [SIZES]       # defaults: /tmp/mfadvr-large, "256 512 1024"
#
# MFADVR (default build/release/src/app/mfadvr) picks the binary. A size whose job needs more
# memory than the machine has is reported as refused (the encoder checks before it allocates).
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${MFADVR:-build/release/src/app/mfadvr}
dir=${1:-/tmp/mfadvr-large}
sizes=${2:-256 512 1024}
mkdir -p "$dir"

timed() {  # timed LOG CMD...: runs CMD, prints "seconds peak_bytes" (or "refused")
  local log=$1
  shift
  if /usr/bin/time -f "%e %M" -o "$log.time" "$@" >"$log" 2>&1; then
    read -r s kb <"$log.time"
    echo "$s $((kb * 1024))"
  else
    echo "refused: $(grep -m1 'error' "$log" || tail -1 "$log")" >&2
    echo "refused"
  fi
}

printf '%-6s %-9s %9s %12s %9s %12s %14s\n' N coding "encode s" "peak bytes" "B/sample" \
  "model bytes" "render 1000^2 s"
for n in $sizes; do
  raw="$dir/ml_${n}x${n}x${n}_uint8.raw"
  [ -f "$raw" ] || /usr/bin/python3 bench/make_large_volume.py "$n" "$dir" >/dev/null
  for coding in default float32; do
    model="$dir/ml$n-$coding.mfa"
    opts=()
    [ "$coding" = float32 ] && opts=(--coding float32)
    read -r secs peak < <(timed "$dir/enc-$n-$coding.log" "$exe" encode "$raw" "${opts[@]}" -o "$model")
    if [ "$secs" = refused ]; then
      printf '%-6s %-9s %9s\n' "$n" "$coding" refused
      continue
    fi
    bytes=$(stat -c %s "$model")
    render=-
    if [ "$coding" = float32 ]; then
      read -r rs rpeak < <(timed "$dir/render-$n.log" "$exe" render "$model" --shade \
        --tf step:0.5 --size 1000x1000 -o "$dir/ml$n.png")
      render="$rs ($(python3 -c "print(f'{$rpeak / 1e9:.2f} GB')"))"
    fi
    printf '%-6s %-9s %9s %12s %9.1f %12s %14s\n' "$n" "$coding" "$secs" "$peak" \
      "$(python3 -c "print($peak / $n**3)")" "$bytes" "$render"
  done
done
