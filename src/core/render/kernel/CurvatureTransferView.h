#pragma once
// Classification by the curvature of the level set through a sample (host and device), from
// the field's gradient and Hessian (field/Curvature.h, Kindlmann et al. 2003):
// - a curvature transfer function, a table over the principal curvatures (k1, k2): its colour
//   replaces the sample's by the entry's weight (before shading), its opacity multiplies the
//   sample's step opacity;
// - thickness-controlled contours (Kindlmann et al. 2003, section 5): a sample is on a contour
//   where |n . v| <= sqrt(T kv (2 - T kv)), v the ray direction, kv the level set's normal
//   curvature along v, T the contour's thickness in world units at the sample (a width in
//   pixels times a pixel's size at that distance along the ray); T kv is clamped to [0, 1].
//   On a circle of radius r = 1 / kv this band is where the surface lies within T of its
//   silhouette in the image, so contours keep one width in pixels whatever the surface's size.
//   Contour samples take the contour colour (after shading).
// ClassificationTables.h builds the table and the pixel footprint.
#include "core/field/Curvature.h"
#include "core/render/kernel/GradientTransferView.h"

namespace mfadvr {

// One entry of the curvature table: colour, how much of it replaces the sample's, and what
// the sample's opacity is multiplied by.
struct CurvatureEntry {
  float r, g, b, weight, opacity;
};

struct CurvatureTransferView {
  // width x height entries, entry (i, j) at table[j * width + i], i along k1 from k1Lo (index
  // (k1 - k1Lo) * k1Scale), j along k2; null: no curvature transfer function.
  const CurvatureEntry* table = nullptr;
  int width = 0, height = 0;
  float k1Lo = 0.0f, k1Scale = 0.0f, k2Lo = 0.0f, k2Scale = 0.0f;
  // Contours: their width in pixels (0: none) and colour; a pixel's size in world units at ray
  // distance t is pixelBase + pixelSlope * t.
  float contourPixels = 0.0f;
  float contourColor[3] = {0.0f, 0.0f, 0.0f};
  double pixelBase = 0.0, pixelSlope = 0.0;

  MFADVR_HD MFADVR_INLINE bool active() const { return table != nullptr || contourPixels > 0.0f; }

  // A visible sample at ray distance t along the unit direction d, with physical gradient g and
  // Hessian h (xx, xy, xz, yy, yz, zz): c (its unshaded colour) takes the table's colour, factor
  // is multiplied by the table's opacity, and contour gets the weight of the contour colour
  // (0 or 1). Where the gradient vanishes the level set has no curvature: nothing changes.
  MFADVR_HD MFADVR_INLINE void apply(const float g[3], const float h[6], const double d[3],
                                     double t, float c[3], float& factor, float& contour) const {
    contour = 0.0f;
    double n[3], G[3][3];
    if (!curvatureTensor(g, h, n, G)) return;
    if (table) {
      const PrincipalCurvatures k = principalCurvaturesOf(G);
      int i, j;
      float s, u;
      tableCell(static_cast<float>(k.k1), k1Lo, k1Scale, width, i, s);
      tableCell(static_cast<float>(k.k2), k2Lo, k2Scale, height, j, u);
      const CurvatureEntry* row0 = table + j * width;
      const CurvatureEntry* row1 = row0 + width;
      auto bilinear = [&](float CurvatureEntry::*channel) {
        return interpolate(interpolate(row0[i].*channel, row0[i + 1].*channel, s),
                           interpolate(row1[i].*channel, row1[i + 1].*channel, s), u);
      };
      const float w = bilinear(&CurvatureEntry::weight);
      c[0] += w * (bilinear(&CurvatureEntry::r) - c[0]);
      c[1] += w * (bilinear(&CurvatureEntry::g) - c[1]);
      c[2] += w * (bilinear(&CurvatureEntry::b) - c[2]);
      factor *= bilinear(&CurvatureEntry::opacity);
    }
    if (contourPixels > 0.0f) {
      const double thickness = contourPixels * (pixelBase + pixelSlope * t);
      const double kv = normalCurvature(n, G, d);
      double x = thickness * (kv < 0.0 ? -kv : kv);
      x = x < 1.0 ? x : 1.0;
      const double nv = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
      if ((nv < 0.0 ? -nv : nv) <= sqrt(x * (2.0 - x))) contour = 1.0f;
    }
  }
};

}  // namespace mfadvr
