// VTK XML: the declared-size check (io/DeclaredSizeCheck.h).
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

// The integers of attribute `name` in the first element that has it at or after `from`, or
// empty; `next` (optional) receives where to look for the next one (npos: none).
std::vector<std::int64_t> attributeCounts(const std::string& text, const std::string& name,
                                          size_t from = 0, size_t* next = nullptr) {
  const std::string key = " " + name + "=\"";
  const auto at = text.find(key, from);
  if (next) *next = at == std::string::npos ? std::string::npos : at + key.size();
  if (at == std::string::npos) return {};
  const auto end = text.find('"', at + key.size());
  if (end == std::string::npos) return {};
  std::vector<std::int64_t> out;
  for (const auto& w : words(text.substr(at + key.size(), end - at - key.size()))) {
    std::int64_t v = 0;
    const auto r = std::from_chars(w.data(), w.data() + w.size(), v);
    if (r.ec != std::errc() || r.ptr != w.data() + w.size()) return {};
    out.push_back(v);
  }
  return out;
}

}  // namespace

void checkXmlVtkText(const std::string& head, const std::string& tail, const std::string& path,
                     std::int64_t fileBytes) {
  if (head.find("<VTKFile") == std::string::npos) return;
  // Composite data (a list of data sets in other files, or AMR levels): VTK's single-data-set
  // readers only say they cannot find their element.
  for (const char* composite : {"vtkMultiBlockDataSet", "vtkOverlappingAMR", "vtkNonOverlappingAMR",
                                "vtkHierarchicalBoxDataSet", "vtkPartitionedDataSet",
                                "vtkPartitionedDataSetCollection", "vtkMultiPieceDataSet"}) {
    if (head.find("type=\"" + std::string(composite) + "\"") != std::string::npos) {
      throw Error("cannot read " + path + ": the file holds a " + composite +
                  ", a composite of several data sets (multi-block), not a data set; mfadvr "
                  "reads one data set per file: encode the block files it lists, or extract a "
                  "block in ParaView (Extract Block) and save it");
    }
  }
  if (trim(tail).size() < 10 || trim(tail).substr(trim(tail).size() - 10) != "</VTKFile>") {
    throw Error("cannot read " + path + " as VTK XML: the file (" + grouped(fileBytes) +
                " bytes) does not end with </VTKFile>, so it is cut off or not well-formed");
  }
  // Compressed and base64 data can be smaller than the raw samples, but not by more than the
  // deflate limit.
  const Encoding enc =
      head.find("compressor=") != std::string::npos ? Encoding::Deflate : Encoding::Binary;
  std::int64_t points = -1;
  std::string declared;
  const auto extent = attributeCounts(head, "WholeExtent");
  if (extent.size() == 6) {
    std::vector<std::int64_t> dims;
    for (int a = 0; a < 3; ++a) {
      const std::int64_t lo = extent[2 * a], hi = extent[2 * a + 1];
      if (hi < lo)
        throw Error("cannot read " + path +
                    " as VTK XML: its WholeExtent has a maximum below its "
                    "minimum along " +
                    "xyz"[a]);
      if (hi - lo >= std::numeric_limits<std::int64_t>::max() / 2) return;
      dims.push_back(hi - lo + 1);
    }
    // VTK's structured readers copy each piece's extent into the whole one without checking
    // that it lies inside (found by fuzzing: a piece past the whole extent made them copy
    // memory from address 0).
    size_t from = 0;
    for (;;) {
      const auto piece = attributeCounts(head, "Extent", from, &from);
      if (from == std::string::npos) break;
      bool inside = piece.size() == 6;
      for (int a = 0; inside && a < 3; ++a)
        inside = extent[2 * a] <= piece[2 * a] && piece[2 * a] <= piece[2 * a + 1] &&
                 piece[2 * a + 1] <= extent[2 * a + 1];
      if (!inside)
        throw Error("cannot read " + path +
                    " as VTK XML: a piece's Extent is not six integers "
                    "inside the WholeExtent");
    }
    // A field of the image has a value per point or per cell: at least one byte per cell.
    std::vector<std::int64_t> cells;
    for (std::int64_t d : dims) cells.push_back(std::max<std::int64_t>(d - 1, 1));
    points = product(cells);
    declared = "an extent of " + dimsText(dims) + " points (" + grouped(points) + " cells)";
  } else {
    const auto n = attributeCounts(head, "NumberOfPoints");
    if (n.size() != 1 || n[0] < 0) return;
    points = n[0];
    declared = grouped(points) + " points";
  }
  // At least one byte per cell of an image, per point (a coordinate) of other data sets,
  // whatever the array types.
  requireData(path, "VTK XML", declared, points, 1, enc, fileBytes, "the file");
}

void checkXmlVtkDeclaredSize(const std::string& path) {
  const std::int64_t size = fileSize(path);
  if (size < 0) return;
  checkXmlVtkText(readHead(path, 8192), readTail(path, size, 256), path, size);
}

}  // namespace mfadvr
