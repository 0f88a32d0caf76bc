#pragma once
// NRRD volumes (.nrrd, or a .nhdr header and its data file), read by mfadvr itself: the header
// is parsed in full (DeclaredSizeCheck.h), raw and gzip samples stream through a
// RawVolumeSource (StreamedVolumeReader.h), ascii values are parsed here. No NRRD reaches VTK's
// reader, which trusts its header (it crashed, looped or corrupted memory on damaged ones) and
// guessed that a first axis of 9 samples or fewer holds vector components.
//
// What is read: three spatial axes (any axis of one sample and a kind of values, such as
// 'vector', is dropped), every scalar type but the 64-bit integers, raw, gzip and ascii
// encodings, either endianness, byte skip (-1: the data at the end of the file), one data
// file. Placement: spacings, or the lengths of the space directions, and the space origin (or
// axis mins); directions that rotate or flip the axes are not applied (a note says so).
// Refused with the reason: components along an axis, data over several files, line skip. A time
// axis (kind 'time', the last axis) makes the file a time series: describeNrrdVolume(path, true)
// gives its first step and the time axis (io/FileTimeSteps.h reads the steps), every other read
// refuses it with advice.
#include <cstdint>
#include <string>

#include "core/grid/StructuredGrid.h"
#include "io/DeclaredSizeCheck.h"
#include "io/FieldSelection.h"

namespace mfadvr {

struct NrrdVolume {
  StructuredGrid layout;    // dims, placement, field name, notes, sample type; no values
  DeclaredPayload payload;  // raw and gzip encodings: where the samples are (file set)
  std::string asciiFile;    // ascii encoding: the file of the values, and their first byte
  std::int64_t asciiOffset = 0;
  std::int64_t timeSteps = 1;  // > 1: a time series, `layout` and `payload` its first step
  double timeStart = 0.0, timeStep = 1.0;
};

// The header of `path`, checked against its data; throws mfadvr::Error naming the file (also for
// a time series, unless `timeSeries`).
NrrdVolume describeNrrdVolume(const std::string& path, bool timeSeries = false);

// The whole volume in memory (`field` may name its one field, as the header labels it).
StructuredGrid readNrrdVolume(const std::string& path, const FieldSelection& field = {});

}  // namespace mfadvr
