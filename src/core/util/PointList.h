#pragma once
// Text lists of 3-D points: one "x y z" (or "x y z v") per line, separated by commas and/or
// whitespace. Blank lines and lines starting with '#' are skipped; a first line without numbers
// is taken as a header. Anything else that is not the expected count of finite numbers is an
// error naming the line.
#include <string_view>
#include <vector>

#include "core/mesh/ScatteredData.h"
#include "core/util/Vec.h"

namespace mfadvr {

// `name` appears in error messages.
std::vector<Vec3d> parsePointList(std::string_view text, std::string_view name = "points");

// Points with times, for queries of time-varying models: four columns "x y z t" per line.
struct PointTimes {
  std::vector<Vec3d> points;
  std::vector<double> times;
};
PointTimes parsePointTimeList(std::string_view text, std::string_view name = "points");

// Scattered values: four columns "x y z v" per line (CSV or whitespace). A header with four
// names gives the field its name (the fourth); otherwise the field is called "value". Returns
// a point cloud (no cells) with source = `name`, fieldAssociation "point data", sampleType
// "text" and inputBytes 8 per value; it is not validated (the caller does that). The text must
// end with a line break: a last line without one is taken for a cut-off file (an error).
ScatteredData parsePointValueList(std::string_view text, std::string_view name = "points");

}  // namespace mfadvr
