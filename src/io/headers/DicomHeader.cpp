// DICOM: the declared-size check (io/DeclaredSizeCheck.h).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <vector>

#include "core/util/Error.h"
#include "io/DeclaredSizeCheck.h"
#include "io/headers/HeaderText.h"

namespace mfadvr {

namespace fs = std::filesystem;
using namespace headers;

namespace {

// The elements of one DICOM Part-10 file, walked without reading the pixel data.
struct DicomWalk {
  std::int64_t rows = -1, columns = -1, bitsAllocated = -1, samplesPerPixel = 1;
  std::int64_t pixelBytes = -1;  // length of (7FE0,0010); -1: not reached
  std::string photometric;       // (0028,0004) up to its first NUL, as VTK's reader keeps it
  std::int64_t frames = 1;       // Number of Frames (0028,0008)
  std::string problem;           // why the walk stopped early ("" when it did not)
};

// Type-1 attributes (never empty in a valid file) that VTK 9.1's DICOM reader takes the value of
// without looking at its length: an empty one makes it dereference a null pointer (found by
// fuzzing: an empty Photometric Interpretation ended the program).
bool needsValue(std::uint32_t group, std::uint32_t element) {
  static constexpr std::uint32_t kTags[][2] = {
      {0x0002, 0x0010},  // transfer syntax
      {0x0020, 0x0032},  // image position (patient)
      {0x0020, 0x0037},  // image orientation (patient)
      {0x0028, 0x0004},  // photometric interpretation
      {0x0028, 0x0010},  // rows
      {0x0028, 0x0011},  // columns
      {0x0028, 0x0030},  // pixel spacing
      {0x0028, 0x0100},  // bits allocated
      {0x0028, 0x0103},  // pixel representation
      {0x0028, 0x1052},  // rescale intercept
      {0x0028, 0x1053},  // rescale slope
  };
  return std::any_of(std::begin(kTags), std::end(kTags),
                     [&](const auto& t) { return t[0] == group && t[1] == element; });
}

DicomWalk walkDicom(std::istream& in, std::int64_t size) {
  DicomWalk w;
  std::int64_t pos = 132;
  bool explicitVr = true, littleEndian = true, inMeta = true;
  auto readBytes = [&](std::int64_t at, size_t n, unsigned char* out) {
    in.clear();
    in.seekg(at);
    in.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n));
    return static_cast<size_t>(in.gcount()) == n;
  };
  bool le = true;  // of the element being read: the meta group is always little endian
  auto u16 = [&](const unsigned char* b) {
    return le ? std::uint32_t(b[0] | b[1] << 8) : std::uint32_t(b[1] | b[0] << 8);
  };
  auto u32 = [&](const unsigned char* b) {
    return le ? std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
                    std::uint32_t(b[3]) << 24
              : std::uint32_t(b[3]) | std::uint32_t(b[2]) << 8 | std::uint32_t(b[1]) << 16 |
                    std::uint32_t(b[0]) << 24;
  };
  for (int guard = 0; pos < size && guard < 100000; ++guard) {
    unsigned char tag[12];
    if (pos + 8 > size || !readBytes(pos, 8, tag)) {
      w.problem = "an element header is cut off at byte " + grouped(pos);
      return w;
    }
    le = inMeta || littleEndian;
    const std::uint32_t group = u16(tag);
    if (inMeta && group != 0x0002) {
      inMeta = false;
      continue;  // read this element again, with the data set's encoding
    }
    const std::uint32_t element = u16(tag + 2);
    std::int64_t length = 0, header = 8;
    const bool explicitHere = inMeta || explicitVr;
    if (explicitHere && std::isupper(tag[4]) && std::isupper(tag[5])) {
      const std::string vr(reinterpret_cast<char*>(tag + 4), 2);
      static const char* kLong[] = {"OB", "OW", "OF", "SQ", "UT", "UN", "OD",
                                    "OL", "UC", "UR", "OV", "SV", "UV"};
      if (std::any_of(std::begin(kLong), std::end(kLong), [&](const char* v) { return vr == v; })) {
        if (!readBytes(pos, 12, tag)) {
          w.problem = "an element header is cut off at byte " + grouped(pos);
          return w;
        }
        length = u32(tag + 8);
        header = 12;
      } else {
        length = u16(tag + 6);
      }
    } else {
      length = u32(tag + 4);
    }
    if (length == 0xFFFFFFFFll) return w;  // undefined length (sequences, encapsulated data)
    const std::int64_t valueAt = pos + header;
    if (group == 0x7FE0 && element == 0x0010) {
      w.pixelBytes = length;
      if (valueAt + length > size)
        w.problem = "its pixel data declares " + grouped(length) + " bytes, but " +
                    grouped(std::max<std::int64_t>(0, size - valueAt)) + " follow";
      return w;
    }
    char name[16];
    std::snprintf(name, sizeof name, "(%04X,%04X)", group, element);
    if (valueAt + length > size) {
      w.problem = std::string("element ") + name + " declares " + grouped(length) +
                  " bytes, past the end of the file";
      return w;
    }
    if (length == 0 && needsValue(group, element)) {
      w.problem = std::string("element ") + name +
                  " is empty, but the image cannot be read without its value";
      return w;
    }
    unsigned char value[64] = {};
    const size_t small = static_cast<size_t>(std::min<std::int64_t>(length, 64));
    if (small > 0 && !readBytes(valueAt, small, value)) return w;
    if (group == 0x0002 && element == 0x0010) {
      std::string ts(reinterpret_cast<char*>(value), small);
      ts = ts.substr(0, ts.find_first_of(std::string("\0 ", 2)));
      explicitVr = ts != "1.2.840.10008.1.2";
      littleEndian = ts != "1.2.840.10008.1.2.2";
    } else if (group == 0x0028 && element == 0x0004) {
      w.photometric.assign(reinterpret_cast<char*>(value), small);
      w.photometric = w.photometric.substr(0, w.photometric.find('\0'));
    } else if (group == 0x0028 && element == 0x0008) {
      // An integer string, padded with spaces; a value that is not one is left to VTK.
      std::string text(reinterpret_cast<char*>(value), small);
      const auto first = text.find_first_not_of(' ');
      if (first != std::string::npos) {
        std::int64_t n = 0;
        const auto [end, ec] = std::from_chars(text.data() + first, text.data() + text.size(), n);
        if (ec == std::errc()) w.frames = n;
      }
    } else if (group == 0x0028 && length == 2) {
      if (element == 0x0010) w.rows = u16(value);
      if (element == 0x0011) w.columns = u16(value);
      if (element == 0x0100) w.bitsAllocated = u16(value);
      if (element == 0x0002) w.samplesPerPixel = u16(value);
    }
    pos = valueAt + length;
  }
  return w;
}

}  // namespace

void checkDicomFile(std::istream& in, std::int64_t size, const std::string& path) {
  const DicomWalk w = walkDicom(in, size);
  if (!w.problem.empty())
    throw Error("cannot read " + path + " as DICOM: " + w.problem +
                "; the file is truncated or corrupt");
  if (w.pixelBytes < 0) {
    throw Error("cannot read " + path +
                " as DICOM: no pixel data (7FE0,0010) before the end of "
                "the file; it is truncated or holds no image");
  }
  // Without these VTK 9.1's reader assumes sizes of its own and copies that many bytes out of
  // the pixel data, past its end (found by fuzzing: a file without Bits Allocated). They are
  // type-1 attributes of every image, so a file that lacks one is refused.
  const struct {
    std::int64_t value;
    const char* name;
  } required[] = {{w.rows, "Rows (0028,0010)"},
                  {w.columns, "Columns (0028,0011)"},
                  {w.bitsAllocated, "Bits Allocated (0028,0100)"},
                  {w.samplesPerPixel, "Samples per Pixel (0028,0002)"}};
  for (const auto& r : required)
    if (r.value <= 0)
      throw Error("cannot read " + path + " as DICOM: " +
                  (r.value < 0 ? std::string("its image has no ") + r.name +
                                     " of two bytes before its pixel data"
                               : std::string("its ") + r.name + " is 0") +
                  "; the file is corrupt or holds no image");
  // VTK 9.1's reader takes its samples per pixel from the photometric interpretation, not from
  // Samples per Pixel: 3 where it reads exactly "RGB " (the padded value), else 1. Where the two
  // differ it reads past the pixel data (RGB of one sample) or mixes a pixel's samples.
  const int vtkSamples = w.photometric == "RGB " ? 3 : 1;
  if (w.samplesPerPixel != vtkSamples) {
    std::string shown = w.photometric;
    shown.erase(shown.find_last_not_of(' ') + 1);
    throw Error("cannot read " + path + " as DICOM: its Samples per Pixel (0028,0002) is " +
                std::to_string(w.samplesPerPixel) + ", but with its Photometric Interpretation '" +
                shown + "' VTK's reader takes " + std::to_string(vtkSamples) +
                (vtkSamples == 1 ? " sample" : " samples") +
                " a pixel (3 only for RGB); the file is corrupt or an image VTK cannot read");
  }
  // VTK 9.1's reader reads samples of 8 and 16 bits; it refuses most other sizes, but takes 9 to
  // 15 bits as one byte when it copies the pixel data and as two when it copies them out (an
  // overflow, found with a slice of 12).
  if (w.bitsAllocated != 8 && w.bitsAllocated != 16)
    throw Error("cannot read " + path + " as DICOM: its Bits Allocated (0028,0100) is " +
                std::to_string(w.bitsAllocated) +
                ", and VTK's reader reads samples of 8 or 16 bits only");
  // VTK's reader reads the first frame of a file and nothing else.
  if (w.frames > 1)
    throw Error("cannot read " + path + " as DICOM: it holds " + std::to_string(w.frames) +
                " frames (Number of Frames, 0028,0008), and VTK's reader reads one frame per "
                "file; split the image into single-frame files, one slice each");
  const std::int64_t need =
      times(times(w.rows, w.columns), times(w.samplesPerPixel, (w.bitsAllocated + 7) / 8));
  if (w.pixelBytes < need) {
    throw Error("cannot read " + path + " as DICOM: " + std::to_string(w.rows) + " x " +
                std::to_string(w.columns) + " pixels of " + std::to_string(w.bitsAllocated) +
                " bits need " + grouped(need) + " bytes, but its pixel data has " +
                grouped(w.pixelBytes));
  }
}

int checkDicomSeries(const std::string& directory) {
  int files = 0;
  std::error_code ec;
  std::vector<fs::path> paths;
  for (const auto& entry : fs::directory_iterator(directory, ec))
    if (entry.is_regular_file(ec)) paths.push_back(entry.path());
  if (ec) throw Error("cannot read " + directory + " as a DICOM series: " + ec.message());
  std::sort(paths.begin(), paths.end());
  for (const fs::path& p : paths) {
    std::ifstream in(p, std::ios::binary);
    char magic[132] = {};
    if (!in.read(magic, sizeof magic) || std::string(magic + 128, 4) != "DICM") continue;
    ++files;
    checkDicomFile(in, fileSize(p.string()), p.string());
  }
  // VTK's reader says little (and twice) about a folder without DICOM files.
  if (files == 0) {
    throw Error("cannot read " + directory + " as a DICOM series: none of its " +
                std::to_string(paths.size()) +
                " files is a DICOM file ('DICM' after a 128-byte preamble); a volume input "
                "that is a directory must hold the slices of one DICOM series");
  }
  return files;
}

}  // namespace mfadvr
