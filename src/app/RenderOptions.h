#pragma once
// The scene options shared by the commands that render (render, demo): image size, camera,
// transfer function, shading, sampling. Registered on a CLI11 subcommand, then turned into
// RenderSettings for a loaded scene (its box frames the default camera; its spacing gives the
// default step; its value range anchors normalized transfer functions).
#include <CLI/CLI.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/SceneLoader.h"
#include "core/render/RenderSettings.h"

namespace mfadvr::app {

struct RenderOptions {
  std::string size = "512x512";
  std::string cameraFile, position, focalPoint, viewUp, range, background = "0,0,0";
  double viewAngle = 30.0, parallelScale = 0.0, azimuth = 0.0, elevation = 0.0, zoom = 1.0;
  bool parallel = false;
  std::string tf, colormap;
  std::string gradientOpacity, tf2d, tf2dRange;
  std::string curvatureTf, contourColor = "0,0,0";
  double contours = 0.0;
  double unitDistance = 0.0, ert = 0.99;
  std::optional<double> step;  // none: half the smallest data spacing
  bool shade = false, noHeadlight = false;
  float ambient = 0.3f, diffuse = 0.7f, specular = 0.2f, specularPower = 10.0f;
  std::vector<std::string> lights;
  int threads = 0;
  bool noSkip = false;
  std::string blend = "composite", averageRange, crop;
  std::vector<std::string> clipPlanes, isoValues;

  // Adds the options to `sub`.
  void addTo(CLI::App* sub);
  // Builds validated settings (throws CLI::ValidationError for malformed values and
  // mfadvr::Error for bad files or impossible scenes). tfWarning, when given, receives a
  // sentence for the user when the transfer function gives every value of the scene's value
  // range one opacity (an empty image, or the whole volume a uniform block: typically a preset in
  // data units, such as ct-skin's Hounsfield units, on data of another scale), else "".
  RenderSettings settingsFor(const LoadedScene& scene, std::string* tfWarning = nullptr) const;
};

// Adds --device (device/RenderDevice.h) to `sub`, storing into `choice`.
void addDeviceOption(CLI::App* sub, std::string& choice);

// The most samples a ray may take (box diagonal / step): a smaller step is refused before
// rendering, where it would run for hours without a sign of progress.
inline constexpr double kMaxSamplesPerRay = 1e6;

// "WxH" -> width, height.
void parseImageSize(const std::string& text, int& width, int& height);

}  // namespace mfadvr::app
