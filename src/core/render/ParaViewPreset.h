#pragma once
// Reading ParaView colour-map preset exports (Choose Preset > Export): a JSON array of objects
// with "Name", "ColorSpace", "RGBPoints" [x,r,g,b,...] and optionally "Points" [x,a,mid,sharp,...]
// for opacity. We do what ParaView does when it applies a preset: each list is rescaled from its
// own x range onto the normalized range [0,1].
#include <string>

#include <nlohmann/json.hpp>

#include "core/render/TransferFunction.h"

namespace mfadvr {

// True when `doc` has the shape of a ParaView preset export rather than our format.
bool isParaViewPreset(const nlohmann::json& doc);

// The preset named `name` (the first one when `name` is empty) as a normalized transfer function;
// a list the preset lacks is left empty. Colour maps in HSV, Lab or Diverging space are sampled
// densely into RGB points, because the renderer interpolates in RGB only. `where` names the file
// in error messages.
TransferFunction paraViewPresetToTransferFunction(const nlohmann::json& doc,
                                                  const std::string& name,
                                                  const std::string& where);

}  // namespace mfadvr
