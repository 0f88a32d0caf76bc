#pragma once
// Checks that a file holds the data its header declares, before any reader allocates for it.
//
// VTK's readers trust headers: a truncated file is read with zeros where the data is missing,
// and a header that declares 100000^3 samples makes them try to allocate it. Each check here
// reads only the header (a few KB; for gzip files, the start of the stream), computes how many
// bytes the declared samples need in the declared encoding, and compares that with what the
// file (or its detached data file) holds after the header:
//   - uncompressed binary data: exactly enough bytes (more is allowed: trailing data);
//   - ASCII data: at least 2 bytes per value (a digit and a separator);
//   - compressed data: at most 1032 bytes per compressed byte (the deflate limit).
// A mismatch throws mfadvr::Error naming the file, what the header declares and what the file
// holds. Headers the check cannot interpret (exotic encodings) are left to the reader, which
// reports its own errors.
#include <cstdint>
#include <functional>
#include <istream>
#include <string>
#include <vector>

namespace mfadvr {

// Samples that a header declares stored in one file from a known byte on, uncompressed or as
// one gzip stream: what a RawVolumeSource needs to read them a box at a time instead of through
// VTK's reader (gzip data once inflated to a temporary file). `file` is empty when they are
// stored otherwise (text data, skips that leave the start open, lists of files, a sample type
// RawVolumeSource does not read).
struct DeclaredPayload {
  std::string file;          // from the file-level checks: a path usable as is
  std::int64_t gzipAt = -1;  // >= 0: `file` holds a gzip stream from this byte on
  std::int64_t offset = 0;   // of the first sample in `file` (gzip: in the inflated stream)
  std::string dtype;         // uint8, int8, uint16, int16, uint32, int32, float32, float64
  bool bigEndian = false;
  std::vector<std::int64_t> sizes;  // the declared axis sizes, fastest first
  int components = 1;               // interleaved values per sample
  std::string arrayName;            // where the header names the samples (legacy SCALARS)
};

// NRRD, attached (.nrrd) or detached (.nhdr + data file), as mfadvr reads it (NrrdVolumeReader.h):
// the header in full (type, sizes, encoding, endianness, skips, data file, kinds, spacings,
// space directions and origin, axis mins, labels), checked against what the file holds.
// The grid such a header describes: three spatial axes (size-1 axes of other kinds dropped),
// placed by its spacings or the lengths of its space directions and by its space origin or
// axis mins.
struct NrrdGrid {
  std::int64_t dims[3] = {0, 0, 0};
  double spacing[3] = {1, 1, 1};
  double origin[3] = {0, 0, 0};
  std::string sampleType;  // uint8, int8, uint16, int16, uint32, int32, float32, float64
  bool bigEndian = false;
  std::string label;  // the first of "labels", or empty
  std::vector<std::string> notes;
  // A time axis ('kinds: ... time') of more than one sample, stored as the last axis: the steps
  // follow one another, each a whole volume. Its times: axis min (else 0) + step x spacing (else
  // the length of its space direction, else 1).
  std::int64_t timeSteps = 1;
  int timeAxis = -1;
  double timeStart = 0.0, timeStep = 1.0;
};
struct NrrdFile {
  NrrdGrid grid;
  DeclaredPayload payload;  // raw and gzip encodings: where the samples are (file set)
  std::string asciiFile;    // ascii encoding: the file that holds the values, and where they start
  std::int64_t asciiOffset = 0;
};
NrrdFile checkNrrdDeclaredSize(const std::string& path);

// The first `count` numbers of the whitespace- or comma-separated ASCII text at byte `offset` of
// `path`; an Error (naming `path`) when one is not a number or fewer are there.
std::vector<double> readAsciiValues(const std::string& path, std::int64_t offset,
                                    std::int64_t count);

// MetaImage (.mha, or .mhd + data file): DimSize, ElementType, channels, compression; also
// that a detached data file exists, and every file of a file series (LIST, or a slice-number
// pattern) with its slice.
DeclaredPayload checkMetaImageDeclaredSize(const std::string& path);

// Legacy VTK: DIMENSIONS / POINT_DATA and the first SCALARS block of structured points, or the
// POINTS block of other datasets.
// The payload is that SCALARS block's, for binary structured points.
DeclaredPayload checkLegacyVtkDeclaredSize(const std::string& path);

// VTK XML (.vti, .vtu, .vts, .vtp, .vtr): that the file ends with </VTKFile> (a cut file does
// not), and that WholeExtent / NumberOfPoints / NumberOfCells are possible for its size.
void checkXmlVtkDeclaredSize(const std::string& path);

// NIfTI-1 / NIfTI-2 (.nii, .nii.gz, .hdr + .img): dim, bitpix, vox_offset.
DeclaredPayload checkNiftiDeclaredSize(const std::string& path);

// DICOM Part-10 files ('DICM' after the 128-byte preamble): walks the elements up to the pixel
// data and checks that every element fits in the file and that the pixel data holds rows x
// columns x samples x bytes. checkDicomSeries checks every such file of a directory (in name
// order) and returns how many there are; a folder without any is an error.
void checkDicomFile(std::istream& in, std::int64_t size, const std::string& path);
int checkDicomSeries(const std::string& directory);

// The same checks on a header already in memory (the fuzzers' entry points): `fileBytes` is
// the size of the whole file; `dataFileBytes` gives the size of a detached data file named in
// the header (relative names are relative to the header's folder), or -1 when it is missing.
using DataFileSize = std::function<std::int64_t(const std::string& name)>;
// Where NRRD data lies that needs a look beyond its size (ASCII values are counted, gzip data
// checked for a complete stream).
struct NrrdDataLocation {
  std::string dataFile;     // empty: the header's own file
  std::int64_t offset = 0;  // of the data in that file
  std::int64_t values = 0;  // declared; 0: nothing more to check
  std::int64_t bytes = 0;   // of the values in binary
  bool gzip = false;        // else ASCII
  std::string declared;     // "40 x 40 x 40 uint8 samples"
  DeclaredPayload raw;      // raw encoding: file as the header names it (the header's own: path)
  NrrdGrid grid;
};
NrrdDataLocation checkNrrdHeaderText(const std::string& header, const std::string& path,
                                     std::int64_t fileBytes, const DataFileSize& dataFileBytes);
DeclaredPayload checkMetaImageHeaderText(const std::string& header, const std::string& path,
                                         std::int64_t fileBytes, const DataFileSize& dataFileBytes);
DeclaredPayload checkLegacyVtkHeaderText(const std::string& header, const std::string& path,
                                         std::int64_t fileBytes);
void checkXmlVtkText(const std::string& head, const std::string& tail, const std::string& path,
                     std::int64_t fileBytes);
// Returns the bytes the declared image needs from the start of the file (-1: not a header it
// understands).
std::int64_t checkNiftiHeaderBytes(const std::string& header, const std::string& path,
                                   std::int64_t fileBytes, bool compressed,
                                   DeclaredPayload* payload = nullptr);

}  // namespace mfadvr
