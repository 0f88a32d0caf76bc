#!/usr/bin/env bash
# Packs the GPU test program and the GPU benchmark, with the shared libraries they load, into one
# folder that runs on a machine with an NVIDIA GPU and driver but no other packages:
#
#   scripts/pack-gpu-check.sh [OUT]          # default OUT: build/gpu-check
#   OUT/run-tests.sh [gtest options]         # GPU images against the CPU's (docs/gpu.md)
#   OUT/run-bench.sh [bench options]         # frame times, GPU and CPU in the same run
#
# The CUDA runtime is linked statically; the driver's libcuda.so comes from the target machine.
# Everything else the programs load, except the C library itself, is copied into OUT/lib, and
# libzfp (opened at run time for zfp-coded models) with what it loads.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-build/gpu-check}"

cmake --preset release >/dev/null
cmake --build --preset release -j2 --target mfadvr_gpu_tests mfadvr_gpu_bench
tests=build/release/tests/mfadvr_gpu_tests
bench=build/release/bench/mfadvr_gpu_bench
for f in "$tests" "$bench"; do
  [[ -x "$f" ]] || { echo "pack-gpu-check: $f was not built (is nvcc installed?)" >&2; exit 1; }
done

rm -rf "$out"
mkdir -p "$out/lib"
cp "$tests" "$bench" "$out/"
# The C library and the dynamic loader stay the target's; libcuda is the target's driver.
keep='^(linux-vdso|ld-linux|libc\.so|libm\.so|libpthread\.so|libdl\.so|librt\.so|libcuda\.so)'
# libzfp is opened at run time (zfp-coded models, e.g. integer scans encoded with the defaults):
# it travels too, when this machine has it.
zfp=$(ldconfig -p | awk '/libzfp\.so\.1 / {p = $NF} END {print p}')
for f in "$tests" "$bench" $zfp; do
  ldd "$f" | awk '/=> \// {print $1, $3}' | while read -r name path; do
    if ! [[ "$name" =~ $keep ]]; then cp -L -n "$path" "$out/lib/"; fi
  done
done
if [[ -n "$zfp" ]]; then cp -L -n "$zfp" "$out/lib/libzfp.so.1"; fi
for tool in tests bench; do
  cat >"$out/run-$tool.sh" <<SCRIPT
#!/bin/sh
# Runs mfadvr_gpu_$tool with the libraries packed beside it.
here=\$(cd "\$(dirname "\$0")" && pwd)
LD_LIBRARY_PATH="\$here/lib\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}" exec "\$here/mfadvr_gpu_$tool" "\$@"
SCRIPT
  chmod +x "$out/run-$tool.sh"
done
echo "packed into $out ($(du -sh "$out" | cut -f1)):"
ls "$out" "$out/lib"
