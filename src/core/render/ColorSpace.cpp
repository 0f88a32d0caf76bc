#include "core/render/ColorSpace.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mfadvr {
namespace {

constexpr double kPi = std::numbers::pi;
const Vec3d kWhiteD65(0.9505, 1.0, 1.089);  // the reference white VTK uses

double srgbToLinear(double c) {
  return c > 0.04045 ? std::pow((c + 0.055) / 1.055, 2.4) : c / 12.92;
}
double linearToSrgb(double c) {
  return c > 0.0031308 ? 1.055 * std::pow(c, 1.0 / 2.4) - 0.055 : 12.92 * c;
}
double labF(double t) {
  return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116.0;
}
double labFInverse(double f) {
  const double t = f * f * f;
  return t > 0.008856 ? t : (f - 16.0 / 116.0) / 7.787;
}

Vec3d rgbToHsv(const Vec3d& c) {
  const double mx = c.maxCoeff(), mn = c.minCoeff(), d = mx - mn;
  double h = 0.0;
  if (d > 0.0) {
    if (mx == c.x())
      h = (c.y() - c.z()) / d;
    else if (mx == c.y())
      h = 2.0 + (c.z() - c.x()) / d;
    else
      h = 4.0 + (c.x() - c.y()) / d;
    h /= 6.0;
    if (h < 0.0) h += 1.0;
  }
  return {h, mx > 0.0 ? d / mx : 0.0, mx};
}

Vec3d hsvToRgb(const Vec3d& hsv) {
  const double h = (hsv.x() - std::floor(hsv.x())) * 6.0, s = hsv.y(), v = hsv.z();
  const int sector = std::min(static_cast<int>(h), 5);
  const double f = h - sector, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  switch (sector) {
    case 0:
      return {v, t, p};
    case 1:
      return {q, v, p};
    case 2:
      return {p, v, t};
    case 3:
      return {p, q, v};
    case 4:
      return {t, p, v};
    default:
      return {v, p, q};
  }
}

// Moreland, "Diverging Color Maps for Scientific Visualization" (2009): Msh is polar Lab.
Vec3d labToMsh(const Vec3d& lab) {
  const double m = lab.norm();
  const double s = m > 0.001 ? std::acos(lab.x() / m) : 0.0;
  const double h = s > 0.001 ? std::atan2(lab.z(), lab.y()) : 0.0;
  return {m, s, h};
}
Vec3d mshToLab(const Vec3d& msh) {
  return {msh.x() * std::cos(msh.y()), msh.x() * std::sin(msh.y()) * std::cos(msh.z()),
          msh.x() * std::sin(msh.y()) * std::sin(msh.z())};
}
double angleDiff(double a, double b) {
  double d = std::fmod(std::abs(a - b), 2 * kPi);
  return d > kPi ? 2 * kPi - d : d;
}
// Hue for an unsaturated end point, spun so the path to the saturated one is smooth (Moreland).
double adjustHue(const Vec3d& msh, double unsatM) {
  if (msh.x() >= unsatM - 0.1) return msh.z();
  const double spin =
      msh.y() * std::sqrt(unsatM * unsatM - msh.x() * msh.x()) / (msh.x() * std::sin(msh.y()));
  return msh.z() > -0.3 * kPi ? msh.z() + spin : msh.z() - spin;
}

Vec3d divergingInterpolate(const Vec3d& a, const Vec3d& b, double t) {
  Vec3d m1 = labToMsh(rgbToLab(a)), m2 = labToMsh(rgbToLab(b));
  // Two saturated, distinct hues: pass through white (unsaturated) in the middle.
  if (m1.y() > 0.05 && m2.y() > 0.05 && angleDiff(m1.z(), m2.z()) > 0.33 * kPi) {
    const double mid = std::max({m1.x(), m2.x(), 88.0});
    if (t < 0.5) {
      m2 = Vec3d(mid, 0.0, 0.0);
      t *= 2.0;
    } else {
      m1 = Vec3d(mid, 0.0, 0.0);
      t = 2.0 * t - 1.0;
    }
  }
  if (m1.y() < 0.05 && m2.y() > 0.05)
    m1.z() = adjustHue(m2, m1.x());
  else if (m2.y() < 0.05 && m1.y() > 0.05)
    m2.z() = adjustHue(m1, m2.x());
  return labToRgb(mshToLab((1.0 - t) * m1 + t * m2));
}

}  // namespace

Vec3d rgbToLab(const Vec3d& rgb) {
  const Vec3d lin(srgbToLinear(rgb.x()), srgbToLinear(rgb.y()), srgbToLinear(rgb.z()));
  const Vec3d xyz(0.4124 * lin.x() + 0.3576 * lin.y() + 0.1805 * lin.z(),
                  0.2126 * lin.x() + 0.7152 * lin.y() + 0.0722 * lin.z(),
                  0.0193 * lin.x() + 0.1192 * lin.y() + 0.9505 * lin.z());
  const double fx = labF(xyz.x() / kWhiteD65.x()), fy = labF(xyz.y() / kWhiteD65.y()),
               fz = labF(xyz.z() / kWhiteD65.z());
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Vec3d labToRgb(const Vec3d& lab) {
  const double fy = (lab.x() + 16.0) / 116.0, fx = lab.y() / 500.0 + fy, fz = fy - lab.z() / 200.0;
  const Vec3d xyz(labFInverse(fx) * kWhiteD65.x(), labFInverse(fy) * kWhiteD65.y(),
                  labFInverse(fz) * kWhiteD65.z());
  Vec3d lin(3.2406 * xyz.x() - 1.5372 * xyz.y() - 0.4986 * xyz.z(),
            -0.9689 * xyz.x() + 1.8758 * xyz.y() + 0.0415 * xyz.z(),
            0.0557 * xyz.x() - 0.2040 * xyz.y() + 1.0570 * xyz.z());
  Vec3d rgb(linearToSrgb(lin.x()), linearToSrgb(lin.y()), linearToSrgb(lin.z()));
  // Clip as VTK does: scale down an over-bright colour, then cut negatives.
  if (rgb.maxCoeff() > 1.0) rgb /= rgb.maxCoeff();
  return rgb.cwiseMax(0.0);
}

Vec3d interpolateColor(const Vec3d& a, const Vec3d& b, double t, ColorInterpolation space) {
  switch (space) {
    case ColorInterpolation::Rgb:
      return a + t * (b - a);
    case ColorInterpolation::Hsv: {
      Vec3d h1 = rgbToHsv(a), h2 = rgbToHsv(b);
      if (std::abs(h1.x() - h2.x()) > 0.5) (h1.x() > h2.x() ? h1.x() : h2.x()) -= 1.0;
      Vec3d h = h1 + t * (h2 - h1);
      if (h.x() < 0.0) h.x() += 1.0;
      return hsvToRgb(h);
    }
    case ColorInterpolation::Lab: {
      const Vec3d l1 = rgbToLab(a), l2 = rgbToLab(b);
      return labToRgb(l1 + t * (l2 - l1));
    }
    case ColorInterpolation::Diverging:
      return divergingInterpolate(a, b, t);
  }
  return a;
}

}  // namespace mfadvr
