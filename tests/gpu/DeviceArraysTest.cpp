// The host side of the CUDA driver, checked on every machine (no GPU needed): the arrays it
// uploads have the sizes of the containers that own them, and a render from copies of exactly
// those arrays (host buffers standing for GPU memory), through the relocated structs the kernels
// receive, is the CPU's image bit for bit. Every pointer the kernels read is checked to point
// into a copy, and under AddressSanitizer a copy too short for what the kernels read fails.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <optional>

#include "GpuTestScenes.h"
#include "core/field/ModelField.h"
#include "core/render/ModelRenderSetup.h"
#include "core/render/RayCaster.h"
#include "core/util/Error.h"
#include "gpu/DeviceArrays.h"

namespace mfadvr {
namespace {

using namespace test;
using gpu::HostArray;

// Host buffers standing for device copies.
struct Copies {
  std::vector<std::vector<unsigned char>> buffers;
  std::vector<const void*> addresses;

  explicit Copies(const std::vector<HostArray>& arrays) {
    for (const HostArray& a : arrays) {
      buffers.emplace_back(a.bytes);
      if (a.bytes) std::memcpy(buffers.back().data(), a.data, a.bytes);
      addresses.push_back(buffers.back().data());
    }
  }
  bool owns(const void* p) const {
    for (const auto& b : buffers)
      if (p == b.data()) return true;
    return false;
  }
};

std::vector<const Model*> models() {
  std::vector<const Model*> out;
  for (int p = 1; p <= 5; ++p) out.push_back(&mlModel(p));
  out.push_back(&mixedDegreeModel());
  out.push_back(&maskedModel());
  out.push_back(&boundedModel());
  return out;
}

TEST(DeviceArrays, SizesAreThoseOfTheOwningContainers) {
  for (const Model* m : models()) {
    ModelView view;
    view.spline = m->spline().view();
    view.mask = m->mask().view();
    if (m->boundary()) view.boundary = m->boundary()->view();
    const std::vector<HostArray> arrays = gpu::modelArrays(view);
    ASSERT_EQ(arrays.size(), 10u + (m->mask().empty() ? 0u : 1u) + (m->boundary() ? 2u : 0u));
    EXPECT_EQ(arrays[0].data, m->spline().controlPoints().data());
    EXPECT_EQ(arrays[0].bytes, m->spline().controlPoints().size() * sizeof(float));
    for (int a = 0; a < 3; ++a) {
      const KnotVector& k = m->spline().knots(a);
      EXPECT_EQ(arrays[1 + 3 * a].bytes, k.knots().size() * sizeof(double)) << "axis " << a;
      EXPECT_EQ(arrays[2 + 3 * a].bytes, k.basisPolynomials().size() * sizeof(float));
    }
    if (!m->mask().empty()) {
      EXPECT_EQ(arrays[10].bytes, m->mask().nodes().size());
    }
    if (const DomainBoundary* b = m->boundary()) {
      EXPECT_EQ(arrays[11].bytes, std::size_t(b->view().nodeCount) * sizeof(BoundaryNode));
      EXPECT_EQ(arrays[12].bytes, b->triangles().size() * 9 * sizeof(double));
    }
    EXPECT_GT(gpu::totalBytes(arrays), arrays[0].bytes);
  }
}

TEST(DeviceArrays, RelocatedCopiesRenderTheCpuImage) {
  int renders = 0, skipping = 0, withRayEnds = 0, bounded = 0;
  for (const Model* m : models())
    for (const TransferFunction& tf : {transferFunctions()[0], transferFunctions()[2]})
      for (bool shade : {false, true}) {
        RenderSettings s = settingsFor(m->domain().min, m->domain().max, tf, shade);
        s.width = 40;
        s.height = 32;
        if (shade) {  // ray ends on half of the image
          s.rayEnd.assign(std::size_t(s.width) * s.height, INFINITY);
          for (std::size_t i = 0; i < s.rayEnd.size(); i += 2) s.rayEnd[i] = 2.5f;
        }
        const ModelField field(*m);
        const ModelRenderSetup setup(field, s);
        const Copies model(gpu::modelArrays(setup.view()));
        ModelView view = gpu::relocateModel(setup.view(), model.addresses);
        std::optional<Copies> flags;
        if (const auto f = setup.emptySpaceFlags()) {
          flags.emplace(gpu::flagArrays(*f));
          view = gpu::relocateFlags(view, flags->addresses);
          ++skipping;
        }
        const Copies frame(gpu::frameArrays(setup.params()));
        const RayParams params = gpu::relocateFrame(setup.params(), frame.addresses);

        // Every pointer the kernels read was moved to a copy.
        EXPECT_TRUE(model.owns(view.spline.ctrl));
        for (const KnotAxisView& a : view.spline.axis) {
          EXPECT_TRUE(model.owns(a.knots));
          EXPECT_TRUE(model.owns(a.poly));
          EXPECT_TRUE(model.owns(a.inverseLength));
        }
        EXPECT_EQ(view.mask.nodes != nullptr, !m->mask().empty());
        if (view.mask.nodes) {
          EXPECT_TRUE(model.owns(view.mask.nodes));
        }
        EXPECT_EQ(view.boundary.nodes != nullptr, m->boundary() != nullptr);
        if (view.boundary.nodes) {
          EXPECT_TRUE(model.owns(view.boundary.nodes));
          EXPECT_TRUE(model.owns(view.boundary.triangles));
          ++bounded;
        }
        if (view.empty) {
          EXPECT_TRUE(flags->owns(view.empty));
          EXPECT_EQ(view.emptyPyramid, nullptr);  // the device's rays read the cells only
          EXPECT_EQ(view.emptyLevels, 0);
        }
        EXPECT_TRUE(frame.owns(params.tf.entries));
        if (params.rayEnd) {
          EXPECT_TRUE(frame.owns(params.rayEnd));
          ++withRayEnds;
        }

        const Image relocated = renderModelView(s, params, view);
        const Image cpu = renderVolume(field, s);
        EXPECT_EQ(relocated.rgba, cpu.rgba) << "shade " << shade;
        ++renders;
      }
  EXPECT_EQ(renders, 32);
  EXPECT_GT(skipping, 0);
  EXPECT_EQ(withRayEnds, 16);
  EXPECT_EQ(bounded, 4);
}

// The gradient-opacity and 2-D tables travel with the frame.
TEST(DeviceArrays, GradientAndCurvatureTablesTravelWithTheFrame) {
  const Model& m = *models()[0];
  for (int variant = 0; variant < 3; ++variant) {
    RenderSettings s = settingsFor(m.domain().min, m.domain().max, transferFunctions()[0], true);
    s.width = 40;
    s.height = 32;
    if (variant == 0) s.gradientOpacity = {{0.5, 0.0f}, {2.0, 1.0f}};
    if (variant == 1) s.transferFunction2D = stripedTransferFunction2D();
    if (variant == 2) s.curvatureTransferFunction = curvaturePreset("gaussian", 4.0);
    const ModelField field(m);
    const ModelRenderSetup setup(field, s);
    const Copies frame(gpu::frameArrays(setup.params()));
    const RayParams params = gpu::relocateFrame(setup.params(), frame.addresses);
    EXPECT_TRUE(variant != 0 || frame.owns(params.gradientTf.opacity));
    EXPECT_TRUE(variant != 1 || frame.owns(params.gradientTf.table));
    EXPECT_TRUE(variant != 2 || frame.owns(params.curvatureTf.table));
    const Image relocated = renderModelView(s, params, setup.view());
    EXPECT_EQ(relocated.rgba, renderVolume(field, s).rgba) << "variant " << variant;
  }
}

TEST(DeviceArrays, WrongNumberOfCopiesIsAnError) {
  const Model& m = mlModel(2);
  ModelView v;
  v.spline = m.spline().view();
  EXPECT_THROW(gpu::relocateModel(v, {}), Error);
  EXPECT_THROW(gpu::relocateFlags(v, {}), Error);
  EXPECT_THROW(gpu::relocateFlags(v, {nullptr, nullptr}), Error);
}

}  // namespace
}  // namespace mfadvr
