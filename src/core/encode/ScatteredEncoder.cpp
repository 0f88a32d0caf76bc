#include "core/encode/ScatteredEncoder.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>

#include "core/encode/KnotPlacement.h"
#include "core/model/ModelFile.h"
#include "core/spline/BasisFunctions.h"
#include "core/spline/DerivativePenalty.h"
#include "core/util/Error.h"
#include "core/util/MemoryBudget.h"
#include "core/util/UtcTime.h"

namespace mfadvr {
namespace {
class NormalOperator;
}  // namespace
}  // namespace mfadvr

// Eigen's matrix-free interface reads an operator's traits before the class is complete.
namespace Eigen::internal {
template <>
struct traits<mfadvr::NormalOperator> : public traits<Eigen::SparseMatrix<double>> {};
}  // namespace Eigen::internal

namespace mfadvr {

namespace {

using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

// y = A x over the rows of a row-major sparse matrix, in parallel; each row is one dot product,
// so the result does not depend on the thread count.
void multiply(const RowSparse& A, const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  y.resize(A.rows());
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const double* values = A.valuePtr();
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, A.rows(), 2048), [&](const auto& r) {
    for (Eigen::Index i = r.begin(); i < r.end(); ++i) {
      double sum = 0.0;
      for (int e = outer[i]; e < outer[i + 1]; ++e) sum += values[e] * x[inner[e]];
      y[i] = sum;
    }
  });
}

// The normal matrix A = (1/P) N^T N + lambda D^T D of the regularized fit, as an operator.
struct NormalSystem {
  RowSparse basis, basisT;  // N (P x C) and its transpose
  RowSparse penalty;        // D^T D (D: weighted second differences), multiplied out: it has
                            // at most 13 entries per row, fewer than D and D^T together
  double dataScale = 1.0, lambda = 0.0;
  Eigen::VectorXd inverseDiagonal;
  mutable Eigen::VectorXd pointTmp, ctrlTmp;

  Eigen::Index size() const { return basis.cols(); }
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
    multiply(basis, x, pointTmp);
    multiply(basisT, pointTmp, y);
    y *= dataScale;
    if (lambda > 0.0) {
      multiply(penalty, x, ctrlTmp);
      y += lambda * ctrlTmp;
    }
  }
};

// Eigen's matrix-free interface: the operator only needs to provide its size and A * x.
class NormalOperator : public Eigen::EigenBase<NormalOperator> {
 public:
  using Scalar = double;
  using RealScalar = double;
  using StorageIndex = int;
  enum {
    ColsAtCompileTime = Eigen::Dynamic,
    MaxColsAtCompileTime = Eigen::Dynamic,
    IsRowMajor = false
  };
  explicit NormalOperator(const NormalSystem& s) : system_(&s) {}
  Eigen::Index rows() const { return system_->size(); }
  Eigen::Index cols() const { return system_->size(); }
  template <typename Rhs>
  Eigen::Product<NormalOperator, Rhs, Eigen::AliasFreeProduct> operator*(
      const Eigen::MatrixBase<Rhs>& x) const {
    return Eigen::Product<NormalOperator, Rhs, Eigen::AliasFreeProduct>(*this, x.derived());
  }
  const NormalSystem& system() const { return *system_; }

 private:
  const NormalSystem* system_;
};

// Jacobi preconditioning with the diagonal the system computed during assembly.
class JacobiPreconditioner {
 public:
  JacobiPreconditioner() = default;
  template <class M>
  explicit JacobiPreconditioner(const M& m) {
    compute(m);
  }
  template <class M>
  JacobiPreconditioner& analyzePattern(const M&) {
    return *this;
  }
  template <class M>
  JacobiPreconditioner& factorize(const M& m) {
    inverse_ = &m.system().inverseDiagonal;
    return *this;
  }
  template <class M>
  JacobiPreconditioner& compute(const M& m) {
    return factorize(m);
  }
  template <class Rhs>
  Eigen::VectorXd solve(const Rhs& b) const {
    return inverse_->cwiseProduct(b);
  }
  Eigen::ComputationInfo info() { return Eigen::Success; }

 private:
  const Eigen::VectorXd* inverse_ = nullptr;
};

}  // namespace
}  // namespace mfadvr

namespace Eigen::internal {
template <typename Rhs>
struct generic_product_impl<mfadvr::NormalOperator, Rhs, SparseShape, DenseShape, GemvProduct>
    : generic_product_impl_base<mfadvr::NormalOperator, Rhs,
                                generic_product_impl<mfadvr::NormalOperator, Rhs>> {
  using Scalar = typename Product<mfadvr::NormalOperator, Rhs>::Scalar;
  template <typename Dest>
  static void scaleAndAddTo(Dest& dst, const mfadvr::NormalOperator& lhs, const Rhs& rhs,
                            const Scalar& alpha) {
    Eigen::VectorXd y;
    lhs.system().apply(rhs, y);
    dst += alpha * y;
  }
};
}  // namespace Eigen::internal

namespace mfadvr {
namespace {

const char* axisName(int a) {
  return a == 0 ? "x" : (a == 1 ? "y" : "z");
}

using Clock = std::chrono::steady_clock;

// Greville abscissae g_i = (u_{i+1} + ... + u_{i+p}) / p: where control point i "sits".
std::vector<double> grevilleAbscissae(const KnotVector& kv) {
  const int p = kv.degree(), n = kv.controlCount();
  std::vector<double> g(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    double sum = 0.0;
    for (int j = 1; j <= p; ++j) sum += kv.knots()[static_cast<size_t>(i + j)];
    g[static_cast<size_t>(i)] = sum / p;
  }
  return g;
}

// Control points of a spline whose knots are `knots`, taken from `coarse` at the Greville
// abscissae (the averages of p consecutive interior knots): a good initial guess, exact for
// linear functions.
Eigen::VectorXd sampleAtGreville(const Model& coarse, const std::array<KnotVector, 3>& knots) {
  std::array<std::vector<double>, 3> g;
  for (int a = 0; a < 3; ++a) g[a] = grevilleAbscissae(knots[a]);
  const auto n0 = static_cast<Eigen::Index>(g[0].size()),
             n1 = static_cast<Eigen::Index>(g[1].size()),
             n2 = static_cast<Eigen::Index>(g[2].size());
  Eigen::VectorXd out(n0 * n1 * n2);
  tbb::parallel_for(Eigen::Index(0), n2, [&](Eigen::Index k) {
    for (Eigen::Index j = 0; j < n1; ++j)
      for (Eigen::Index i = 0; i < n0; ++i)
        out[i + n0 * (j + n1 * k)] =
            coarse.spline().value(Vec3d(g[0][static_cast<size_t>(i)], g[1][static_cast<size_t>(j)],
                                        g[2][static_cast<size_t>(k)]));
  });
  return out;
}

// N: one row per point with the (p+1)^3 tensor basis weights, columns sorted (z, y, x order).
RowSparse assembleBasis(const std::vector<Vec3d>& params, const std::array<KnotVector, 3>& knots) {
  const int p0 = knots[0].degree(), p1 = knots[1].degree(), p2 = knots[2].degree();
  const int w0 = p0 + 1, w1 = p1 + 1, w2 = p2 + 1, perRow = w0 * w1 * w2;
  const auto rows = static_cast<std::int64_t>(params.size());
  const std::int64_t n0 = knots[0].controlCount(), n1 = knots[1].controlCount(),
                     n2 = knots[2].controlCount();
  if (rows * perRow > std::numeric_limits<int>::max() ||
      n0 * n1 * n2 > std::numeric_limits<int>::max())
    throw Error("too many points or control points for one scattered fit (" + std::to_string(rows) +
                " points x " + std::to_string(perRow) +
                " basis weights each); use fewer points or a lower degree");
  RowSparse N(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(n0 * n1 * n2));
  N.resizeNonZeros(static_cast<Eigen::Index>(rows * perRow));
  int* outer = N.outerIndexPtr();
  int* inner = N.innerIndexPtr();
  double* values = N.valuePtr();
  for (std::int64_t r = 0; r <= rows; ++r) outer[r] = static_cast<int>(r * perRow);
  tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, rows, 1024), [&](const auto& range) {
    double b0[kMaxDegree + 1], b1[kMaxDegree + 1], b2[kMaxDegree + 1];
    for (std::int64_t r = range.begin(); r < range.end(); ++r) {
      const Vec3d& u = params[static_cast<size_t>(r)];
      const int s0 = knots[0].findSpan(u[0]), s1 = knots[1].findSpan(u[1]),
                s2 = knots[2].findSpan(u[2]);
      basisFunctions(knots[0], p0, s0, std::clamp(u[0], 0.0, 1.0), b0);
      basisFunctions(knots[1], p1, s1, std::clamp(u[1], 0.0, 1.0), b1);
      basisFunctions(knots[2], p2, s2, std::clamp(u[2], 0.0, 1.0), b2);
      std::int64_t e = r * perRow;
      for (int k = 0; k < w2; ++k)
        for (int j = 0; j < w1; ++j) {
          const std::int64_t rowBase = (s0 - p0) + n0 * ((s1 - p1 + j) + n1 * (s2 - p2 + k));
          const double bjk = b1[j] * b2[k];
          for (int i = 0; i < w0; ++i, ++e) {
            inner[e] = static_cast<int>(rowBase + i);
            values[e] = b0[i] * bjk;
          }
        }
    }
  });
  return N;
}

// D: the second-derivative penalty rows of each axis (core/spline/DerivativePenalty.h) times
// the square roots of the basis integrals (u_{j+p+1} - u_j) / (p + 1) of the other two axes, so
// that |D c|^2 approximates h^4 times the integral of the squared second derivatives (mass
// lumping). Multilinear functions have zero penalty: they are not biased, and spans without
// points get the smoothest continuation of their surroundings.
RowSparse assembleSecondDifferences(const std::array<KnotVector, 3>& knots) {
  const std::int64_t n[3] = {knots[0].controlCount(), knots[1].controlCount(),
                             knots[2].controlCount()};
  std::array<std::vector<double>, 3> mass;
  for (int a = 0; a < 3; ++a) {
    const int p = knots[a].degree();
    const auto& u = knots[a].knots();
    mass[a].resize(static_cast<size_t>(n[a]));
    for (std::int64_t j = 0; j < n[a]; ++j)
      mass[a][static_cast<size_t>(j)] =
          (u[static_cast<size_t>(j + p + 1)] - u[static_cast<size_t>(j)]) / (p + 1);
  }
  const std::int64_t stride[3] = {1, n[0], n[0] * n[1]};
  std::vector<Eigen::Triplet<double, int>> t;
  std::int64_t rows = 0;
  for (int a = 0; a < 3; ++a) {
    const DerivativePenalty d = derivativePenalty(knots[a], kScatteredPenaltyOrder);
    const int w = d.order + 1;
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    for (int r = 0; r < d.rows(); ++r) {
      const std::int64_t i = d.first[static_cast<size_t>(r)];
      const double* wr = &d.weights[static_cast<size_t>(r * w)];
      for (std::int64_t k = 0; k < n[c]; ++k)
        for (std::int64_t j = 0; j < n[b]; ++j) {
          const double scale =
              std::sqrt(mass[b][static_cast<size_t>(j)] * mass[c][static_cast<size_t>(k)]);
          const std::int64_t base = i * stride[a] + j * stride[b] + k * stride[c];
          for (int e = 0; e < w; ++e)
            t.emplace_back(static_cast<int>(rows), static_cast<int>(base + e * stride[a]),
                           scale * wr[e]);
          ++rows;
        }
    }
  }
  RowSparse D(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(n[0] * n[1] * n[2]));
  D.setFromTriplets(t.begin(), t.end());
  return D;
}

Eigen::VectorXd columnSquaredNorms(const RowSparse& AT) {
  // Rows of A^T are the columns of A.
  Eigen::VectorXd out(AT.rows());
  for (Eigen::Index i = 0; i < AT.rows(); ++i) out[i] = AT.row(i).squaredNorm();
  return out;
}

void validateOptions(const ScatteredFitOptions& o) {
  if (!(o.smoothing >= 0.0) || !std::isfinite(o.smoothing))
    throw Error("smoothing must be a finite number >= 0");
  if (!(o.tolerance > 0.0 && o.tolerance < 1.0)) throw Error("solver tolerance must be in (0, 1)");
  if (o.maxIterations < 1) throw Error("solver iterations must be at least 1");
}

}  // namespace

std::array<std::vector<double>, 3> sortedAxisParameters(const ScatteredData& data) {
  const DomainBox box{data.boxMin(), data.boxMax()};
  std::array<std::vector<double>, 3> u;
  for (int a = 0; a < 3; ++a) u[a].resize(data.points.size());
  tbb::parallel_for(std::size_t(0), data.points.size(), [&](std::size_t i) {
    const Vec3d t = box.toParameter(data.points[i]);
    for (int a = 0; a < 3; ++a) u[a][i] = t[a];
  });
  tbb::parallel_for(0, 3, [&](int a) { std::sort(u[a].begin(), u[a].end()); });
  return u;
}

Index3 defaultScatteredControlCounts(const ScatteredData& data, const Degree3& degree) {
  const Vec3d extent = data.boxMax() - data.boxMin();
  double volume = 0.0;
  const auto points = static_cast<std::int64_t>(data.points.size());
  for (const Tetrahedron& t : data.tets) {
    if (std::any_of(t.begin(), t.end(), [&](std::int64_t i) { return i < 0 || i >= points; }))
      continue;  // ScatteredData::validate names it
    volume += std::abs(data.volume6(t)) / 6.0;
  }
  const double box = extent.prod();
  if (!(volume > 0.0) || !(volume <= box)) volume = box;  // clouds; cells beyond the box
  const double spacing = std::cbrt(volume / static_cast<double>(data.pointCount()));
  constexpr double kMaxTotal = 64.0 * 64.0 * 64.0;
  constexpr std::int64_t kMaxPerAxis = 256;
  double n[3];
  for (int a = 0; a < 3; ++a) n[a] = extent[a] / spacing + 1.0;
  const double total = n[0] * n[1] * n[2];
  const double shrink = total > kMaxTotal ? std::cbrt(kMaxTotal / total) : 1.0;
  Index3 out{};
  for (int a = 0; a < 3; ++a) {
    const auto c = static_cast<std::int64_t>(std::floor(n[a] * shrink + 0.5));
    out[a] = std::clamp<std::int64_t>(c, degree[a] + 1,
                                      std::max<std::int64_t>(kMaxPerAxis, degree[a] + 1));
  }
  return out;
}

Index3 resolveScatteredControlCounts(const ScatteredData& data,
                                     const ScatteredFitOptions& options) {
  validateOptions(options);
  for (int a = 0; a < 3; ++a)
    if (options.degree[a] < 1 || options.degree[a] > kMaxDegree) {
      std::ostringstream m;
      m << "degree " << options.degree[a] << " on axis " << axisName(a) << " is outside 1.."
        << kMaxDegree;
      throw Error(m.str());
    }
  const Index3 defaults = defaultScatteredControlCounts(data, options.degree);
  Index3 n{};
  for (int a = 0; a < 3; ++a) {
    const int p = options.degree[a];
    std::ostringstream m;
    n[a] = options.controlCounts[a] == 0 ? defaults[a] : options.controlCounts[a];
    if (n[a] < p + 1) {
      m << n[a] << " control points on axis " << axisName(a) << " are too few for degree " << p
        << "; use at least " << p + 1;
      throw Error(m.str());
    }
    if (n[a] > 4096) {
      m << n[a] << " control points on axis " << axisName(a) << " are more than 4096";
      throw Error(m.str());
    }
  }
  return n;
}

Model fitScatteredWithKnots(const ScatteredData& data, std::array<KnotVector, 3> knots,
                            const ScatteredFitOptions& options, const Model* initial,
                            FitReport* report, std::array<std::vector<double>, 3>* spanErrors) {
  const auto start = Clock::now();
  validateOptions(options);
  data.validate();
  const DomainBox box{data.boxMin(), data.boxMax()};
  std::vector<Vec3d> params(data.points.size());
  for (size_t i = 0; i < params.size(); ++i) params[i] = box.toParameter(data.points[i]);
  auto progress = [&](double f, const std::string& stage) {
    if (options.progress) options.progress(f, stage);
  };

  NormalSystem sys;
  sys.basis = assembleBasis(params, knots);
  sys.basisT = sys.basis.transpose();
  const RowSparse diff = assembleSecondDifferences(knots);
  sys.penalty = RowSparse(diff.transpose()) * diff;
  sys.dataScale = 1.0 / static_cast<double>(params.size());
  sys.lambda = penaltyWeight(options.smoothing, kScatteredPenaltyOrder);
  Eigen::VectorXd diagonal = sys.dataScale * columnSquaredNorms(sys.basisT);
  if (sys.lambda > 0.0) diagonal += sys.lambda * sys.penalty.diagonal();
  sys.inverseDiagonal = diagonal.unaryExpr([](double d) { return d > 0.0 ? 1.0 / d : 0.0; });
  if (sys.lambda == 0.0 && (diagonal.array() <= 0.0).any())
    throw Error(
        "some control points touch no input point; use a smoothing weight above 0 "
        "(--smooth) or fewer control points");

  const Eigen::VectorXd values = Eigen::Map<const Eigen::VectorXd>(
      data.values.data(), static_cast<Eigen::Index>(data.values.size()));
  Eigen::VectorXd rhs;
  multiply(sys.basisT, values, rhs);
  rhs *= sys.dataScale;

  Eigen::VectorXd x;
  if (initial)
    x = sampleAtGreville(*initial, knots);
  else
    x = Eigen::VectorXd::Constant(sys.size(), values.mean());

  NormalOperator op(sys);
  Eigen::ConjugateGradient<NormalOperator, Eigen::Lower | Eigen::Upper, JacobiPreconditioner> cg;
  cg.compute(op);
  cg.setTolerance(options.tolerance);
  // Chunks of iterations so that long solves report progress; each chunk restarts from the
  // exact residual of the current solution.
  constexpr int kChunk = 250;
  int iterations = 0;
  double residual = 1.0;
  const double rhsNorm = rhs.norm();
  if (rhsNorm == 0.0) {
    x.setZero();
    residual = 0.0;
  }
  while (rhsNorm > 0.0 && iterations < options.maxIterations) {
    cg.setMaxIterations(std::min(kChunk, options.maxIterations - iterations));
    x = cg.solveWithGuess(rhs, x);
    iterations += static_cast<int>(cg.iterations());
    residual = cg.error();
    char stage[96];
    std::snprintf(stage, sizeof stage, "solve (%d iterations, residual %.1e)", iterations,
                  residual);
    progress(std::min(0.9, 0.9 * iterations / options.maxIterations), stage);
    if (cg.info() == Eigen::Success || cg.iterations() == 0) break;
  }

  std::vector<float> ctrl(static_cast<size_t>(x.size()));
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    ctrl[static_cast<size_t>(i)] = static_cast<float>(x[i]);
    if (!std::isfinite(ctrl[static_cast<size_t>(i)]))
      throw Error("the scattered fit diverged (non-finite control point); try a larger --smooth");
  }

  // Errors of the stored (float32) model at every input point.
  progress(0.92, "error");
  const TensorBSpline spline(knots, std::move(ctrl));
  std::vector<double> errors(params.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, params.size(), 4096), [&](const auto& r) {
    for (size_t i = r.begin(); i < r.end(); ++i)
      errors[i] = std::abs(static_cast<double>(spline.value(params[i])) - data.values[i]);
  });
  double maxErr = 0.0, sumSq = 0.0;
  double vmin = data.values[0], vmax = vmin;
  if (spanErrors)
    for (int a = 0; a < 3; ++a)
      (*spanErrors)[a].assign(static_cast<size_t>(knots[a].controlCount() - knots[a].degree()),
                              0.0);
  for (size_t i = 0; i < params.size(); ++i) {
    maxErr = std::max(maxErr, errors[i]);
    sumSq += errors[i] * errors[i];
    vmin = std::min(vmin, data.values[i]);
    vmax = std::max(vmax, data.values[i]);
    if (spanErrors)
      for (int a = 0; a < 3; ++a) {
        const int s = knots[a].findSpan(params[i][a]) - knots[a].degree();
        double& worst = (*spanErrors)[a][static_cast<size_t>(s)];
        worst = std::max(worst, errors[i]);
      }
  }
  const double rms = std::sqrt(sumSq / static_cast<double>(params.size()));
  progress(1.0, "done");

  Provenance prov;
  prov.source = data.source;
  prov.field = data.fieldName;
  prov.sampleType = data.sampleType;
  prov.inputBytes = data.inputBytes;
  prov.inputPoints = data.pointCount();
  prov.fieldAssociation = data.fieldAssociation;
  prov.encoder = "scattered-least-squares";
  prov.smoothing = options.smoothing;
  prov.created = utcNow();
  prov.toolVersion = MFADVR_VERSION;
  prov.maxError = maxErr;
  prov.rmsError = rms;
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  prov.fitSeconds = seconds;
  Model model(spline, box, vmin, vmax, std::move(prov));
  if (report) {
    *report = fitReportOf(model);
    report->inputKind = data.kind;
    report->smoothing = options.smoothing;
    report->solverIterations = iterations;
    report->solverResidual = residual;
  }
  return model;
}

std::int64_t scatteredFitPeakBytes(std::int64_t points, const Index3& counts,
                                   const Degree3& degree) {
  const std::int64_t perPoint = std::int64_t(degree[0] + 1) * (degree[1] + 1) * (degree[2] + 1);
  const std::int64_t c = counts[0] * counts[1] * counts[2];
  const std::int64_t params = 24 * points;
  const std::int64_t basis = 2 * 12 * perPoint * points + 8 * points;  // N and N^T
  const std::int64_t penalty = 12 * 9 * c + 12 * 13 * c;  // second differences and D^T D
  const std::int64_t vectors = 8 * (8 * c + 3 * points);  // right side, CG, diagonal, values
  return params + basis + penalty + vectors;
}

Model fitScattered(const ScatteredData& data, const ScatteredFitOptions& options,
                   FitReport* report) {
  const auto start = Clock::now();
  data.validate();
  const Index3 n = resolveScatteredControlCounts(data, options);
  requireMemory(
      scatteredFitPeakBytes(static_cast<std::int64_t>(data.points.size()), n, options.degree),
      "fitting " + std::to_string(data.points.size()) + " points with " + std::to_string(n[0]) +
          "x" + std::to_string(n[1]) + "x" + std::to_string(n[2]) +
          " control points (fewer control points, --ctrl, need less)");
  // Every level's knots follow the points' density along each axis (knotsFollowingDensity).
  const std::array<std::vector<double>, 3> sorted = sortedAxisParameters(data);
  // Levels: halve the number of spans per axis until every axis has at most 4 spans.
  std::vector<Index3> levels{n};
  for (;;) {
    const Index3& f = levels.back();
    Index3 c{};
    bool coarser = false;
    for (int a = 0; a < 3; ++a) {
      const std::int64_t spans = f[a] - options.degree[a];
      c[a] = spans > 4 ? (spans + 1) / 2 + options.degree[a] : f[a];
      coarser = coarser || c[a] < f[a];
    }
    if (!coarser) break;
    levels.push_back(c);
  }
  std::reverse(levels.begin(), levels.end());

  std::optional<Model> previous;
  int iterations = 0;
  for (size_t l = 0; l < levels.size(); ++l) {
    std::array<KnotVector, 3> knots;
    for (int a = 0; a < 3; ++a)
      knots[a] = knotsFollowingDensity(options.degree[a], static_cast<int>(levels[l][a]), sorted[a],
                                       options.knotDensity);
    ScatteredFitOptions levelOptions = options;
    const std::string name = "level " + std::to_string(l + 1) + "/" +
                             std::to_string(levels.size()) + " (" + std::to_string(levels[l][0]) +
                             "x" + std::to_string(levels[l][1]) + "x" +
                             std::to_string(levels[l][2]) + ")";
    // Work grows about 8x per level: give the finest most of the progress bar.
    const double lo = levels.size() == 1 ? 0.0 : 0.3 * l / (levels.size() - 1);
    const double hi = l + 1 == levels.size() ? 1.0 : 0.3 * (l + 1) / (levels.size() - 1);
    levelOptions.progress = [&](double f, const std::string& stage) {
      if (options.progress) options.progress(lo + (hi - lo) * f, name + ": " + stage);
    };
    FitReport levelReport;
    Model m = fitScatteredWithKnots(data, std::move(knots), levelOptions,
                                    previous ? &*previous : nullptr, &levelReport);
    iterations += levelReport.solverIterations;
    if (l + 1 == levels.size() && report) {
      *report = levelReport;
      report->solverIterations = iterations;
      report->seconds = std::chrono::duration<double>(Clock::now() - start).count();
      m.provenance().fitSeconds = report->seconds;
      report->modelBytes = modelFileSize(m);  // the header holds the time
    }
    previous = std::move(m);
  }
  return std::move(*previous);
}

}  // namespace mfadvr
