#!/usr/bin/env bash
# check_exported_symbols.sh LIBRARY...: fails when a shared library of mfadvr exports a symbol
# of the code it links in (mfadvr's own namespace, ZFP's and CFITSIO's C names, zlib, libpng,
# zstd, Eigen, TBB, nlohmann-json): a host process that loads another library with such a name
# would bind one of the two to the other. What may leave: the VTK classes and the entry points
# that VTK, Python and ParaView look up (and the C++ runtime's template code, which libstdc++
# exports by design).
set -euo pipefail
status=0
for lib in "$@"; do
  if [ ! -f "$lib" ]; then
    echo "check_exported_symbols: $lib does not exist" >&2
    exit 1
  fi
  # Mangled names: after _Z and the prefixes of guard variables, vtables, type infos, local
  # statics and nested names, the first name says whose code it is.
  leaks=$(nm -D --defined-only --format=posix "$lib" | cut -d' ' -f1 |
          grep -E '^_Z(GV|TV|TI|TS|TT|TH|TW|Z|N|K|L)*(6mfadvr|5Eigen|3tbb|8nlohmann)|^(zfp_|stream_|png_|ZSTD_|ZDICT_|deflate|inflate|crc32|adler32)' |
          c++filt || true)
  count=$(nm -D --defined-only "$lib" | wc -l)
  if [ -n "$leaks" ]; then
    echo "$lib exports $(echo "$leaks" | wc -l) symbol(s) of the code it links in, e.g.:" >&2
    echo "$leaks" | head -20 >&2
    status=1
  else
    echo "$lib: $count exported symbols, none of the code it links in"
  fi
done
exit $status
