#include "core/render/BlendMode.h"

namespace mfadvr {

namespace {
struct Name {
  std::string_view name;
  BlendMode mode;
};
// The short name of each mode first: blendModeName() takes it.
constexpr Name kNames[] = {
    {"composite", BlendMode::Composite}, {"max", BlendMode::Maximum},
    {"min", BlendMode::Minimum},         {"average", BlendMode::Average},
    {"additive", BlendMode::Additive},   {"iso", BlendMode::Iso},
    {"isosurface", BlendMode::Iso},      {"mip", BlendMode::Maximum},
    {"maximum", BlendMode::Maximum},     {"minimum", BlendMode::Minimum},
    {"minip", BlendMode::Minimum},       {"average-intensity", BlendMode::Average},
};
}  // namespace

std::optional<BlendMode> parseBlendMode(std::string_view name) {
  for (const Name& n : kNames)
    if (n.name == name) return n.mode;
  return std::nullopt;
}

const char* blendModeName(BlendMode mode) {
  for (const Name& n : kNames)
    if (n.mode == mode) return n.name.data();
  return "composite";
}

const char* depthRule(BlendMode mode) {
  switch (mode) {
    case BlendMode::Composite:
      return "ray distance from the camera position to the sample where the opacity first "
             "reaches 0.5";
    case BlendMode::Maximum:
    case BlendMode::Minimum:
      return "ray distance from the camera position to the extreme sample, where it is visible";
    case BlendMode::Iso:
      return "ray distance from the camera position to the first isosurface hit";
    default:
      return "ray distance from the camera position to the first sample that adds to the pixel";
  }
}

std::string blendModeChoices() {
  return "composite|max|min|average|additive|iso";
}

}  // namespace mfadvr
