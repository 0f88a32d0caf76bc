#include "gpu/DeviceArrays.h"

#include "core/render/IsoBasis.h"
#include "core/util/Error.h"

namespace mfadvr::gpu {

namespace {

void expectCopies(const std::vector<HostArray>& arrays, const std::vector<const void*>& copies) {
  if (arrays.size() != copies.size())
    throw Error("device arrays: " + std::to_string(copies.size()) + " copies for " +
                std::to_string(arrays.size()) + " arrays");
}

}  // namespace

std::size_t totalBytes(const std::vector<HostArray>& arrays) {
  std::size_t sum = 0;
  for (const HostArray& a : arrays) sum += a.bytes;
  return sum;
}

std::vector<HostArray> modelArrays(const ModelView& v) {
  const SplineView& s = v.spline;
  std::vector<HostArray> out;
  out.push_back({s.ctrl,
                 std::size_t(s.axis[0].count) * s.axis[1].count * s.axis[2].count * sizeof(float),
                 "the control points"});
  for (const KnotAxisView& a : s.axis) {
    const std::size_t count = std::size_t(a.count), width = std::size_t(a.degree) + 1;
    out.push_back({a.knots, (count + width) * sizeof(double), "the knots"});
    out.push_back({a.poly, (count * width * width + kSplineRowPadding) * sizeof(float),
                   "the basis polynomials"});
    out.push_back({a.inverseLength, count * sizeof(double), "the knot spans"});
  }
  if (v.mask.nodes)
    out.push_back({v.mask.nodes, std::size_t(v.mask.dims[0] * v.mask.dims[1] * v.mask.dims[2]),
                   "the domain mask"});
  if (v.boundary.nodes) {
    out.push_back({v.boundary.nodes, std::size_t(v.boundary.nodeCount) * sizeof(BoundaryNode),
                   "the boundary's hierarchy"});
    out.push_back({v.boundary.triangles, std::size_t(v.boundary.triangleCount) * 9 * sizeof(double),
                   "the boundary triangles"});
  }
  return out;
}

ModelView relocateModel(const ModelView& view, const std::vector<const void*>& copies) {
  expectCopies(modelArrays(view), copies);
  ModelView v = view;
  std::size_t i = 0;
  v.spline.ctrl = static_cast<const float*>(copies[i++]);
  for (KnotAxisView& a : v.spline.axis) {
    a.knots = static_cast<const double*>(copies[i++]);
    a.poly = static_cast<const float*>(copies[i++]);
    a.inverseLength = static_cast<const double*>(copies[i++]);
  }
  if (v.mask.nodes) v.mask.nodes = static_cast<const std::uint8_t*>(copies[i++]);
  if (v.boundary.nodes) {
    v.boundary.nodes = static_cast<const BoundaryNode*>(copies[i++]);
    v.boundary.triangles = static_cast<const double*>(copies[i++]);
  }
  return v;
}

std::vector<HostArray> flagArrays(const EmptySpaceFlags& flags) {
  return {{flags.cells.data(), flags.cells.size(), "the empty-space flags"}};
}

ModelView relocateFlags(const ModelView& view, const std::vector<const void*>& copies) {
  if (copies.size() != 1) throw Error("device arrays: the flags need 1 copy");
  ModelView v = view;
  v.empty = static_cast<const std::uint8_t*>(copies[0]);
  v.emptyPyramid = nullptr;
  v.emptyLevels = 0;
  return v;
}

std::vector<HostArray> frameArrays(const RayParams& p) {
  std::vector<HostArray> out{
      {p.tf.entries, std::size_t(p.tf.count) * sizeof(TfEntry), "the transfer-function table"}};
  if (p.rayEnd)
    out.push_back(
        {p.rayEnd, std::size_t(p.camera.width) * p.camera.height * sizeof(float), "the ray ends"});
  if (p.isoCount > 0) {
    const IsoBasisTables& t = isoBasisTables();
    out.push_back({p.isoNodes, t.nodes.size() * sizeof(double), "the isosurface nodes"});
    out.push_back({p.isoBasis, t.basis.size() * sizeof(double), "the isosurface bases"});
  }
  const GradientTransferView& g = p.gradientTf;
  if (g.opacity)
    out.push_back({g.opacity, std::size_t(g.opacityCount) * sizeof(float), "the gradient opacity"});
  if (g.table)
    out.push_back(
        {g.table, std::size_t(g.width) * g.height * sizeof(TfEntry), "the 2-D transfer function"});
  const CurvatureTransferView& c = p.curvatureTf;
  if (c.table)
    out.push_back({c.table, std::size_t(c.width) * c.height * sizeof(CurvatureEntry),
                   "the curvature transfer function"});
  return out;
}

RayParams relocateFrame(const RayParams& params, const std::vector<const void*>& copies) {
  expectCopies(frameArrays(params), copies);
  RayParams p = params;
  p.tf.entries = static_cast<const TfEntry*>(copies[0]);
  std::size_t next = 1;
  if (p.rayEnd) p.rayEnd = static_cast<const float*>(copies[next++]);
  if (p.isoCount > 0) {
    p.isoNodes = static_cast<const double*>(copies[next++]);
    p.isoBasis = static_cast<const double*>(copies[next++]);
  }
  if (p.gradientTf.opacity) p.gradientTf.opacity = static_cast<const float*>(copies[next++]);
  if (p.gradientTf.table) p.gradientTf.table = static_cast<const TfEntry*>(copies[next++]);
  if (p.curvatureTf.table) p.curvatureTf.table = static_cast<const CurvatureEntry*>(copies[next++]);
  return p;
}

}  // namespace mfadvr::gpu
