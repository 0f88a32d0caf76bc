#include "core/spline/TensorBSpline.h"

#include <algorithm>
#include <string>

#include "core/spline/BasisFunctions.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

// NaN maps to 0 so that a bad coordinate yields a finite answer instead of undefined behaviour.
inline double clamp01(double u) {
  return !(u > 0.0) ? 0.0 : (u > 1.0 ? 1.0 : u);
}

// Value (and, with kGradient, the three parametric partials) by separable contraction: the
// x sums of each (j,k) row are shared by the value and the y/z partials, so the gradient costs
// about twice the value, not four times.
template <bool kGradient>
MFADVR_INLINE void evaluateKernel(const TensorBSpline& s, int p0, int p1, int p2, const Vec3d& u,
                                  float* out) {
  const KnotVector& k0 = s.knots(0);
  const KnotVector& k1 = s.knots(1);
  const KnotVector& k2 = s.knots(2);
  const double u0 = clamp01(u[0]), u1 = clamp01(u[1]), u2 = clamp01(u[2]);
  const int s0 = k0.findSpan(u0), s1 = k1.findSpan(u1), s2 = k2.findSpan(u2);

  constexpr int W = kMaxDegree + 1;
  double d0[2 * W], d1[2 * W], d2[2 * W];
  if constexpr (kGradient) {
    basisDerivatives(k0, p0, s0, u0, 1, d0);
    basisDerivatives(k1, p1, s1, u1, 1, d1);
    basisDerivatives(k2, p2, s2, u2, 1, d2);
  } else {
    basisFunctions(k0, p0, s0, u0, d0);
    basisFunctions(k1, p1, s1, u1, d1);
    basisFunctions(k2, p2, s2, u2, d2);
  }
  float N0[W], N1[W], N2[W], D0[W], D1[W], D2[W];
  for (int i = 0; i <= p0; ++i) {
    N0[i] = static_cast<float>(d0[i]);
    if constexpr (kGradient) D0[i] = static_cast<float>(d0[p0 + 1 + i]);
  }
  for (int j = 0; j <= p1; ++j) {
    N1[j] = static_cast<float>(d1[j]);
    if constexpr (kGradient) D1[j] = static_cast<float>(d1[p1 + 1 + j]);
  }
  for (int k = 0; k <= p2; ++k) {
    N2[k] = static_cast<float>(d2[k]);
    if constexpr (kGradient) D2[k] = static_cast<float>(d2[p2 + 1 + k]);
  }

  const std::int64_t n0 = k0.controlCount(), n1 = k1.controlCount();
  const float* base = s.controlPoints().data() + (s0 - p0) + n0 * ((s1 - p1) + n1 * (s2 - p2));
  float v = 0.0f, gx = 0.0f, gy = 0.0f, gz = 0.0f;
  for (int k = 0; k <= p2; ++k) {
    float vk = 0.0f, xk = 0.0f, yk = 0.0f;
    for (int j = 0; j <= p1; ++j) {
      const float* row = base + n0 * (j + n1 * k);
      float a = 0.0f, b = 0.0f;
      for (int i = 0; i <= p0; ++i) {
        a += N0[i] * row[i];
        if constexpr (kGradient) b += D0[i] * row[i];
      }
      vk += N1[j] * a;
      if constexpr (kGradient) {
        xk += N1[j] * b;
        yk += D1[j] * a;
      }
    }
    v += N2[k] * vk;
    if constexpr (kGradient) {
      gx += N2[k] * xk;
      gy += N2[k] * yk;
      gz += D2[k] * vk;
    }
  }
  out[0] = v;
  if constexpr (kGradient) {
    out[1] = gx;
    out[2] = gy;
    out[3] = gz;
  }
}

template <int P>
float valueFixed(const TensorBSpline& s, const Vec3d& u) {
  float out[1];
  evaluateKernel<false>(s, P, P, P, u, out);
  return out[0];
}

template <int P>
ValueGradient gradientFixed(const TensorBSpline& s, const Vec3d& u) {
  float out[4];
  evaluateKernel<true>(s, P, P, P, u, out);
  return {out[0], Vec3f(out[1], out[2], out[3])};
}

float valueGeneric(const TensorBSpline& s, const Vec3d& u) {
  const Degree3 p = s.degrees();
  float out[1];
  evaluateKernel<false>(s, p[0], p[1], p[2], u, out);
  return out[0];
}

ValueGradient gradientGeneric(const TensorBSpline& s, const Vec3d& u) {
  const Degree3 p = s.degrees();
  float out[4];
  evaluateKernel<true>(s, p[0], p[1], p[2], u, out);
  return {out[0], Vec3f(out[1], out[2], out[3])};
}

template <int... P>
constexpr std::array<TensorBSpline::ValueFn, sizeof...(P)> valueTable(
    std::integer_sequence<int, P...>) {
  return {&valueFixed<P + 1>...};
}
template <int... P>
constexpr std::array<TensorBSpline::GradientFn, sizeof...(P)> gradientTable(
    std::integer_sequence<int, P...>) {
  return {&gradientFixed<P + 1>...};
}

}  // namespace

TensorBSpline::TensorBSpline(std::array<KnotVector, 3> knots, std::vector<float> ctrl)
    : knots_(std::move(knots)), ctrl_(std::move(ctrl)) {
  const Index3 n = counts();
  for (int a = 0; a < 3; ++a) {
    if (knots_[a].degree() < 1) throw Error("spline axis " + std::to_string(a) + " has no knots");
  }
  if (static_cast<std::int64_t>(ctrl_.size()) != n[0] * n[1] * n[2])
    throw Error("control point array has " + std::to_string(ctrl_.size()) + " entries, expected " +
                std::to_string(n[0] * n[1] * n[2]));
  const Degree3 p = degrees();
  if (p[0] == p[1] && p[1] == p[2]) {
    static constexpr auto values = valueTable(std::make_integer_sequence<int, kMaxDegree>{});
    static constexpr auto gradients = gradientTable(std::make_integer_sequence<int, kMaxDegree>{});
    valueFn_ = values[p[0] - 1];
    gradientFn_ = gradients[p[0] - 1];
  } else {
    valueFn_ = &valueGeneric;
    gradientFn_ = &gradientGeneric;
  }
}

Degree3 TensorBSpline::degrees() const {
  return {knots_[0].degree(), knots_[1].degree(), knots_[2].degree()};
}

Index3 TensorBSpline::counts() const {
  return {knots_[0].controlCount(), knots_[1].controlCount(), knots_[2].controlCount()};
}

ValueGradientHessian TensorBSpline::valueGradientHessian(const Vec3d& u) const {
  const Degree3 p = degrees();
  constexpr int W = kMaxDegree + 1;
  double d[3][3 * W];
  int span[3];
  for (int a = 0; a < 3; ++a) {
    const double ua = clamp01(u[a]);
    span[a] = knots_[a].findSpan(ua);
    basisDerivatives(knots_[a], p[a], span[a], ua, 2, d[a]);
  }
  const std::int64_t n0 = knots_[0].controlCount(), n1 = knots_[1].controlCount();
  // acc[a][b][c]: sum of P * N0^(a) N1^(b) N2^(c) for the derivative orders we need.
  double acc[3][3][3] = {};
  for (int k = 0; k <= p[2]; ++k) {
    for (int j = 0; j <= p[1]; ++j) {
      const float* row =
          ctrl_.data() + (span[0] - p[0]) + n0 * ((span[1] - p[1] + j) + n1 * (span[2] - p[2] + k));
      double x[3] = {0, 0, 0};
      for (int i = 0; i <= p[0]; ++i)
        for (int o = 0; o < 3; ++o) x[o] += d[0][o * (p[0] + 1) + i] * row[i];
      for (int a = 0; a < 3; ++a)
        for (int b = 0; a + b < 3; ++b)
          for (int c = 0; a + b + c < 3; ++c)
            acc[a][b][c] += x[a] * d[1][b * (p[1] + 1) + j] * d[2][c * (p[2] + 1) + k];
    }
  }
  ValueGradientHessian r;
  r.value = static_cast<float>(acc[0][0][0]);
  r.gradient = Vec3f(static_cast<float>(acc[1][0][0]), static_cast<float>(acc[0][1][0]),
                     static_cast<float>(acc[0][0][1]));
  r.hessian = {static_cast<float>(acc[2][0][0]), static_cast<float>(acc[1][1][0]),
               static_cast<float>(acc[1][0][1]), static_cast<float>(acc[0][2][0]),
               static_cast<float>(acc[0][1][1]), static_cast<float>(acc[0][0][2])};
  return r;
}

TensorBSpline TensorBSpline::withInsertedKnot(int axis, double u) const {
  if (axis < 0 || axis > 2) throw Error("axis must be 0, 1 or 2");
  const KnotVector& kv = knots_[axis];
  const std::vector<double>& U = kv.knots();
  const int p = kv.degree();
  const int k = kv.findSpan(u);
  const int mult = static_cast<int>(std::count(U.begin(), U.end(), u));
  if (mult >= p) throw Error("knot multiplicity would exceed the degree");

  const Index3 n = counts();
  Index3 m = n;
  m[axis] += 1;
  // alpha[i] for the control points that blend; indices k-p+1 .. k-mult.
  std::vector<double> alpha(static_cast<size_t>(n[axis] + 1), 0.0);
  for (int i = k - p + 1; i <= k - mult; ++i) alpha[i] = (u - U[i]) / (U[i + p] - U[i]);

  const std::int64_t strideIn[3] = {1, n[0], n[0] * n[1]};
  const std::int64_t strideOut[3] = {1, m[0], m[0] * m[1]};
  std::vector<float> out(static_cast<size_t>(m[0] * m[1] * m[2]));
  // Iterate over all lines parallel to `axis`.
  const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  for (std::int64_t y = 0; y < n[a2]; ++y) {
    for (std::int64_t x = 0; x < n[a1]; ++x) {
      const float* in = ctrl_.data() + x * strideIn[a1] + y * strideIn[a2];
      float* o = out.data() + x * strideOut[a1] + y * strideOut[a2];
      const std::int64_t si = strideIn[axis], so = strideOut[axis];
      for (std::int64_t i = 0; i <= m[axis] - 1; ++i) {
        double q;
        if (i <= k - p)
          q = in[i * si];
        else if (i >= k - mult + 1)
          q = in[(i - 1) * si];
        else
          q = alpha[i] * in[i * si] + (1.0 - alpha[i]) * in[(i - 1) * si];
        o[i * so] = static_cast<float>(q);
      }
    }
  }
  std::array<KnotVector, 3> knots = knots_;
  knots[axis] = kv.withInsertedKnot(u);
  return TensorBSpline(std::move(knots), std::move(out));
}

}  // namespace mfadvr
