#include "core/render/TransferFunctionTable.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/util/Error.h"

namespace mfadvr {

TransferFunctionTable::TransferFunctionTable(const TransferFunction& tf,
                                             const OpacityCorrection& correction)
    : entries_(kEntries) {
  if (tf.space != TfSpace::Data || tf.colorPointSpace() != TfSpace::Data)
    throw Error("internal: the transfer function table needs data-value points");
  if (tf.color.empty() || tf.opacity.empty()) throw Error("transfer function has no points");
  double lo = std::min(tf.color.front().x, tf.opacity.front().x);
  double hi = std::max(tf.color.back().x, tf.opacity.back().x);
  if (!(hi > lo)) hi = lo + 1.0;  // a single x: constant maps, any span will do
  lo_ = static_cast<float>(lo);
  scale_ = static_cast<float>((kEntries - 1) / (hi - lo));
  for (int i = 0; i < kEntries; ++i) {
    const double x = i == kEntries - 1 ? hi : lo + (hi - lo) * i / double(kEntries - 1);
    const Vec3f rgb = tf.colorAt(x);
    const float alpha = tf.opacityAt(x);
    entries_[i] = {rgb[0], rgb[1], rgb[2], alpha, correction.full(alpha), {}};
  }
  countVisible();
}

TransferFunctionTable::TransferFunctionTable(const TransferFunction2D& tf,
                                             const OpacityCorrection& correction)
    : entries_(kEntries) {
  tf.validate();
  const double lo = tf.valueLo, hi = tf.valueHi;
  lo_ = static_cast<float>(lo);
  scale_ = static_cast<float>((kEntries - 1) / (hi - lo));
  // Each 2-D column's greatest opacity over the gradient axis.
  std::vector<float> column(tf.width, 0.0f);
  for (int j = 0; j < tf.height; ++j)
    for (int i = 0; i < tf.width; ++i) column[i] = std::max(column[i], tf.entry(i, j)[3]);
  const double columns = (tf.width - 1) / (hi - lo);  // 2-D column index per value
  for (int k = 0; k < kEntries; ++k) {
    // Values in [x(k-1), x(k+1)] interpolate from entry k; they read 2-D columns
    // floor(u) .. floor(u) + 1 for u over that span (one more each side for rounding).
    const double x0 = lo + (hi - lo) * (k - 1) / double(kEntries - 1);
    const double x1 = lo + (hi - lo) * (k + 1) / double(kEntries - 1);
    const int c0 =
        std::clamp(static_cast<int>(std::floor((x0 - lo) * columns)) - 1, 0, tf.width - 1);
    const int c1 =
        std::clamp(static_cast<int>(std::floor((x1 - lo) * columns)) + 2, 0, tf.width - 1);
    float alpha = 0.0f;
    for (int c = c0; c <= c1; ++c) alpha = std::max(alpha, column[c]);
    entries_[k] = {1.0f, 1.0f, 1.0f, alpha, correction.full(alpha), {}};
  }
  countVisible();
}

void TransferFunctionTable::countVisible() {
  visibleBefore_.assign(kEntries + 1, 0);
  for (int i = 0; i < kEntries; ++i)
    visibleBefore_[i + 1] = visibleBefore_[i] + (entries_[i].alpha != 0.0f ? 1 : 0);
}

bool TransferFunctionTable::transparentOver(float lo, float hi) const {
  int first, last;
  if (!touchedEntries(lo, hi, first, last)) return false;
  return visibleBefore_[last + 1] - visibleBefore_[first] == 0;
}

bool TransferFunctionTable::mayBeTransparentOver(float lo, float hi) const {
  int first, last;
  if (!touchedEntries(lo, hi, first, last)) return true;
  return visibleBefore_[last + 1] - visibleBefore_[first] < last + 1 - first;
}

namespace {
// Floats in their order as integers (both zeros as 0), and back.
std::int64_t orderedKey(float f) {
  std::int32_t bits;
  std::memcpy(&bits, &f, 4);
  return bits >= 0 ? std::int64_t(bits) : -std::int64_t(bits & 0x7fffffff);
}
float fromOrderedKey(std::int64_t key) {
  const std::uint32_t bits =
      key >= 0 ? static_cast<std::uint32_t>(key) : static_cast<std::uint32_t>(-key) | 0x80000000u;
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}
// The last float in [-FLT_MAX, FLT_MAX] where `holds` (true at -FLT_MAX, monotone) is true.
template <class Holds>
float lastWhere(Holds holds) {
  std::int64_t yes = orderedKey(-FLT_MAX), no = orderedKey(FLT_MAX);
  while (no - yes > 1) {
    const std::int64_t mid = yes + (no - yes) / 2;
    (holds(fromOrderedKey(mid)) ? yes : no) = mid;
  }
  return fromOrderedKey(yes);
}
}  // namespace

float TransferFunctionTable::transparentUpTo() const {
  // transparentOver(-FLT_MAX, v) only loses entries' transparency as v grows: monotone.
  if (!transparentOver(-FLT_MAX, -FLT_MAX)) return -INFINITY;
  if (transparentOver(-FLT_MAX, FLT_MAX)) return INFINITY;
  return lastWhere([&](float v) { return transparentOver(-FLT_MAX, v); });
}

float TransferFunctionTable::transparentFrom() const {
  if (!transparentOver(FLT_MAX, FLT_MAX)) return INFINITY;
  if (transparentOver(-FLT_MAX, FLT_MAX)) return -INFINITY;
  return -lastWhere([&](float v) { return transparentOver(-v, FLT_MAX); });
}

}  // namespace mfadvr
