#include "app/RenderOptions.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include "app/OptionParsing.h"
#include "core/util/Error.h"

namespace mfadvr::app {

namespace {

Vec3d toVec(const std::vector<double>& v) {
  return Vec3d(v[0], v[1], v[2]);
}

Vec3d parseVec(const std::string& option, const std::string& text) {
  return toVec(parseNumberList(option, text, 3, 3));
}

// Reads a camera in VTK's terms from JSON: position, focal_point, view_up, view_angle,
// parallel_projection, parallel_scale (all optional).
void readCameraFile(const std::string& path, Camera& camera) {
  std::ifstream in(path);
  if (!in) throw Error("cannot open camera file " + path);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw Error("camera file " + path + " is not valid JSON: " + e.what());
  }
  if (!j.is_object()) throw Error("camera file " + path + " must hold a JSON object");
  auto vec = [&](const char* key, Vec3d& out) {
    if (!j.contains(key)) return;
    const auto& a = j[key];
    if (!a.is_array() || a.size() != 3 || !a[0].is_number() || !a[1].is_number() ||
        !a[2].is_number())
      throw Error("camera file " + path + ": '" + key + "' must be an array of 3 numbers");
    out = Vec3d(a[0].get<double>(), a[1].get<double>(), a[2].get<double>());
  };
  auto number = [&](const char* key, double& out) {
    if (!j.contains(key)) return;
    if (!j[key].is_number())
      throw Error("camera file " + path + ": '" + key + "' must be a number");
    out = j[key].get<double>();
  };
  static const std::set<std::string> known = {
      "position", "focal_point", "view_up", "view_angle", "parallel_projection", "parallel_scale"};
  for (const auto& item : j.items())
    if (!known.contains(item.key()))
      throw Error("camera file " + path + ": unknown key '" + item.key() +
                  "' (known: position, focal_point, view_up, view_angle, parallel_projection, "
                  "parallel_scale)");
  vec("position", camera.position);
  vec("focal_point", camera.focalPoint);
  vec("view_up", camera.viewUp);
  number("view_angle", camera.viewAngle);
  number("parallel_scale", camera.parallelScale);
  if (j.contains("parallel_projection")) {
    if (!j["parallel_projection"].is_boolean())
      throw Error("camera file " + path + ": 'parallel_projection' must be true or false");
    camera.parallelProjection = j["parallel_projection"].get<bool>();
  }
}

// The sentence for RenderOptions::settingsFor's warning when `resolved` (the function `spec`
// placed on the value range; `range`: --range, empty if none) gives every value of the scene's
// range one opacity; empty otherwise. A constant field has one opacity whatever the function.
std::string uniformOpacityWarning(const TransferFunction& spec, const TransferFunction& resolved,
                                  const LoadedScene& scene, const std::string& range) {
  if (!(scene.valueMax > scene.valueMin)) return {};
  const auto [least, greatest] = resolved.opacityOver(scene.valueMin, scene.valueMax);
  if (least != greatest) return {};
  std::ostringstream m;
  m << "the transfer function gives every value of the data (" << scene.valueMin << " .. "
    << scene.valueMax << ") ";
  if (greatest == 0.0f)
    m << "opacity 0: the image will be empty";
  else
    m << "the same opacity " << greatest << ": the image will show the volume as a uniform "
      << "block, not its structures";
  if (spec.space == TfSpace::Data)
    m << ". Its points are data values (the ct-* presets are in Hounsfield units); the "
         "normalized forms (ramp, step:ISO, tent:CENTER:WIDTH) follow any data range";
  else if (!range.empty())
    m << " (the function is placed on --range " << range << ")";
  return m.str();
}

}  // namespace

void parseImageSize(const std::string& text, int& width, int& height) {
  const auto x = text.find('x');
  auto bad = [&] {
    return CLI::ValidationError("--size",
                                "expected WIDTHxHEIGHT (e.g. 1000x1000), got '" + text + "'");
  };
  if (x == std::string::npos) throw bad();
  try {
    size_t used = 0;
    const std::string w = text.substr(0, x), h = text.substr(x + 1);
    width = std::stoi(w, &used);
    if (used != w.size()) throw bad();
    height = std::stoi(h, &used);
    if (used != h.size()) throw bad();
  } catch (const std::logic_error&) {
    throw bad();
  }
  if (width < 1 || height < 1 || width > 32768 || height > 32768)
    throw CLI::ValidationError("--size", "width and height must be 1..32768");
}

void RenderOptions::addTo(CLI::App* sub) {
  sub->add_option("--size", size, "Image size WIDTHxHEIGHT")->capture_default_str()->group("Image");
  sub->add_option("--background", background, "Background colour R,G,B in [0,1]")
      ->capture_default_str()
      ->group("Image");
  sub->add_option("--threads", threads, "Render threads (0: all cores; the image is the same)")
      ->check(CLI::NonNegativeNumber)
      ->group("Image");

  const char* cam = "Camera (VTK semantics)";
  sub->add_option("--camera", cameraFile,
                  "JSON file with position, focal_point, view_up, view_angle, "
                  "parallel_projection, parallel_scale (any subset)")
      ->group(cam);
  sub->add_option("--position", position,
                  "Camera position X,Y,Z (default: framed like "
                  "ResetCamera, looking down -z)")
      ->group(cam);
  sub->add_option("--focal-point", focalPoint, "Camera focal point X,Y,Z")->group(cam);
  sub->add_option("--view-up", viewUp, "Camera view-up X,Y,Z")->group(cam);
  sub->add_option("--view-angle", viewAngle, "Vertical view angle, degrees")
      ->capture_default_str()
      ->group(cam);
  sub->add_flag("--parallel", parallel, "Parallel (orthographic) projection")->group(cam);
  sub->add_option("--parallel-scale", parallelScale,
                  "Half the view height in world units (default: framed)")
      ->group(cam);
  sub->add_option("--azimuth", azimuth, "Rotate about view-up, degrees (after framing)")
      ->group(cam);
  sub->add_option("--elevation", elevation, "Rotate up about the right axis, degrees")->group(cam);
  sub->add_option("--zoom", zoom, "Zoom factor (>1 magnifies)")->group(cam);

  const char* tfGroup = "Transfer function (docs/transfer-functions.md)";
  sub->add_option("--tf", tf,
                  "Opacity: ramp, step:ISO, ... (normalized to the value range), a medical preset "
                  "with its colours (ct-bone, ct-skin, ct-soft-tissue, ct-vessels in Hounsfield "
                  "units; mr-tissue, mr-vessels), inline 'x:a,x:a,...', or a JSON file (ours or "
                  "a ParaView preset) [default: ramp]")
      ->group(tfGroup);
  sub->add_option("--colormap", colormap,
                  "Colour: grayscale, cool-to-warm, viridis, red, white, ..., inline "
                  "'x:r:g:b,...', or a JSON file [default: the colours of the --tf file or "
                  "preset, else cool-to-warm]")
      ->group(tfGroup);
  sub->add_option("--range", range,
                  "Value range MIN,MAX that normalized TF points map onto (default: the data's)")
      ->group(tfGroup);
  sub->add_option("--gradient-opacity", gradientOpacity,
                  "Gradient opacity: each sample's opacity times a piecewise-linear function of "
                  "|grad f| (data units per world unit), inline 'G:A,G:A,...' (VTK's "
                  "SetGradientOpacity; composite blend)")
      ->group(tfGroup);
  sub->add_option("--tf2d", tf2d,
                  "2-D transfer function over (value, |grad f|) replacing --tf and --colormap: "
                  "a JSON file of boxes, or an RGBA PNG (x: value, bottom to top: |grad f|) "
                  "placed by --tf2d-range (composite blend)")
      ->group(tfGroup);
  sub->add_option("--tf2d-range", tf2dRange,
                  "The PNG's axes: GLO,GHI (|grad f|; values over --range or the data's) or "
                  "VLO,VHI,GLO,GHI")
      ->group(tfGroup);
  sub->add_option("--curvature-tf", curvatureTf,
                  "Colour (and opacity) by the principal curvatures k1 >= k2 of the level set "
                  "at each sample: a preset " +
                      curvaturePresetNames() +
                      " with an optional :K (the curvature of full colour, 1/world units; "
                      "default 1/8 of the inverse smallest data spacing), or a JSON file of "
                      "boxes over (k1, k2) (composite and iso blends)")
      ->group(tfGroup);
  sub->add_option("--contours", contours,
                  "Draw thickness-controlled contours (silhouettes) PIXELS wide, from the "
                  "curvature along the view (composite and iso blends)")
      ->group(tfGroup);
  sub->add_option("--contour-color", contourColor, "Colour R,G,B of --contours")
      ->capture_default_str()
      ->group(tfGroup);
  sub->add_option("--unit-distance", unitDistance,
                  "Opacity unit distance, world units (default: the TF file's, else the "
                  "smallest data spacing)")
      ->group(tfGroup);

  const char* shading = "Shading (Blinn-Phong)";
  sub->add_flag("--shade", shade, "Shade with the field's gradient")->group(shading);
  sub->add_option("--ambient", ambient, "Ambient coefficient")
      ->capture_default_str()
      ->group(shading);
  sub->add_option("--diffuse", diffuse, "Diffuse coefficient")
      ->capture_default_str()
      ->group(shading);
  sub->add_option("--specular", specular, "Specular coefficient")
      ->capture_default_str()
      ->group(shading);
  sub->add_option("--specular-power", specularPower, "Specular power")
      ->capture_default_str()
      ->group(shading);
  sub->add_option("--light", lights,
                  "Extra directional light DX,DY,DZ[,INTENSITY]: the direction it shines in, "
                  "world coordinates (repeatable)")
      ->group(shading);
  sub->add_flag("--no-headlight", noHeadlight, "No light at the camera")->group(shading);

  const char* sampling = "Sampling";
  sub->add_option("--step", step,
                  "Sample distance along rays, world units (default: half the smallest data "
                  "spacing)")
      ->group(sampling);
  sub->add_option("--ert", ert, "Early ray termination opacity (>= 1 disables it)")
      ->capture_default_str()
      ->group(sampling);
  const char* blending = "Blending and clipping";
  sub->add_option("--blend", blend,
                  "How samples become a pixel: " + blendModeChoices() +
                      " (VTK's blend modes; max/min classify the extreme value, average/additive "
                      "give a grey level: docs/rendering.md)")
      ->capture_default_str()
      ->group(blending);
  sub->add_option("--iso", isoValues,
                  "--blend iso: the isovalues (data units), V1,V2,... or, repeated, "
                  "V[:R,G,B[,A]] with the surface's colour and opacity (default: the transfer "
                  "function's at V)")
      ->group(blending);
  sub->add_option("--average-range", averageRange,
                  "--blend average: only values in MIN,MAX count (default: all)")
      ->group(blending);
  sub->add_option("--clip-plane", clipPlanes,
                  "Keep the side of the plane through PX,PY,PZ that the normal NX,NY,NZ points "
                  "to: PX,PY,PZ,NX,NY,NZ (repeatable, up to 8)")
      ->group(blending);
  sub->add_option("--crop", crop, "Render only inside the box X0,X1,Y0,Y1,Z0,Z1 (world units)")
      ->group(blending);
  sub->add_flag("--no-skip", noSkip,
                "MFA models: sample every step instead of skipping knot-span cells the transfer "
                "function makes invisible (the image is the same; for timing what skipping saves)")
      ->group(sampling);
}

RenderSettings RenderOptions::settingsFor(const LoadedScene& scene, std::string* tfWarning) const {
  RenderSettings s;
  parseImageSize(size, s.width, s.height);
  s.threads = threads;
  s.skipEmptySpace = !noSkip;
  s.background = parseVec("--background", background).cast<float>();
  if ((s.background.array() < 0.0f).any() || (s.background.array() > 1.0f).any())
    throw CLI::ValidationError("--background", "components must lie in [0, 1]");

  // Camera: VTK's default direction, framed on the box, then the user's explicit values, then
  // the relative moves.
  Camera& c = s.camera;
  c.viewAngle = viewAngle;  // before framing: the distance depends on it
  c.resetToBounds(scene.boxMin, scene.boxMax);
  if (!cameraFile.empty()) readCameraFile(cameraFile, c);
  if (!position.empty()) {
    c.position = parseVec("--position", position);
  }
  if (!focalPoint.empty()) c.focalPoint = parseVec("--focal-point", focalPoint);
  if (!viewUp.empty()) c.viewUp = parseVec("--view-up", viewUp);
  if (parallel) c.parallelProjection = true;
  if (parallelScale != 0.0) c.parallelScale = parallelScale;
  c.validate();
  if (azimuth != 0.0) c.azimuth(azimuth);
  if (elevation != 0.0) c.elevation(elevation);
  if (zoom != 1.0) {
    if (!(zoom > 0.0)) throw CLI::ValidationError("--zoom", "must be positive");
    c.zoom(zoom);
  }
  c.validate();

  // Transfer function, resolved against the common value range.
  const TransferFunction tfSpec = parseTransferFunction(tf, colormap);
  double lo = scene.valueMin, hi = scene.valueMax;
  if (!range.empty()) {
    const auto r = parseNumberList("--range", range, 2, 2);
    if (!(r[1] > r[0])) throw CLI::ValidationError("--range", "MAX must exceed MIN");
    lo = r[0];
    hi = r[1];
  }
  s.transferFunction = tfSpec.resolved(lo, hi);
  if (!gradientOpacity.empty()) {
    std::stringstream points(gradientOpacity);
    for (std::string point; std::getline(points, point, ',');) {
      const auto colon = point.find(':');
      if (colon == std::string::npos)
        throw CLI::ValidationError(
            "--gradient-opacity",
            "expected points G:A,G:A,... (|grad f| : opacity), got '" + point + "'");
      const double g = parseNumberList("--gradient-opacity", point.substr(0, colon), 1, 1)[0];
      const double a = parseNumberList("--gradient-opacity", point.substr(colon + 1), 1, 1)[0];
      if (!(g >= 0.0) || !(a >= 0.0 && a <= 1.0))
        throw CLI::ValidationError("--gradient-opacity",
                                   "|grad f| must be >= 0 and opacity in [0, 1]: '" + point + "'");
      if (!s.gradientOpacity.empty() && g < s.gradientOpacity.back().x)
        throw CLI::ValidationError("--gradient-opacity", "the |grad f| points must be sorted");
      s.gradientOpacity.push_back({g, static_cast<float>(a)});
    }
  }
  if (!tf2dRange.empty() && tf2d.empty())
    throw CLI::ValidationError("--tf2d-range", "applies to --tf2d");
  if (!tf2d.empty()) {
    std::optional<TransferFunction2DRange> axes;
    if (!tf2dRange.empty()) {
      const auto r = parseNumberList("--tf2d-range", tf2dRange, 2, 4);
      if (r.size() == 3)
        throw CLI::ValidationError("--tf2d-range", "expected GLO,GHI or VLO,VHI,GLO,GHI");
      axes = r.size() == 2 ? TransferFunction2DRange{lo, hi, r[0], r[1]}
                           : TransferFunction2DRange{r[0], r[1], r[2], r[3]};
    }
    s.transferFunction2D = readTransferFunction2D(tf2d, axes ? &*axes : nullptr);
  }
  if (tfWarning) *tfWarning = uniformOpacityWarning(tfSpec, s.transferFunction, scene, range);
  const double smallestSpacing = scene.spacing.minCoeff();
  if (!curvatureTf.empty())
    s.curvatureTransferFunction =
        readCurvatureTransferFunction(curvatureTf, 1.0 / (8.0 * smallestSpacing));
  if (!std::isfinite(contours) || contours < 0.0)
    throw CLI::ValidationError("--contours", "must be a width in pixels >= 0");
  s.contourPixels = contours;
  s.contourColor = parseVec("--contour-color", contourColor).cast<float>();
  if ((s.contourColor.array() < 0.0f).any() || (s.contourColor.array() > 1.0f).any())
    throw CLI::ValidationError("--contour-color", "components must lie in [0, 1]");
  if (unitDistance < 0.0 || !std::isfinite(unitDistance))
    throw CLI::ValidationError("--unit-distance", "must be positive");
  s.opacityUnitDistance = unitDistance > 0.0        ? unitDistance
                          : tfSpec.unitDistance > 0 ? tfSpec.unitDistance
                                                    : smallestSpacing;
  if (step && (!(*step > 0.0) || !std::isfinite(*step)))
    throw CLI::ValidationError("--step",
                               "must be a positive distance (omit it for the default, "
                               "half the smallest data spacing)");
  s.sampleDistance = step ? *step : 0.5 * smallestSpacing;
  const double diagonal = (scene.boxMax - scene.boxMin).norm();
  if (diagonal / s.sampleDistance > kMaxSamplesPerRay) {
    char m[256];
    std::snprintf(m, sizeof m,
                  "%g would take %.3g samples along a ray through the %g-long box; at most %.0e "
                  "(a step of at least %g)",
                  s.sampleDistance, diagonal / s.sampleDistance, diagonal, kMaxSamplesPerRay,
                  diagonal / kMaxSamplesPerRay);
    throw CLI::ValidationError("--step", m);
  }
  s.earlyTerminationOpacity = ert;

  const auto mode = parseBlendMode(blend);
  if (!mode)
    throw CLI::ValidationError("--blend",
                               "expected " + blendModeChoices() + ", got '" + blend + "'");
  s.blend = *mode;
  for (const auto& text : isoValues) {
    const auto colon = text.find(':');
    if (colon == std::string::npos) {
      for (double v : parseNumberList("--iso", text, 1, kMaxIsoValues))
        s.isoSurfaces.push_back({v, {}, {}});
      continue;
    }
    IsoSurface iso;
    iso.value = parseNumberList("--iso", text.substr(0, colon), 1, 1)[0];
    const auto c = parseNumberList("--iso", text.substr(colon + 1), 3, 4);
    for (double x : c)
      if (!(x >= 0.0 && x <= 1.0))
        throw CLI::ValidationError("--iso", "colour and opacity must lie in [0, 1]: " + text);
    iso.color = Vec3f(float(c[0]), float(c[1]), float(c[2]));
    if (c.size() == 4) iso.opacity = static_cast<float>(c[3]);
    s.isoSurfaces.push_back(iso);
  }
  if (!s.isoSurfaces.empty() && s.blend != BlendMode::Iso)
    throw CLI::ValidationError("--iso", "applies to --blend iso only");
  if (s.blend == BlendMode::Iso && s.isoSurfaces.empty())
    throw CLI::ValidationError("--blend", "iso needs the isovalues: --iso V1,V2,...");
  if (s.isoSurfaces.size() > static_cast<size_t>(kMaxIsoValues))
    throw CLI::ValidationError("--iso", "at most " + std::to_string(kMaxIsoValues) + " isovalues");
  if (!averageRange.empty()) {
    if (s.blend != BlendMode::Average)
      throw CLI::ValidationError("--average-range", "applies to --blend average only");
    const auto r = parseNumberList("--average-range", averageRange, 2, 2);
    if (!(r[1] >= r[0])) throw CLI::ValidationError("--average-range", "MAX must be >= MIN");
    s.averageRange = std::pair(r[0], r[1]);
  }
  if (clipPlanes.size() > static_cast<size_t>(kMaxClipPlanes))
    throw CLI::ValidationError("--clip-plane", "at most " + std::to_string(kMaxClipPlanes) +
                                                   " planes, got " +
                                                   std::to_string(clipPlanes.size()));
  for (const auto& text : clipPlanes) {
    const auto v = parseNumberList("--clip-plane", text, 6, 6);
    ClipPlane c;
    c.point = Vec3d(v[0], v[1], v[2]);
    c.normal = Vec3d(v[3], v[4], v[5]);
    if (!(c.normal.norm() > 0.0))
      throw CLI::ValidationError("--clip-plane", "the normal NX,NY,NZ must not be zero: " + text);
    s.clipPlanes.push_back(c);
  }
  if (!crop.empty()) {
    const auto v = parseNumberList("--crop", crop, 6, 6);
    DomainBox b;
    for (int a = 0; a < 3; ++a) {
      if (!(v[2 * a + 1] >= v[2 * a]))
        throw CLI::ValidationError("--crop",
                                   "each axis needs MIN <= MAX (X0,X1,Y0,Y1,Z0,Z1): " + crop);
      b.min[a] = v[2 * a];
      b.max[a] = v[2 * a + 1];
    }
    s.crop = b;
  }

  s.shade = shade;
  s.lighting.ambient = ambient;
  s.lighting.diffuse = diffuse;
  s.lighting.specular = specular;
  s.lighting.specularPower = specularPower;
  s.lighting.headlight = !noHeadlight;
  for (const auto& text : lights) {
    const auto v = parseNumberList("--light", text, 3, 4);
    DirectionalLight l;
    l.direction = Vec3d(v[0], v[1], v[2]);
    if (v.size() == 4) l.intensity = static_cast<float>(v[3]);
    s.lighting.lights.push_back(l);
  }
  if (shade && s.lighting.lights.empty() && !s.lighting.headlight)
    throw CLI::ValidationError("--no-headlight", "shading needs a light: add --light");
  s.validate();
  return s;
}

void addDeviceOption(CLI::App* sub, std::string& choice) {
  sub->add_option("--device", choice,
                  "Where to render: auto (a CUDA GPU when one is usable and the method runs "
                  "there, else the CPU), cpu, or cuda (error when no GPU can). The GPU renders "
                  "'mfa' and 'trilinear'")
      ->check(CLI::IsMember({"auto", "cpu", "cuda"}))
      ->capture_default_str();
}

}  // namespace mfadvr::app
