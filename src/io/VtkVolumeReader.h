#pragma once
// Image-data formats read through VTK's own readers. The header stays free of VTK types so
// that code using mfadvr_io does not need VTK's include paths.
#include <string>

#include "core/grid/StructuredGrid.h"

namespace mfadvr {

enum class VtkVolumeFormat {
  kNrrd,                    // .nrrd / .nhdr (vtkNrrdReader: raw, ascii and gzip encodings)
  kXmlImageData,            // .vti (vtkXMLImageDataReader)
  kLegacyStructuredPoints,  // .vtk with DATASET STRUCTURED_POINTS (vtkStructuredPointsReader)
  kMetaImage,               // .mha / .mhd (vtkMetaImageReader)
};

// Reads the point-data array named `field` (empty: the active scalars, else the first
// point-data array) of an image volume, converted to double, with the file's origin, spacing
// and dims. Throws mfadvr::Error with the reader's own messages when VTK fails, when the field
// is missing (listing the arrays there are) or has more than one component, and when a legacy
// file holds another dataset type. The grid is not validated (the caller overrides and
// validates).
StructuredGrid readVtkVolume(const std::string& path, VtkVolumeFormat format,
                             const std::string& field);

}  // namespace mfadvr
