#pragma once
// Image-data formats read through VTK's own readers (NRRD is read by mfadvr itself:
// NrrdVolumeReader.h). The header stays free of VTK types so
// that code using mfadvr_io does not need VTK's include paths.
#include <string>

#include "core/grid/StructuredGrid.h"
#include "io/FieldSelection.h"

namespace mfadvr {

enum class VtkVolumeFormat {
  kXmlImageData,            // .vti (vtkXMLImageDataReader)
  kLegacyStructuredPoints,  // .vtk with DATASET STRUCTURED_POINTS (vtkStructuredPointsReader)
  kMetaImage,               // .mha / .mhd (vtkMetaImageReader)
  kNifti,                   // .nii / .nii.gz / .hdr+.img (vtkNIFTIImageReader)
  kDicomSeries,             // a directory of DICOM slices (vtkDICOMImageReader)
};

// Reads the array `field` selects (selectVtkField: by default the active scalars, else the first
// one-component point-data array, else the same from the cell data) of an image volume,
// converted to double (a chosen component, or the magnitude), with the file's origin, spacing
// and dims. Cell data gives one sample at each cell centre: a grid of one sample fewer per
// axis, half a cell in from the image's bounds. Throws mfadvr::Error with the reader's own
// messages when VTK fails, when the field is missing (listing the arrays there are) or has
// more than one component and none was chosen, when the samples span fewer than 2 along an
// axis (2-D data), and when a legacy file holds another dataset type. The grid is not validated
// (the caller overrides and validates).
//
// NIfTI: the scl_slope / scl_inter calibration is applied; the sform (else the qform) matrix
// places the grid in world (RAS) coordinates when its axes are parallel to the world axes
// (samples reordered, GridOrientation.h), else the grid keeps its voxel axes and grid.notes
// says so. DICOM: `path` is the series' directory; VTK's reader sorts the slices along their
// normal (largest position first), applies the rescale slope and intercept and puts the
// image's last row first (VTK's lower-left convention); the grid keeps those voxel axes with
// the first voxel at the origin, x spacing from Pixel Spacing's column spacing, and
// grid.notes says so.
StructuredGrid readVtkVolume(const std::string& path, VtkVolumeFormat format,
                             const FieldSelection& field);

}  // namespace mfadvr
