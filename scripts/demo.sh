#!/usr/bin/env bash
# Installs the dependencies, builds mfadvr, and runs the main job on a built-in default:
# `mfadvr demo` encodes the Marschner-Lobb function (41^3 samples) into an interpolating cubic
# MFA model, renders the analytic truth, the model and trilinear filtering of the same samples
# with one camera and transfer function, writes the images and a side-by-side montage, and prints
# each method's PSNR/SSIM against the truth and its render time.
set -euo pipefail
cd "$(dirname "$0")/.."

./scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" --target mfadvr

out=${MFADVR_DEMO_OUT:-out/demo}
build/release/src/app/mfadvr demo --out "$out" --size 1000x1000
