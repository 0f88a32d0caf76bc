#!/usr/bin/env bash
# Renders the pictures of the medical transfer-function presets in docs/transfer-functions.md:
# the built-in CT head phantom (Hounsfield units) with each CT preset, from the side.
# Usage: scripts/tf-preset-pictures.sh [OUT_DIR]   (default docs/images/tf-presets; needs a
# release build: cmake --preset release && cmake --build --preset release)
set -euo pipefail
cd "$(dirname "$0")/.."
mfadvr=build/release/src/app/mfadvr
out=${1:-docs/images/tf-presets}
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$mfadvr" encode builtin:ct-head -o "$tmp/head.mfa" --degree 2 -q > /dev/null
for preset in ct-bone ct-skin ct-soft-tissue ct-vessels; do
  "$mfadvr" render "$tmp/head.mfa" --tf "$preset" --shade --size 320x320 \
    --position 2.4,-3.2,1.0 --focal-point 0,0,0 --view-up 0,0,1 -q -o "$out/$preset.png" \
    > /dev/null
  echo "$out/$preset.png"
done
