#include "core/render/TransferFunction.h"

#include <cmath>
#include <sstream>

#include "core/util/Error.h"

namespace mfadvr {
namespace {

bool inUnit(double v) {
  return v >= 0.0 && v <= 1.0;
}  // false for NaN

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// Checks what both lists share: non-empty, finite x, sorted.
template <typename Point>
void validateXs(const std::vector<Point>& points, const char* list) {
  if (points.empty())
    throw Error(std::string("transfer function has no ") + list +
                " points (it needs at least one)");
  for (size_t i = 0; i < points.size(); ++i) {
    const std::string where = std::string(list) + "[" + std::to_string(i) + "]";
    if (!std::isfinite(points[i].x))
      throw Error("transfer function " + where + ": x is " + number(points[i].x) +
                  "; it must be finite");
    if (i > 0 && points[i].x < points[i - 1].x)
      throw Error("transfer function " + where + ": x = " + number(points[i].x) +
                  " comes after x = " + number(points[i - 1].x) +
                  "; points must be sorted by x (equal x make a jump)");
  }
}

// std::lerp is exact at both ends and monotonic, so x = 0 and 1 land exactly on the range ends.
double toData(double x, double vmin, double span) {
  return std::lerp(vmin, vmin + span, x);
}

}  // namespace

void TransferFunction::validate() const {
  validateXs(color, "color");
  validateXs(opacity, "opacity");
  for (size_t i = 0; i < color.size(); ++i) {
    const Vec3f& c = color[i].rgb;
    if (!(inUnit(c.x()) && inUnit(c.y()) && inUnit(c.z())))
      throw Error("transfer function color[" + std::to_string(i) + "]: rgb (" + number(c.x()) +
                  ", " + number(c.y()) + ", " + number(c.z()) +
                  ") must be in [0,1] (ParaView's scale, not 0..255)");
  }
  for (size_t i = 0; i < opacity.size(); ++i)
    if (!inUnit(opacity[i].alpha))
      throw Error("transfer function opacity[" + std::to_string(i) + "]: alpha " +
                  number(opacity[i].alpha) + " must be in [0,1]");
  if (!(std::isfinite(unitDistance) && unitDistance >= 0.0))
    throw Error("transfer function unit distance " + number(unitDistance) +
                " must be finite and >= 0 (0 means: the renderer's default)");
}

std::pair<float, float> TransferFunction::opacityOver(double lo, double hi) const {
  const float atLo = opacityAt(lo), atHi = opacityAt(hi);
  float least = std::min(atLo, atHi), greatest = std::max(atLo, atHi);
  for (const OpacityPoint& p : opacity)
    if (p.x > lo && p.x < hi) {
      least = std::min(least, p.alpha);
      greatest = std::max(greatest, p.alpha);
    }
  return {least, greatest};
}

TransferFunction TransferFunction::resolved(double vmin, double vmax) const {
  if (!(std::isfinite(vmin) && std::isfinite(vmax) && vmin <= vmax))
    throw Error("transfer function: bad data range [" + number(vmin) + ", " + number(vmax) + "]");
  // Constant data still needs a non-empty range so that "step:0.5" stays a step.
  const double span = vmax > vmin ? vmax - vmin : 1.0;
  TransferFunction out = *this;
  if (colorPointSpace() == TfSpace::Normalized)
    for (auto& p : out.color) p.x = toData(p.x, vmin, span);
  if (space == TfSpace::Normalized)
    for (auto& p : out.opacity) p.x = toData(p.x, vmin, span);
  out.space = TfSpace::Data;
  out.colorSpace.reset();
  return out;
}

}  // namespace mfadvr
