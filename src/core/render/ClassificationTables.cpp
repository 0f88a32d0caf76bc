#include "core/render/ClassificationTables.h"

#include <cmath>

namespace mfadvr {

namespace {

TransferFunctionTable oneDimensionalTable(const RenderSettings& s) {
  const OpacityCorrection correction(s.sampleDistance / s.opacityUnitDistance);
  if (s.transferFunction2D) return TransferFunctionTable(*s.transferFunction2D, correction);
  return TransferFunctionTable(s.transferFunction, correction);
}

}  // namespace

ClassificationTables::ClassificationTables(const RenderSettings& s)
    : table_(oneDimensionalTable(s)) {
  if (!s.gradientOpacity.empty()) {
    // The piecewise-linear function sampled as the 1-D transfer function is.
    TransferFunction f;
    f.space = TfSpace::Data;
    f.color = {{0.0, Vec3f::Ones()}};
    f.opacity = s.gradientOpacity;
    const double lo = s.gradientOpacity.front().x;
    double hi = s.gradientOpacity.back().x;
    if (!(hi > lo)) hi = lo + 1.0;  // one x: a constant factor
    constexpr int n = kGradientOpacityEntries;
    gradientOpacity_.resize(n);
    for (int i = 0; i < n; ++i)
      gradientOpacity_[i] = f.opacityAt(i == n - 1 ? hi : lo + (hi - lo) * i / double(n - 1));
    opacityLo_ = static_cast<float>(lo);
    opacityScale_ = static_cast<float>((n - 1) / (hi - lo));
  }
  if (s.transferFunction2D) {
    const TransferFunction2D& t = *s.transferFunction2D;
    const OpacityCorrection correction(s.sampleDistance / s.opacityUnitDistance);
    width_ = t.width;
    height_ = t.height;
    table2D_.resize(static_cast<size_t>(width_) * height_);
    for (int j = 0; j < height_; ++j)
      for (int i = 0; i < width_; ++i) {
        const float* e = t.entry(i, j);
        table2D_[static_cast<size_t>(j) * width_ + i] = {
            e[0], e[1], e[2], e[3], correction.full(e[3]), {}};
      }
    valueLo_ = static_cast<float>(t.valueLo);
    valueScale_ = static_cast<float>((width_ - 1) / (t.valueHi - t.valueLo));
    gradientLo_ = static_cast<float>(t.gradientLo);
    gradientScale_ = static_cast<float>((height_ - 1) / (t.gradientHi - t.gradientLo));
  }
  CurvatureTransferView& c = curvatureView_;
  if (s.curvatureTransferFunction) {
    const CurvatureTransferFunction& t = *s.curvatureTransferFunction;
    curvature_.resize(static_cast<size_t>(t.width) * t.height);
    for (int j = 0; j < t.height; ++j)
      for (int i = 0; i < t.width; ++i) {
        const float* e = t.entry(i, j);
        curvature_[static_cast<size_t>(j) * t.width + i] = {e[0], e[1], e[2], e[3], e[4]};
      }
    c.width = t.width;
    c.height = t.height;
    c.k1Lo = static_cast<float>(t.k1Lo);
    c.k1Scale = static_cast<float>((t.width - 1) / (t.k1Hi - t.k1Lo));
    c.k2Lo = static_cast<float>(t.k2Lo);
    c.k2Scale = static_cast<float>((t.height - 1) / (t.k2Hi - t.k2Lo));
  }
  c.contourPixels = static_cast<float>(s.contourPixels);
  for (int a = 0; a < 3; ++a) c.contourColor[a] = s.contourColor[a];
}

CurvatureTransferView ClassificationTables::curvatureView(const CameraRays& rays) const {
  CurvatureTransferView v = curvatureView_;
  v.table = curvature_.empty() ? nullptr : curvature_.data();
  // A pixel spans 2 halfHeight |up| / height on the image plane (primaryRay), which lies
  // |forward| from the eye of a perspective view: its size grows by that over |forward| per
  // unit of distance along a ray. (The vectors need not be unit: a host's rays, raysFromVtk,
  // span its near plane.)
  auto norm = [](const double* x) { return std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]); };
  const double pixel = 2.0 * rays.halfHeight * norm(rays.up) / rays.height;
  v.pixelBase = rays.parallel ? pixel : 0.0;
  v.pixelSlope = rays.parallel ? 0.0 : pixel / norm(rays.forward);
  return v;
}

GradientTransferView ClassificationTables::gradientView() const {
  GradientTransferView v;
  if (!gradientOpacity_.empty()) {
    v.opacity = gradientOpacity_.data();
    v.opacityCount = static_cast<int>(gradientOpacity_.size());
    v.opacityLo = opacityLo_;
    v.opacityScale = opacityScale_;
  }
  if (!table2D_.empty()) {
    v.table = table2D_.data();
    v.width = width_;
    v.height = height_;
    v.valueLo = valueLo_;
    v.valueScale = valueScale_;
    v.gradientLo = gradientLo_;
    v.gradientScale = gradientScale_;
  }
  return v;
}

}  // namespace mfadvr
