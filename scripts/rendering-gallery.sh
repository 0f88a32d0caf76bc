#!/usr/bin/env bash
# Renders the gallery of docs/rendering.md: every blend mode and classification of a real scan,
# the MFA model beside a grid filter on the same samples (trilinear; tricubic where curvature
# needs second derivatives), and prints each frame's time.
# Usage: scripts/rendering-gallery.sh [VOLUME [ISO [K]]] [OUT_DIR]
#   VOLUME   default ../shared/data/bonsai.nrrd (a 256^3 uint8 CT scan), else the built-in CT
#            head phantom
#   ISO      the isovalue (data units) of the surface pictures: default 80 (the bonsai's
#            branches and pebbles), 300 (the phantom's bone)
#   K        the curvature of full colour of the ridges-valleys picture (1 / world units):
#            default 0.5 for the bonsai (branches of a few voxels), else the preset's default
#   OUT_DIR  default docs/images/gallery
# Needs a release build (cmake --preset release && cmake --build --preset release).
set -euo pipefail
cd "$(dirname "$0")/.."
mfadvr=build/release/src/app/mfadvr
volume=${1:-../shared/data/bonsai.nrrd}
iso=${2:-80}
k=${3:-0.5}
out=${4:-docs/images/gallery}
if [ ! -f "$volume" ] && [ -z "${1:-}" ]; then
  volume=builtin:ct-head
  iso=${2:-300}
  k=${3:-}
fi
ridges=ridges-valleys${k:+:$k}
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$mfadvr" encode "$volume" -o "$tmp/model.mfa" -q > /dev/null

# One camera for every picture: the scan from the front, a little from above.
view=(--size 320x320 --elevation 20 --azimuth 30 --zoom 1.4 -q)
# name | options | the grid filter beside the model
modes=(
  "composite|--tf 0.2:0,0.3:0.5,1:0.9 --colormap viridis --shade|trilinear"
  "max|--blend max --colormap grayscale|trilinear"
  "average|--blend average|trilinear"
  "iso|--blend iso --iso $iso:0.45,0.75,0.35,1 --shade|trilinear"
  "gradient-opacity|--tf 0.2:0,0.3:0.5,1:0.9 --colormap viridis --gradient-opacity 5:0,30:1 --shade|trilinear"
  "curvature|--blend iso --iso $iso:0.9,0.9,0.9,1 --curvature-tf $ridges --shade|tricubic"
  "contours|--blend iso --iso $iso:0.9,0.9,0.9,1 --contours 1 --background 1,1,1 --shade|tricubic"
)
for entry in "${modes[@]}"; do
  IFS='|' read -r name options filter <<< "$entry"
  # shellcheck disable=SC2206
  opts=($options)
  for method in mfa "$filter"; do
    input="$tmp/model.mfa"
    [ "$method" = mfa ] || input="$volume"
    png="$out/$name-$method.png"
    start=$(date +%s.%N)
    "$mfadvr" render "$input" --method "$method" "${view[@]}" "${opts[@]}" -o "$png" > /dev/null
    end=$(date +%s.%N)
    printf '%-18s %-10s %6.2f s  %s\n' "$name" "$method" "$(echo "$end - $start" | bc)" "$png"
  done
done
