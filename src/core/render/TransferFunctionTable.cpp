#include "core/render/TransferFunctionTable.h"

#include <algorithm>

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

}  // namespace mfadvr
