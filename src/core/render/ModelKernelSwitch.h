#pragma once
// The one switch per render of the MFA model: the spline's degree (splineDegreeSwitch), the
// domain mask, shading and empty-space skipping become the template arguments of
// f.template operator()<P, Masked, Shade, Skip>(), eight loops per degree. The CPU driver
// (ModelRenderer.cpp) instantiates its ray loop through it; MaxP caps the unrolled degrees
// (splineDegreeSwitch), as the tests' reference loops do.
#include "core/render/kernel/SplineRaySampler.h"

namespace mfadvr {

template <int MaxP = kMaxUnrolledDegree, class F>
void modelKernelSwitch(const ModelView& view, bool shade, F&& f) {
  const bool masked = view.mask.nodes != nullptr || view.boundary.nodes != nullptr;
  const bool skip = view.empty != nullptr || view.extremeUpper != nullptr;
  splineDegreeSwitch<MaxP>(view.spline, [&]<int P>() {
    auto withSkip = [&]<bool Masked, bool Shade>() {
      if (skip)
        f.template operator()<P, Masked, Shade, true>();
      else
        f.template operator()<P, Masked, Shade, false>();
    };
    auto withShade = [&]<bool Masked>() {
      if (shade)
        withSkip.template operator()<Masked, true>();
      else
        withSkip.template operator()<Masked, false>();
    };
    if (masked)
      withShade.template operator()<true>();
    else
      withShade.template operator()<false>();
  });
}

}  // namespace mfadvr
