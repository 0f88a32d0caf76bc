#pragma once
// Which array of an input file becomes the scalar field that is encoded: its name, whether it
// is read from the points or from the cells, and which component of a multi-component array.
// Shared by the volume and the scattered loaders; free of VTK types.
#include <string>

namespace mfadvr {

enum class FieldAssociation {
  kAny,     // point data first, then cell data
  kPoints,  // point data only
  kCells,   // cell data only (grids: one sample at each cell centre)
};

struct FieldSelection {
  static constexpr int kWholeArray = -1;  // the array must have one component
  static constexpr int kMagnitude = -2;   // the Euclidean norm of the components

  std::string name;  // empty: the active scalars, else the first array that can be used
  FieldAssociation association = FieldAssociation::kAny;
  int component = kWholeArray;  // 0, 1, ...: that component of each tuple

  bool chosen() const {
    return !name.empty() || association != FieldAssociation::kAny || component != kWholeArray;
  }
};

// "point" | "points" | "cell" | "cells" | "auto" (the --association option); throws
// mfadvr::Error otherwise.
FieldAssociation parseFieldAssociation(const std::string& text);

// "N" (a component index >= 0) | "magnitude" (the --component option); throws mfadvr::Error
// otherwise.
int parseFieldComponent(const std::string& text);

// "point data", "cell data".
const char* associationName(FieldAssociation association);

// The name an encoded field is given: the array's name, with "_magnitude" or "_N" appended
// when a component was chosen from a multi-component array.
std::string selectedFieldName(const std::string& arrayName, int components, int component);

}  // namespace mfadvr
