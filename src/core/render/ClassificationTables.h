#pragma once
// Every table a render classifies its samples with, built once per render from its settings:
// the 1-D transfer-function table (with a 2-D transfer function: that function's envelope over
// the gradient axis, which decides which samples and cells are visible), the gradient-opacity
// table and the 2-D table (GradientTransferView.h reads the last two), the curvature table and
// contours (CurvatureTransferView.h).
#include <vector>

#include "core/render/RenderSettings.h"
#include "core/render/TransferFunctionTable.h"
#include "core/render/kernel/CurvatureTransferView.h"
#include "core/render/kernel/GradientTransferView.h"

namespace mfadvr {

class ClassificationTables {
 public:
  // Entries of the gradient-opacity table, evenly spaced over its points' span.
  static constexpr int kGradientOpacityEntries = 1024;

  // settings must be validated (their transfer function resolved to data values).
  explicit ClassificationTables(const RenderSettings& settings);
  ClassificationTables(const ClassificationTables&) = delete;
  ClassificationTables& operator=(const ClassificationTables&) = delete;

  const TransferFunctionTable& table() const { return table_; }
  // Valid while this object lives; inactive without gradient classification.
  GradientTransferView gradientView() const;
  // The arrays gradientView() points to and their sizes in bytes (for a device copy).
  size_t gradientOpacityBytes() const { return gradientOpacity_.size() * sizeof(float); }
  size_t table2DBytes() const { return table2D_.size() * sizeof(TfEntry); }
  // Valid while this object lives; inactive without curvature classification. rays: the
  // render's primary rays (a pixel's size along them sizes the contours).
  CurvatureTransferView curvatureView(const CameraRays& rays) const;
  size_t curvatureTableBytes() const { return curvature_.size() * sizeof(CurvatureEntry); }

 private:
  TransferFunctionTable table_;
  std::vector<float> gradientOpacity_;
  float opacityLo_ = 0.0f, opacityScale_ = 0.0f;
  std::vector<TfEntry> table2D_;
  int width_ = 0, height_ = 0;
  float valueLo_ = 0.0f, valueScale_ = 0.0f, gradientLo_ = 0.0f, gradientScale_ = 0.0f;
  std::vector<CurvatureEntry> curvature_;
  CurvatureTransferView curvatureView_;  // all but the pixel size
};

}  // namespace mfadvr
