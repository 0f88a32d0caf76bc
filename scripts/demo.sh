#!/usr/bin/env bash
# Installs the dependencies, builds mfadvr, and runs the main job on a built-in default:
# encode the Marschner-Lobb function (41^3 samples, degree 3, interpolating) into an MFA model,
# print the fit report, describe the model and query it at the centre.
set -euo pipefail
cd "$(dirname "$0")/.."

./scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" --target mfadvr

out=${MFADVR_DEMO_OUT:-out/demo}
mkdir -p "$out"
mfadvr=build/release/src/app/mfadvr
set -x
"$mfadvr" encode builtin:marschner-lobb -o "$out/marschner-lobb.mfa"
"$mfadvr" info "$out/marschner-lobb.mfa"
"$mfadvr" query "$out/marschner-lobb.mfa" 0 0 0 --derivatives 1
