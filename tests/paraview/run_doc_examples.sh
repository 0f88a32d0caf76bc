#!/usr/bin/env bash
# run_doc_examples.sh DOC.md WORK_DIR BUILD_ROOT HEAD_MODEL: runs the shell and Python examples
# of DOC.md as written (tests/docs/run_doc_examples.py) in WORK_DIR, where `build` is BUILD_ROOT
# (the folder of the presets' build trees) and head.mfa the model the examples open, under
# one Xvfb. Exit 77 (skipped) when pvbatch, mpiexec or xvfb-run is missing.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
PV_TOOLS="pvbatch mpiexec xvfb-run python3"
source "$here/pv_test_env.sh"
rm -rf "$2" "$2-bin"
# One Xvfb for all the examples: the examples' own `xvfb-run` (first on their PATH) runs its
# command under this display instead of starting a second server inside the first, which now
# and then refused pvpython's first window ("bad X server connection").
mkdir -p "$2-bin"
cat >"$2-bin/xvfb-run" <<'SHIM'
#!/usr/bin/env bash
while [ $# -gt 0 ]; do
  case "$1" in
    -a | --auto-servernum) shift ;;
    -s | --server-args | -n | --server-num | -e | --error-file | -f | --auth-file | -p | --xauth-protocol) shift 2 ;;
    --*=*) shift ;;
    --) shift; break ;;
    *) break ;;
  esac
done
exec "$@"
SHIM
chmod +x "$2-bin/xvfb-run"
xvfb=$(command -v xvfb-run)
PATH="$2-bin:$PATH" timeout 900 "$xvfb" -a "${screen[@]}" python3 "$here/../docs/run_doc_examples.py" \
  "$1" "$2" --link "build=$3" --link "head.mfa=$4"
for image in head.png; do
  [ -s "$2/$image" ] || { echo "the examples did not write $image"; exit 1; }
done
