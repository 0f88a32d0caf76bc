#pragma once
// The built-in colour maps and opacity maps, all in normalized x (0 = data min, 1 = data max),
// and whole transfer functions for medical data (colour and opacity together: CT in Hounsfield
// units, MR in fractions of the value range).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/render/TransferFunction.h"

namespace mfadvr {

// The colour map named `name` (case-insensitive; ParaView's names such as "Cool to Warm" and
// "Viridis (matplotlib)" are accepted too), or nullopt when there is none.
std::optional<std::vector<ColorPoint>> findColorMapPreset(std::string_view name);

// The opacity map for a preset form such as "step:0.5", or nullopt when the text before the first
// ':' names no opacity preset. Throws mfadvr::Error when the name is known but its parameters are
// not valid, saying which form was expected.
std::optional<std::vector<OpacityPoint>> findOpacityPreset(std::string_view spec);

// The complete transfer function named `name` (ct-bone, ct-skin, ct-soft-tissue, ct-vessels,
// mr-tissue, mr-vessels; case-insensitive), or nullopt. CT presets are in data space
// (Hounsfield units), MR presets normalized: MR intensities have no absolute scale.
std::optional<TransferFunction> findTransferFunctionPreset(std::string_view name);

// The names findTransferFunctionPreset knows.
std::vector<std::string> transferFunctionPresetNames();

}  // namespace mfadvr
