#include "core/image/ImageMetrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/util/Error.h"

namespace mfadvr {
namespace {

constexpr int kWindow = 11;
constexpr double kSigma = 1.5;
constexpr double kPeak = 255.0;
constexpr double kC1 = (0.01 * kPeak) * (0.01 * kPeak);
constexpr double kC2 = (0.03 * kPeak) * (0.03 * kPeak);

void checkSameSize(const Image8& a, const Image8& b, const char* what) {
  checkImage8(a, std::string(what) + ": first image");
  checkImage8(b, std::string(what) + ": second image");
  if (a.width != b.width || a.height != b.height)
    throw Error(std::string(what) + ": images differ in size (" + std::to_string(a.width) + " x " +
                std::to_string(a.height) + " and " + std::to_string(b.width) + " x " +
                std::to_string(b.height) + ")");
}

// 1-D Gaussian weights of length n (at most kWindow) centred on the window, summing to 1. The
// 2-D circular-symmetric window is the outer product of two of these, which is what makes the
// filtering separable.
std::vector<double> gaussianWeights(int n) {
  std::vector<double> w(n);
  const double centre = 0.5 * (n - 1);
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double d = i - centre;
    w[i] = std::exp(-d * d / (2 * kSigma * kSigma));
    sum += w[i];
  }
  for (double& v : w) v /= sum;
  return w;
}

// Mean SSIM of channel c. Filters x, y, x^2, y^2 and xy with the window in two 1-D passes over
// the valid positions: rows first (into `h`, five values per position), then columns.
double channelSsim(const Image8& a, const Image8& b, int c) {
  const int width = a.width, height = a.height;
  const int nx = std::min(kWindow, width), ny = std::min(kWindow, height);
  const std::vector<double> wx = gaussianWeights(nx), wy = gaussianWeights(ny);
  const int outW = width - nx + 1, outH = height - ny + 1;

  std::vector<double> h(5 * static_cast<size_t>(outW) * height);
  std::vector<double> xs(width), ys(width);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const size_t pa = (static_cast<size_t>(y) * width + x) * a.channels + c;
      const size_t pb = (static_cast<size_t>(y) * width + x) * b.channels + c;
      xs[x] = a.data[pa];
      ys[x] = b.data[pb];
    }
    double* row = h.data() + 5 * static_cast<size_t>(y) * outW;
    for (int i = 0; i < outW; ++i) {
      double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
      for (int k = 0; k < nx; ++k) {
        const double w = wx[k], u = xs[i + k], v = ys[i + k];
        sx += w * u;
        sy += w * v;
        sxx += w * u * u;
        syy += w * v * v;
        sxy += w * u * v;
      }
      double* o = row + 5 * static_cast<size_t>(i);
      o[0] = sx, o[1] = sy, o[2] = sxx, o[3] = syy, o[4] = sxy;
    }
  }

  double total = 0;
  std::vector<double> acc(5 * static_cast<size_t>(outW));
  for (int j = 0; j < outH; ++j) {
    std::fill(acc.begin(), acc.end(), 0.0);
    for (int k = 0; k < ny; ++k) {
      const double w = wy[k];
      const double* row = h.data() + 5 * static_cast<size_t>(j + k) * outW;
      for (size_t q = 0; q < acc.size(); ++q) acc[q] += w * row[q];
    }
    double rowSum = 0;
    for (int i = 0; i < outW; ++i) {
      const double* m = acc.data() + 5 * static_cast<size_t>(i);
      const double mx = m[0], my = m[1];
      const double vx = m[2] - mx * mx, vy = m[3] - my * my, cxy = m[4] - mx * my;
      rowSum +=
          ((2 * mx * my + kC1) * (2 * cxy + kC2)) / ((mx * mx + my * my + kC1) * (vx + vy + kC2));
    }
    total += rowSum;
  }
  return total / (static_cast<double>(outW) * outH);
}

}  // namespace

double psnrFromMse(double mse) {
  if (mse == 0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(kPeak * kPeak / mse);
}

ImageComparison compareImages(const Image8& a, const Image8& b) {
  checkSameSize(a, b, "compareImages");
  const size_t n = static_cast<size_t>(a.width) * a.height;
  ImageComparison r;
  for (int c = 0; c < 3; ++c) {
    double sum = 0;
    for (size_t i = 0; i < n; ++i) {
      const double d = static_cast<double>(a.data[i * a.channels + c]) - b.data[i * b.channels + c];
      sum += d * d;
    }
    ChannelMetrics& m = r.channel[c];
    m.mse = sum / static_cast<double>(n);
    m.psnr = psnrFromMse(m.mse);
    m.ssim = channelSsim(a, b, c);
  }
  r.mse = (r.channel[0].mse + r.channel[1].mse + r.channel[2].mse) / 3.0;
  r.psnr = psnrFromMse(r.mse);
  r.ssim = (r.channel[0].ssim + r.channel[1].ssim + r.channel[2].ssim) / 3.0;
  return r;
}

Image8 differenceImage(const Image8& a, const Image8& b, double gain) {
  checkSameSize(a, b, "differenceImage");
  if (!std::isfinite(gain) || gain < 0)
    throw Error("differenceImage: gain must be finite and not negative, got " +
                std::to_string(gain));
  Image8 out;
  out.width = a.width;
  out.height = a.height;
  out.channels = 3;
  const size_t n = static_cast<size_t>(a.width) * a.height;
  out.data.resize(3 * n);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const double d =
          std::abs(static_cast<double>(a.data[i * a.channels + c]) - b.data[i * b.channels + c]);
      out.data[3 * i + c] = static_cast<std::uint8_t>(std::min(255.0, std::round(d * gain)));
    }
  return out;
}

}  // namespace mfadvr
