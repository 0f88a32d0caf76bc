#pragma once
// Image quality metrics for comparing renderings with a reference (docs/architecture.md, Evaluation
// protocol). Everything is computed on 8-bit RGB values (0..255), alpha ignored, in double
// precision; docs/images-and-metrics.md states the definitions.
#include <array>

#include "core/image/Image.h"

namespace mfadvr {

struct ChannelMetrics {
  double mse = 0, psnr = 0, ssim = 0;
};

struct ImageComparison {
  std::array<ChannelMetrics, 3> channel;  // R, G, B
  // mse: mean over the 3 channels; psnr from that mse (peak 255); ssim: mean of the 3 channel
  // SSIMs.
  double mse = 0, psnr = 0, ssim = 0;
};

// Compares the RGB channels of two 8-bit images of equal size (alpha ignored; either may have 3
// or 4 channels); throws mfadvr::Error on a size mismatch.
//
// MSE: mean of (a - b)^2 over the pixels. PSNR = 10 log10(255^2 / MSE); +infinity when MSE == 0.
// SSIM: Wang, Bovik, Sheikh, Simoncelli 2004: an 11x11 circular-symmetric Gaussian window with
// sigma 1.5 (weights normalized to sum 1), K1 0.01, K2 0.03, L 255, the SSIM map over the 'valid'
// window positions (window fully inside the image), and the mean of the map. Along a side shorter
// than 11 pixels the window is clipped to the image: its length becomes that side, its 1-D
// weights the same Gaussian (sigma 1.5) centred on it and renormalized, and there is one position.
ImageComparison compareImages(const Image8& a, const Image8& b);

// Per-channel |a - b| times gain, rounded to nearest and clamped to 255; RGB output. Throws
// mfadvr::Error on a size mismatch or a gain that is negative or not finite.
Image8 differenceImage(const Image8& a, const Image8& b, double gain = 1.0);

// PSNR in dB of a mean squared error on 0..255 values; +infinity for 0.
double psnrFromMse(double mse);

}  // namespace mfadvr
