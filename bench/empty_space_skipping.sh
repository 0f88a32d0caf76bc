#!/usr/bin/env bash
# Empty-space skipping, measured: each scene rendered with skipping (the default) and with
# --no-skip, in the same run; frame time (median of the frames after the first), samples
# evaluated and skipped, and whether the two images are identical.
#
#   bench/empty_space_skipping.sh [MFADVR] [DATA_DIR]
#
# MFADVR defaults to build/release/src/app/mfadvr, DATA_DIR to ../shared/data (the bonsai scene
# is left out when bonsai.nrrd is absent). Scenes:
#   - Marschner-Lobb, 128^3 samples, cubic, interpolating; step TF at 0.5; shaded
#   - the same with a narrow band 0.70..0.75 visible (tent TF); unshaded
#   - bonsai CT, 256^3, quadratic on 128^3 control points; step TF at 0.2 that hides the air;
#     shaded
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-build/release/src/app/mfadvr}
data=${2:-../shared/data}
size=${SIZE:-1000x1000}
frames=${FRAMES:-4}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$exe" encode builtin:marschner-lobb:128 -o "$tmp/ml.mfa" -q >/dev/null
scenes=("ml-step|$tmp/ml.mfa|--shade --tf step:0.5 --colormap white"
        "ml-band|$tmp/ml.mfa|--tf tent:0.725:0.05 --colormap viridis")
if [ -f "$data/bonsai.nrrd" ]; then
  "$exe" encode "$data/bonsai.nrrd" --degree 2 --ctrl 128 -o "$tmp/bonsai.mfa" -q >/dev/null
  scenes+=("bonsai-step|$tmp/bonsai.mfa|--shade --tf step:0.2 --azimuth 20 --elevation 10")
fi

field() { python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print(j$1)" "$3"; }
printf '%-12s %10s %10s %8s %12s %12s %10s\n' scene "skip s" "no-skip s" speedup \
  "samples" "skipped" "images"
for scene in "${scenes[@]}"; do
  IFS='|' read -r name model opts <<<"$scene"
  # shellcheck disable=SC2086
  "$exe" render "$model" $opts --size "$size" --frames "$frames" -o "$tmp/$name-skip.png" \
    --json >"$tmp/$name-skip.json"
  # shellcheck disable=SC2086
  "$exe" render "$model" $opts --size "$size" --frames "$frames" --no-skip \
    -o "$tmp/$name-noskip.png" --json >"$tmp/$name-noskip.json"
  on=$(field "['seconds']['render']" "" "$tmp/$name-skip.json")
  off=$(field "['seconds']['render']" "" "$tmp/$name-noskip.json")
  samples=$(field "['samples']" "" "$tmp/$name-skip.json")
  skipped=$(field "['samples_skipped']" "" "$tmp/$name-skip.json")
  if cmp -s "$tmp/$name-skip.png" "$tmp/$name-noskip.png"; then same=identical; else same=DIFFERENT; fi
  printf '%-12s %10.3f %10.3f %7.2fx %12s %12s %10s\n' "$name" "$on" "$off" \
    "$(python3 -c "print($off / $on)")" "$samples" "$skipped" "$same"
done
