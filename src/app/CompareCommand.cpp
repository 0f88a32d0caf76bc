// mfadvr compare A.png B.png [--diff D.png] [--gain G] [--json]
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "app/Commands.h"
#include "core/image/ImageMetrics.h"
#include "core/image/PngFile.h"
#include "core/util/Error.h"

namespace mfadvr::app {
namespace {

// JSON has no infinity: an infinite PSNR (identical images) becomes null.
nlohmann::json psnrJson(double psnr) {
  return std::isinf(psnr) ? nlohmann::json(nullptr) : nlohmann::json(psnr);
}

nlohmann::json metricsJson(double mse, double psnr, double ssim) {
  return {{"mse", mse}, {"psnr", psnrJson(psnr)}, {"ssim", ssim}};
}

std::string psnrText(double psnr) {
  if (std::isinf(psnr)) return "inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4f", psnr);
  return buf;
}

std::string row(const char* label, double mse, double psnr, double ssim) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%-6s %14.6f %12s %10.6f\n", label, mse, psnrText(psnr).c_str(),
                ssim);
  return buf;
}

}  // namespace

Command addCompareCommand(CLI::App& app) {
  struct Options {
    std::string a, b, diff;
    double gain = 1.0;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "compare", "Compare two PNG images: MSE, PSNR and SSIM per channel on 8-bit RGB");
  sub->add_option("a", o->a, "First image (PNG), e.g. the reference")->required();
  sub->add_option("b", o->b, "Second image (PNG)")->required();
  sub->add_option("--diff", o->diff, "Write the per-channel absolute difference as a PNG");
  sub->add_option("--gain", o->gain, "Multiply the difference image by this (clamped to 255)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  sub->add_flag("--json", o->json, "Print as JSON");
  sub->footer(
      "Alpha is ignored. MSE and PSNR (peak 255) per channel; the mean row's MSE is the mean over "
      "R, G, B, its PSNR comes from that MSE, its SSIM is the mean of the channel SSIMs. SSIM: "
      "Wang et al. 2004, 11x11 Gaussian window (sigma 1.5), K1 0.01, K2 0.03, mean of the map.");

  return {sub, [o]() {
            if (!std::isfinite(o->gain))
              throw CLI::ValidationError("--gain", "must be a finite number");
            const Image8 a = readPng(o->a);
            const Image8 b = readPng(o->b);
            if (a.width != b.width || a.height != b.height)
              throw Error("images differ in size: " + o->a + " is " + std::to_string(a.width) +
                          " x " + std::to_string(a.height) + ", " + o->b + " is " +
                          std::to_string(b.width) + " x " + std::to_string(b.height));
            const ImageComparison c = compareImages(a, b);
            if (!o->diff.empty()) writePng(o->diff, differenceImage(a, b, o->gain));

            if (o->json) {
              const char* names[3] = {"r", "g", "b"};
              nlohmann::json channels = nlohmann::json::object();
              for (int i = 0; i < 3; ++i)
                channels[names[i]] =
                    metricsJson(c.channel[i].mse, c.channel[i].psnr, c.channel[i].ssim);
              nlohmann::json j = {{"a", o->a},
                                  {"b", o->b},
                                  {"width", a.width},
                                  {"height", a.height},
                                  {"computed_on", "8-bit RGB, alpha ignored"},
                                  {"mse", c.mse},
                                  {"psnr", psnrJson(c.psnr)},
                                  {"ssim", c.ssim},
                                  {"identical", c.mse == 0},
                                  {"channels", channels}};
              if (!o->diff.empty()) j["diff"] = o->diff;
              std::cout << j.dump(2) << "\n";
              return 0;
            }
            std::string out = "a      " + o->a + "\nb      " + o->b + "\nsize   " +
                              std::to_string(a.width) + " x " + std::to_string(a.height) +
                              "  (8-bit RGB, alpha ignored)\n";
            char header[128];
            std::snprintf(header, sizeof header, "%-6s %14s %12s %10s\n", "", "MSE", "PSNR (dB)",
                          "SSIM");
            out += header;
            const char* labels[3] = {"R", "G", "B"};
            for (int i = 0; i < 3; ++i)
              out += row(labels[i], c.channel[i].mse, c.channel[i].psnr, c.channel[i].ssim);
            out += row("mean", c.mse, c.psnr, c.ssim);
            if (c.mse == 0) out += "identical (RGB)\n";
            if (!o->diff.empty()) out += "difference image written to " + o->diff + "\n";
            std::cout << out;
            return 0;
          }};
}

}  // namespace mfadvr::app
