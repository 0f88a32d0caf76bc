#pragma once
// MFA models carried by a vtkImageData: the form in which ParaView's pipeline moves models
// between processes and ranks (it knows nothing of vtkMFAModelData). A carrier holds one or
// more models, each with the region it renders (the blocks of a multi-block file that one rank
// reads, or one piece of a partitioned volume):
//   field data "MFAModel0", "MFAModel1", ...: each model as the bytes of a .mfa file (unsigned
//     char), and "MFARegions" (double, 6 components: xmin, xmax, ymin, ymax, zmin, zmax, one
//     tuple per model);
//   geometry: a grid over the union of the regions with the spacing of the data the models
//     stand for (Model::dataSpacing), so that a pipeline sees the carrier where its models
//     render, at the data's resolution (ParaView derives its default opacity unit distance from
//     the cell size, which must not depend on how many ranks share the volume);
//   point scalars: the models evaluated at those points (float, named after the model's field;
//     NaN outside every region and outside a domain mask): the model resampled on the data
//     grid, for colour maps, slices and contours of the model in the pipeline (or, from an
//     encoder with PassInputValues, its input's samples).
// Private to the module.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "vtkSmartPointer.h"

class vtkDataArray;
class vtkDataObject;
class vtkImageData;

#include "core/model/DomainBox.h"
#include "core/util/Vec.h"

namespace mfadvr {
class Model;
}  // namespace mfadvr

namespace mfadvr::vtkglue {

struct CarriedModel {
  std::shared_ptr<const Model> model;
  DomainBox region;
};

// Where a carrier lies in the image grid of the whole data set: the origin and spacing that every
// piece's carrier shares, and this carrier's extent in it. ParaView treats the pieces of one
// image as sub-extents of a whole extent (WHOLE_EXTENT, ORIGIN, SPACING): the representation
// takes the view's bounds and the ranks' compositing order from them.
struct CarrierGrid {
  Vec3d origin = Vec3d::Zero();
  Vec3d spacing = Vec3d::Ones();
  int extent[6] = {0, -1, 0, -1, 0, -1};
};

// The grid of the data that `box` holds, sampled `step` apart (Model::dataSpacing): at least 2
// points per axis, the spacing adjusted so that the points end on the box's faces; its extent
// is the whole grid (from 0).
CarrierGrid wholeCarrierGrid(const DomainBox& box, const Vec3d& step);

// The part of `whole` that covers `region` (its faces rounded to the nearest grid points; at
// least 2 points per axis).
CarrierGrid carrierSubGrid(const CarrierGrid& whole, const DomainBox& region);

// Point scalars for a carrier's grid in place of the models evaluated there (the encoder's input
// values, vtkMFAEncoder::PassInputValues): an array of one tuple per point of `grid` (x
// fastest), or null for the models' values.
using CarrierValues = std::function<vtkSmartPointer<vtkDataArray>(const CarrierGrid& grid)>;

// The carrier of `models` on `grid` (carrierSubGrid of the whole data's grid for a piece). Each
// model is written into its byte array and, from there on, used where it lies there (float32
// control points): a model that the caller moved in is freed before the carrier's values are
// computed, so that a large model is not held twice. `values` (optional) gives the point
// scalars instead.
vtkSmartPointer<vtkImageData> imageOfModels(std::vector<CarriedModel> models,
                                            const CarrierGrid& grid,
                                            const CarrierValues& values = {});

// The carrier on the data's grid over the union of the models' regions. firstIndex (optional):
// the index of the carrier's first point, for a carrier made from image data, so that its
// extent lies in the input's index space (a pipeline crops an image to the update extent it
// asked for, which is in that space); null: the extent starts at 0.
// reach (optional, with values): the carrier's extent in that index space when it reaches past
// the regions (a piece of a parallel pipeline with its ghost layers). Where `values` gives its
// array for that grid, the carrier takes it (the input's own array: no copy) and marks the
// cells outside the regions as ghost cells (vtkGhostType, duplicates that another piece owns);
// otherwise the carrier covers the regions only.
vtkSmartPointer<vtkImageData> imageOfModels(std::vector<CarriedModel> models,
                                            const int* firstIndex = nullptr,
                                            const CarrierValues& values = {},
                                            const int* reach = nullptr);

// The name of a carrier's point array for `model`: the model's field, "MFA value" when it has
// none.
std::string carrierArrayName(const Model& model);

// Whether `data` is an image carrying models (it has the regions array).
bool carriesModels(vtkDataObject* data);

// The models of a carrier, checked as a .mfa file is; throws mfadvr::Error for a damaged or
// inconsistent carrier.
std::vector<CarriedModel> modelsOfImage(vtkImageData* image);

}  // namespace mfadvr::vtkglue
