#pragma once
// The ZFP library (Debian's libzfp.so.1), loaded into a link namespace of its own.
//
// Why: libzfp exports its bit-stream functions under plain names (stream_open, stream_close,
// stream_flush, stream_size, ...), and so does CFITSIO, which ParaView's readers pull into every
// ParaView process. The dynamic linker binds each name to the first library of the process that
// defines it, so in such a process ZFP's own calls, and ours, reach CFITSIO's functions of the
// same names: wrong results or a crash. Loaded with dlmopen(LM_ID_NEWLM), libzfp and its
// dependencies see only each other, whatever else the process has loaded, in every host (the
// command, Python, VTK programs, ParaView's GUI, pvbatch, pvserver) and under the sanitizers
// (which refuse RTLD_DEEPBIND, the other way to bind a library to itself).
//
// The library is loaded once, on first use, and checked by a round trip through compression
// before any caller sees it: a ZFP that cannot be loaded or does not round-trip is an
// mfadvr::Error with the reason, every time it is asked for, never a crash.
#include <zfp.h>

#include <string>

namespace mfadvr {

// ZFP's C functions that mfadvr calls, resolved in ZFP's own namespace.
struct ZfpLibrary {
  decltype(&::zfp_field_3d) field_3d;
  decltype(&::zfp_field_4d) field_4d;
  decltype(&::zfp_field_free) field_free;
  decltype(&::zfp_stream_open) stream_open;
  decltype(&::zfp_stream_close) stream_close;
  decltype(&::zfp_stream_set_rate) set_rate;
  decltype(&::zfp_stream_set_accuracy) set_accuracy;
  decltype(&::zfp_stream_maximum_size) maximum_size;
  decltype(&::zfp_stream_set_bit_stream) set_bit_stream;
  decltype(&::zfp_stream_rewind) rewind;
  decltype(&::zfp_compress) compress;
  decltype(&::zfp_decompress) decompress;
  decltype(&::stream_open) bitstream_open;
  decltype(&::stream_close) bitstream_close;
  std::string path;  // the file that was loaded
};

// The loaded and checked library; throws mfadvr::Error saying why ZFP is not usable.
const ZfpLibrary& zfpLibrary();

}  // namespace mfadvr
