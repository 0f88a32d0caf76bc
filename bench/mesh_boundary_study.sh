#!/usr/bin/env bash
# Exact mesh boundaries, measured: each mesh encoded with the defaults (voxel mask and exact
# boundary) and with --no-boundary (mask only), both rendered unshaded with a ramp next to VTK's
# Bunyk ray caster on the mesh itself (same camera, TF and size), whole and zoomed on a part of
# the boundary; image PSNR / SSIM of each model against Bunyk, boundary size, and the frame
# times (median of the frames after the first) of the exact model, the mask-only model and
# Bunyk, with Bunyk's over the exact model's.
#
#   bench/mesh_boundary_study.sh [MFADVR] [OUT_DIR] [MESH|FIELD|ZOOM|FOCAL_X,Y,Z ...]
#
# MFADVR defaults to build/release/src/app/mfadvr, OUT_DIR to a temporary folder (the PNGs are
# kept when it is given). Without meshes: ../shared/data's spx.vtk and bluntfin_tets.vtu (when
# present). Needs a display for VTK (run it under xvfb-run -a).
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-build/release/src/app/mfadvr}
out=${2:-}
shift $(($# > 2 ? 2 : $#))
size=${SIZE:-512x512}
frames=${FRAMES:-5}
if [ -z "$out" ]; then
  out=$(mktemp -d)
  trap 'rm -rf "$out"' EXIT
fi
mkdir -p "$out"
meshes=("$@")
if [ ${#meshes[@]} -eq 0 ]; then
  data=../shared/data
  [ -f "$data/spx.vtk" ] && meshes+=("$data/spx.vtk||4|0.4,0.4,0.9")
  [ -f "$data/bluntfin_tets.vtu" ] && meshes+=("$data/bluntfin_tets.vtu|Density|4|5.5,2,10")
fi

field() { python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print(j$1)" "$2"; }
psnr() { "$exe" compare "$1" "$2" --json | python3 -c \
  "import json,sys; j=json.load(sys.stdin); print('%.2f %.4f' % (j['psnr'], j['ssim']))"; }
printf '%-22s %-6s %9s %8s %13s %13s %22s %7s\n' mesh view triangles "encode s" "mask dB/SSIM" \
  "exact dB/SSIM" "frame s exact/mask/Bunyk" "Bunyk/x"
for spec in "${meshes[@]}"; do
  IFS='|' read -r mesh fieldName zoom focal <<<"$spec"
  name=$(basename "${mesh%.*}")
  fopt=()
  [ -n "$fieldName" ] && fopt=(--field "$fieldName")
  "$exe" encode "$mesh" "${fopt[@]}" -o "$out/$name.mfa" --json >"$out/$name-encode.json"
  "$exe" encode "$mesh" "${fopt[@]}" -o "$out/$name-mask.mfa" --no-boundary -q >/dev/null
  for view in whole zoom; do
    cam=(--size "$size" --tf ramp --frames "$frames")
    [ "$view" = zoom ] && cam+=(--zoom "$zoom" --focal-point "$focal")
    "$exe" render "$mesh" "${fopt[@]}" --method vtk-bunyk "${cam[@]}" \
      -o "$out/$name-$view-bunyk.png" --json >"$out/$name-$view-bunyk.json"
    "$exe" render "$out/$name-mask.mfa" "${cam[@]}" -o "$out/$name-$view-mask.png" --json \
      >"$out/$name-$view-mask.json"
    "$exe" render "$out/$name.mfa" "${cam[@]}" -o "$out/$name-$view-exact.png" --json \
      >"$out/$name-$view-exact.json"
    exact=$(field "['seconds']['render']" "$out/$name-$view-exact.json")
    bunyk=$(field "['seconds']['render']" "$out/$name-$view-bunyk.json")
    printf '%-22s %-6s %9s %8.2f %13s %13s %8.3f/%6.3f/%6.3f %7.1f\n' "$name" "$view" \
      "$(field "['boundary']['triangles']" "$out/$name-encode.json")" \
      "$(field "['fit_seconds']" "$out/$name-encode.json")" \
      "$(psnr "$out/$name-$view-bunyk.png" "$out/$name-$view-mask.png" | tr ' ' /)" \
      "$(psnr "$out/$name-$view-bunyk.png" "$out/$name-$view-exact.png" | tr ' ' /)" \
      "$exact" "$(field "['seconds']['render']" "$out/$name-$view-mask.json")" "$bunyk" \
      "$(python3 -c "print($bunyk / $exact)")"
  done
done
