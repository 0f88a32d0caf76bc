#include "io/FieldSelection.h"

#include <algorithm>
#include <cctype>
#include <charconv>

#include "core/util/Error.h"

namespace mfadvr {
namespace {

// Option values are read in any case.
std::string lowered(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

}  // namespace

FieldAssociation parseFieldAssociation(const std::string& text) {
  const std::string t = lowered(text);
  if (t == "point" || t == "points") return FieldAssociation::kPoints;
  if (t == "cell" || t == "cells") return FieldAssociation::kCells;
  if (t == "auto" || t == "any") return FieldAssociation::kAny;
  throw Error("--association '" + text + "': expected point, cell or auto");
}

int parseFieldComponent(const std::string& text) {
  const std::string t = lowered(text);
  if (t == "magnitude" || t == "mag") return FieldSelection::kMagnitude;
  int value = -1;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), value);
  if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size() || value < 0 ||
      value > 1 << 20)
    throw Error("--component '" + text + "': expected a component index (0, 1, ...) or magnitude");
  return value;
}

const char* associationName(FieldAssociation association) {
  switch (association) {
    case FieldAssociation::kPoints:
      return "point data";
    case FieldAssociation::kCells:
      return "cell data";
    case FieldAssociation::kAny:
      break;
  }
  return "point or cell data";
}

std::string selectedFieldName(const std::string& arrayName, int components, int component) {
  if (component == FieldSelection::kWholeArray || components == 1) return arrayName;
  if (component == FieldSelection::kMagnitude) return arrayName + "_magnitude";
  return arrayName + "_" + std::to_string(component);
}

}  // namespace mfadvr
