#include "core/encode/Encoder.h"

#include "core/mask/MaskVoxelizer.h"
#include "core/model/ModelFile.h"
#include "core/util/Error.h"

namespace mfadvr {

Model encodeStructured(const StructuredGrid& grid, const EncodeOptions& options,
                       FitReport* report) {
  StructuredFitOptions fit;
  fit.degree = options.degree;
  fit.controlCounts = options.controlCounts;
  fit.progress = options.progress;
  if (options.adaptive) return fitStructuredAdaptive(grid, fit, *options.adaptive, report);
  return fitStructured(grid, fit, report);
}

Index3 maskDimsFor(const ScatteredData& data, const MaskOptions& options) {
  if (options.dims[0] > 0) return options.dims;
  const DomainBox box{data.boxMin(), data.boxMax()};
  const int longest = options.longestAxisNodes > 0 ? options.longestAxisNodes
                      : data.hasCells()            ? kDefaultMeshMaskNodes
                                                   : defaultCoverageResolution(data.pointCount());
  return defaultMaskDims(box, longest);
}

Model encodeScattered(const ScatteredData& data, const EncodeOptions& options, FitReport* report) {
  ScatteredFitOptions fit;
  fit.degree = options.degree;
  fit.controlCounts = options.controlCounts;
  fit.smoothing = options.smoothing;
  fit.progress = options.progress;
  FitReport local;
  FitReport& r = report ? *report : local;
  Model model = options.adaptive ? fitScatteredAdaptive(data, fit, *options.adaptive, &r)
                                 : fitScattered(data, fit, &r);
  if (options.mask.enabled) {
    const Index3 dims = maskDimsFor(data, options.mask);
    DomainMask mask = data.hasCells()
                          ? meshOccupancyMask(data.points, data.tets, model.domain(), dims)
                          : pointCoverageMask(data.points, model.domain(), dims);
    if (mask.insideFraction() == 0.0)
      throw Error(data.source +
                  ": the domain mask is empty (no mask node lies inside the data); use a finer "
                  "--mask-res or --no-mask");
    model.setMask(std::move(mask));
    r.maskKind = maskKindName(model.mask().kind());
    r.maskDims = model.mask().dims();
    r.maskInsideFraction = model.mask().insideFraction();
    r.modelBytes = modelFileSize(model);
  }
  return model;
}

}  // namespace mfadvr
