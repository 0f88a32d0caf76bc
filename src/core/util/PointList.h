#pragma once
// Text lists of 3-D points: one "x y z" per line, separated by commas and/or whitespace.
// Blank lines and lines starting with '#' are skipped; a first line without numbers is taken as
// a header. Anything else that is not three finite numbers is an error naming the line.
#include <string_view>
#include <vector>

#include "core/util/Vec.h"

namespace mfadvr {

// `name` appears in error messages.
std::vector<Vec3d> parsePointList(std::string_view text, std::string_view name = "points");

}  // namespace mfadvr
