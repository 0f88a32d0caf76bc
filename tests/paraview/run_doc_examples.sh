#!/usr/bin/env bash
# run_doc_examples.sh DOC.md WORK_DIR BUILD_ROOT HEAD_MODEL: runs the shell and Python examples
# of DOC.md as written (tests/docs/run_doc_examples.py) in WORK_DIR, where `build` is BUILD_ROOT
# (the folder of the presets' build trees) and head.mfa the model the examples open, under
# Xvfb. Exit 77 (skipped) when pvbatch, mpiexec or xvfb-run is missing.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
PV_TOOLS="pvbatch mpiexec xvfb-run python3"
source "$here/pv_test_env.sh"
rm -rf "$2"
timeout 900 xvfb-run -a "${screen[@]}" python3 "$here/../docs/run_doc_examples.py" "$1" "$2" \
  --link "build=$3" --link "head.mfa=$4"
for image in head.png; do
  [ -s "$2/$image" ] || { echo "the examples did not write $image"; exit 1; }
done
