#pragma once
// How a ray's samples become a pixel (VTK's vtkVolumeMapper blend modes), host and device.
//
//   composite  front-to-back emission-absorption (paper section 3.1): the default.
//   max, min   the largest (smallest) value along the ray, then classified: colour c and opacity a
//              of that value from the transfer function (a not corrected for the step: one
//              sample stands for the ray), pixel = a c over the background (VTK's MIP / MinIP).
//   average    the mean, weighted by step length, of a(v) v' over the samples whose value v lies
//              in the average range (all values by default), v' = v normalized over the
//              transfer function's value range; a grey pixel of that level, clamped to [0, 1],
//              opacity 1 (VTK's GPU AVERAGE_INTENSITY_BLEND); background where no sample counts.
//   additive   the sum of a(v) v' dt / u over the samples (dt: the step, u: the opacity unit
//              distance), clamped to [0, 1], grey, opacity 1 (VTK's GPU ADDITIVE_BLEND, which sums
//              samples: the same when the step is the unit distance; here it does not depend on
//              the step).
//   iso        surfaces where the field crosses each isovalue (RenderSettings::isoSurfaces), in
//              depth order, each of its own colour and opacity (the transfer function's at the
//              value unless given), shaded with the field's gradient at the hit when shading is
//              on. MFA models: exact crossings of the spline, found cell by cell, whatever the
//              step (kernel/IsoSurfaceWalk.h); other methods: sign changes between samples,
//              then solved on the field.
// Shading applies to composite and iso renders only (VTK's mappers do not shade the others).
#include <optional>
#include <string>
#include <string_view>

namespace mfadvr {

enum class BlendMode : int { Composite = 0, Maximum, Minimum, Average, Additive, Iso };

// "composite", "max", "min", "average", "additive", "iso" (also VTK's long names: "mip",
// "maximum", "minimum", "minip", "average-intensity", "isosurface"); none for anything else.
std::optional<BlendMode> parseBlendMode(std::string_view name);
// The short name parseBlendMode takes.
const char* blendModeName(BlendMode mode);
// "composite|max|min|average|additive|iso", for help texts and errors.
std::string blendModeChoices();
// What a depth image (RenderSettings::depth) holds for this mode, one line.
const char* depthRule(BlendMode mode);

}  // namespace mfadvr
