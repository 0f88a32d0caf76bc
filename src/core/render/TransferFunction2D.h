#pragma once
// A 2-D transfer function over (value, |grad f|), VTK's vtkVolumeProperty::SetTransferFunction2D
// and ParaView's 2-D transfer-function editor: a table of colours and opacities, read back with
// bilinear interpolation and clamped to its edges. It replaces the 1-D function's colour and
// opacity; boundaries between materials, where |grad f| is large, can then be shown apart from
// the materials' interiors (Kniss et al. 2002).
//
// Forms (docs/transfer-functions.md): an RGBA PNG (x: the value axis, left to right; y: the
// gradient axis, bottom row |grad f| = the low end), placed by explicit ranges; or a JSON file
// of boxes, in data units:
//   {"boxes": [{"value": [LO, HI], "gradient": [LO, HI], "color": [R, G, B], "opacity": A}, ...],
//    "size": [W, H]}
// with later boxes over earlier ones and nothing outside them.
#include <string>
#include <vector>

#include "core/image/Image.h"
#include "core/util/Vec.h"

namespace mfadvr {

struct TransferFunction2D {
  int width = 0, height = 0;  // >= 2 each
  // width * height * 4 floats: entry (i, j) at (j * width + i) * 4, i along the value axis,
  // j along the gradient axis; straight (not premultiplied) RGB in [0, 1] and opacity in [0, 1]
  // per opacity unit distance, as the 1-D function's.
  std::vector<float> rgba;
  // The axes' ends (data units; |grad f| in data units per world unit): entry i = 0 sits at
  // valueLo, i = width - 1 at valueHi; likewise for the gradient.
  double valueLo = 0.0, valueHi = 1.0, gradientLo = 0.0, gradientHi = 1.0;

  // Throws mfadvr::Error naming the first problem (sizes, entries outside [0, 1], ranges that
  // are not finite and increasing).
  void validate() const;
  const float* entry(int i, int j) const { return &rgba[(static_cast<size_t>(j) * width + i) * 4]; }
};

// The axes' ends for a 2-D transfer function read from an image.
struct TransferFunction2DRange {
  double valueLo, valueHi, gradientLo, gradientHi;
};

// An RGBA (or RGB: opaque) image as the table: column x at value valueLo + x/(W-1) of the range,
// the image's bottom row at gradientLo, its top row at gradientHi.
TransferFunction2D transferFunction2DFromImage(const Image8& image,
                                               const TransferFunction2DRange& range);

// The JSON box form; `where` names the source in errors.
TransferFunction2D parseTransferFunction2DJson(const std::string& text, const std::string& where);

// Reads `path`: .png (placed by `range`, which must then be given) or .json (boxes; `range` is
// not used). mfadvr::Error naming the file for anything else.
TransferFunction2D readTransferFunction2D(const std::string& path,
                                          const TransferFunction2DRange* range);

}  // namespace mfadvr
