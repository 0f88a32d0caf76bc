// Batches of samples (kernel/SampleBatch.h) change how much the processor overlaps, never what
// a ray computes: the renderer's batched MFA sampler, driven one sample at a time through the
// same evaluation, gives the same image bit for bit and the same counters (samples, skipped,
// terminated), with masks, empty-space skipping, shading, ray ends and every kind of transfer
// function. A GPU takes one sample at a time, and its tests compare these counters.
#include <gtest/gtest.h>

#include <cmath>

#include "core/FrameAgreement.h"
#include "core/field/ModelField.h"
#include "core/render/ModelKernelSwitch.h"
#include "core/render/ModelRenderSetup.h"
#include "core/render/RayCaster.h"
#include "gpu/GpuTestScenes.h"

namespace mfadvr {
namespace {

using namespace test;

// Any batch sampler as one with batches of one lane: the same stage / evaluate / gradient calls
// on lane 0.
template <class S>
class OneLane {
 public:
  static constexpr bool kSkipsEmptySpace = S::kSkipsEmptySpace;
  static constexpr int kBatch = 1;
  explicit OneLane(S s) : s_(std::move(s)) {}
  void beginRay(const RaySegment& ray) { s_.beginRay(ray); }
  bool inside(const double p[3]) { return s_.inside(p); }
  bool emptyAt(const double p[3], double& tLeave) { return s_.emptyAt(p, tLeave); }
  bool boundedAt(const double p[3], bool maximum, int bound, double& tLeave) {
    return s_.boundedAt(p, maximum, bound, tLeave);
  }
  const float* upperLevels() const { return s_.upperLevels(); }
  const float* lowerLevels() const { return s_.lowerLevels(); }
  void stage(int, const double p[3]) { s_.stage(0, p); }
  // The batched sampler writes all of its kBatch lanes (its lane kernel stores whole vectors).
  void evaluate(int n, float v[]) {
    float lanes[S::kBatch];
    s_.evaluate(n, lanes);
    for (int i = 0; i < n; ++i) v[i] = lanes[i];
  }
  void gradient(int, float g[3]) { s_.gradient(0, g); }
  void hessian(int, const double p[3], float h[6]) { s_.hessian(0, p, h); }

 private:
  S s_;
};

// The frame through one-lane batches, instantiated as renderModelView does.
Image renderOneLane(const RenderSettings& s, const ModelRenderSetup& setup, RenderStats* stats) {
  Image image(s.width, s.height);
  const ModelView& view = setup.view();
  requireReferenceDegree(view);
  modelKernelSwitch<kReferenceMaxDegree>(view, s.shade, [&]<int P, bool Masked, bool Shade, bool Skip>() {
    using Batched = SplineRaySampler<P, Skip, Shade>;
    castRays<Masked, Shade>(
        s, setup.params(), [&] { return OneLane<Batched>(Batched(view)); }, image, stats);
  });
  return image;
}

TEST(SampleBatch, BatchesRenderTheImageAndCountersOfOneSampleAtATime) {
  static_assert(SplineRaySampler<2, false, false>::kBatch == kSampleBatch);
  ASSERT_GT(kSampleBatch, 1);
  int renders = 0, batched = 0;
  std::int64_t skipped = 0, terminated = 0;
  // An opaque thin shell: rays terminate in it with empty cells right behind, which a batch
  // has already staged (and skipped) when the ray stops.
  std::vector<TransferFunction> tfs = transferFunctions();
  tfs.push_back(
      tfWith(TfSpace::Data, {{0.0, 0.0f}, {0.2, 0.0f}, {0.21, 1.0f}, {0.3, 1.0f}, {0.31, 0.0f}}));
  for (const Model* m : {&mlModel(2), &mlModel(3), &maskedModel(), &mixedDegreeModel()})
    for (const TransferFunction& tf : tfs)
      for (bool shade : {false, true}) {
        RenderSettings s = settingsFor(m->domain().min, m->domain().max, tf, shade);
        if (&tf == &tfs.back()) s.sampleDistance = 0.04;  // about half a cell
        s.width = 48;
        s.height = 40;
        if (shade) {  // ray ends on every third pixel
          s.rayEnd.assign(std::size_t(s.width) * s.height, INFINITY);
          for (std::size_t i = 0; i < s.rayEnd.size(); i += 3) s.rayEnd[i] = 2.5f;
        }
        const ModelField field(*m);
        const ModelRenderSetup setup(field, s);
        RenderStats batchStats, laneStats;
        const Image batch = renderModelView(s, setup.params(), setup.view(), &batchStats);
        const Image oneLane = renderOneLane(s, setup, &laneStats);
        expectSameFrame(batch, batchStats, oneLane, laneStats, renders);
        skipped += batchStats.skipped;
        terminated += batchStats.terminated;
        if (m->spline().degrees()[0] == m->spline().degrees()[1] &&
            m->spline().degrees()[1] == m->spline().degrees()[2])
          ++batched;
        ++renders;
      }
  EXPECT_EQ(renders, 56);
  EXPECT_EQ(batched, 42);  // the mixed-degree model takes one sample at a time anyway
  // The scenes exercise what the counters must survive: skipping and early termination.
  EXPECT_GT(skipped, 0);
  EXPECT_GT(terminated, 0);
}

}  // namespace
}  // namespace mfadvr
