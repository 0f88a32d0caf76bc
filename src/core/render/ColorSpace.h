#pragma once
// Colour interpolation in the spaces ParaView presets name ("ColorSpace"), following
// vtkColorTransferFunction: RGB, HSV (shortest way round the hue circle), CIELAB, and Moreland's
// diverging Msh space. Used to turn such presets into dense RGB points, because the renderer
// interpolates in RGB only.
#include <string>

#include "core/util/Vec.h"

namespace mfadvr {

enum class ColorInterpolation { Rgb, Hsv, Lab, Diverging };

// sRGB in [0,1] <-> CIELAB (D65 white), as vtkMath::RGBToLab / LabToRGB.
Vec3d rgbToLab(const Vec3d& rgb);
Vec3d labToRgb(const Vec3d& lab);  // out-of-gamut results are clipped into [0,1]

// The colour a fraction t in [0,1] of the way from a to b.
Vec3d interpolateColor(const Vec3d& a, const Vec3d& b, double t, ColorInterpolation space);

}  // namespace mfadvr
