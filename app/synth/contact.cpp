// Contact step solver (Hunt–Crossley + elasto-plastic friction, discrete-gradient scheme) and
// the rigid-wall impact entry point; see contact.h for the scheme and its sources.
#include "synth/contact.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "synth/contact_kernel.h"

namespace sas::synth {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// 1 / n! for the series of Phis.
constexpr double kInverseFactorial[19] = {1.0,
                                          1.0,
                                          1.0 / 2.0,
                                          1.0 / 6.0,
                                          1.0 / 24.0,
                                          1.0 / 120.0,
                                          1.0 / 720.0,
                                          1.0 / 5040.0,
                                          1.0 / 40320.0,
                                          1.0 / 362880.0,
                                          1.0 / 3628800.0,
                                          1.0 / 39916800.0,
                                          1.0 / 479001600.0,
                                          1.0 / 6227020800.0,
                                          1.0 / 87178291200.0,
                                          1.0 / 1307674368000.0,
                                          1.0 / 20922789888000.0,
                                          1.0 / 355687428096000.0,
                                          1.0 / 6402373705728000.0};

// φ1 = (1 - e^-r) / r and φ2 = (r - 1 + e^-r) / r², with their series where the closed forms
// lose digits. Inlined into the bristle step: as a call its two results went through memory
// (4 % of a rub's instructions).
[[gnu::always_inline]] inline void Phis(double r, double* phi1, double* phi2) {
  if (r < 0.125) {
    // φ1 = Σ (-r)^n / (n+1)!, φ2 = Σ (-r)^n / (n+2)!: the terms to n = 9 leave < 1e-16 for
    // r < 1/8, and a bristle sliding a fraction of z_ss per step (the usual case) needs no exp.
    // Estrin's scheme (pairs, then powers of x²) keeps the dependency chain short.
    const double x = -r, x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
    const double* c = kInverseFactorial;
    // Coefficients of x^n: φ1 -> c[n + 1], φ2 -> c[n + 2].
    *phi1 = (c[1] + c[2] * x) + x2 * (c[3] + c[4] * x) +
            x4 * ((c[5] + c[6] * x) + x2 * (c[7] + c[8] * x)) + x8 * (c[9] + c[10] * x);
    *phi2 = (c[2] + c[3] * x) + x2 * (c[4] + c[5] * x) +
            x4 * ((c[6] + c[7] * x) + x2 * (c[8] + c[9] * x)) + x8 * (c[10] + c[11] * x);
    return;
  }
  if (r < 1.0) {
    // The same series for φ2 to n = 16 (the rest < 1e-17 relative for r < 1), and φ1 = 1 - r φ2:
    // a saturating bristle (glass) lands here on most steps, and expm1 took twice exp's time.
    const double x = -r, x2 = x * x, x4 = x2 * x2, x8 = x4 * x4, x16 = x8 * x8;
    const double* c = kInverseFactorial;
    // Coefficient of x^n: c[n + 2].
    const double low = ((c[2] + c[3] * x) + x2 * (c[4] + c[5] * x)) +
                       x4 * ((c[6] + c[7] * x) + x2 * (c[8] + c[9] * x));
    const double high = ((c[10] + c[11] * x) + x2 * (c[12] + c[13] * x)) +
                        x4 * ((c[14] + c[15] * x) + x2 * (c[16] + c[17] * x));
    *phi2 = (low + x8 * high) + x16 * c[18];
    *phi1 = 1.0 + x * *phi2;
    return;
  }
  // e^-r <= 1/e: exp(-r) - 1 is as accurate as expm1 here (within an ulp of the result).
  const double e = std::exp(-r) - 1.0;
  *phi1 = -e / r;
  *phi2 = (r + e) / (r * r);
}

// Discrete gradient G(x0, x0 + d) of the contact potential and its derivative in d.
struct Secant {
  double g = 0.0;
  double dg = 0.0;
  double f1 = -1.0;  // k x1^α where the secant needed it (x1 > 0, not the midpoint expansion)
};
// k (x0 + d)^α for a step from x0 > 0 with f0 = k x0^α: by the binomial series where the caller
// allows it (inv_x0 = 1 / x0 > 0, ImpactModel::has_pow_series) and d is small enough, else a pow.
// Inlined: as a call it cost wood 3 % (its sqrt fast path had been inlined).
[[gnu::always_inline]] inline double ForceNear(const ImpactModel& m, double x0, double d, double f0,
                                               double inv_x0) {
  const double delta = d * inv_x0;
  if (inv_x0 > 0.0 && std::fabs(delta) <= ImpactModel::kPowSeriesReach) {
    return f0 * m.PowRatio(delta);
  }
  return m.k * m.PowAlpha(x0 + d);
}

// `f0`, `inv_x0`: as ForceNear's.
// Inlined: as a call, its 24-byte result went through memory on the Newton chain.
[[gnu::always_inline]] inline Secant PotentialSecant(const ImpactModel& m, double x0, double v0,
                                                     double d, double f0, double inv_x0) {
  const double x1 = x0 + d;
  Secant s;
  if (x0 <= 0.0 && x1 <= 0.0) return s;
  const double a = m.alpha;
  if (x0 > 0.0 && x1 > 0.0 && std::fabs(d) <= 1e-4 * std::min(x0, x1)) {
    // Midpoint expansion: the plain difference quotient cancels for tiny d.
    const double mid = x0 + 0.5 * d;
    const double inv_mid = 1.0 / mid;
    const double d1 = ForceNear(m, x0, 0.5 * d, f0, inv_x0);  // first derivative of V: k x^α
    const double d2 = a * d1 * inv_mid;                       // second
    const double d3 = (a - 1.0) * d2 * inv_mid;               // third
    s.g = d1 + d3 * d * d / 24.0;
    s.dg = 0.5 * d2 + d3 * d / 12.0;  // derivative of the expansion in d (x0 fixed)
    return s;
  }
  if (x1 <= 0.0) {
    s.g = -v0 / d;  // V(x1) = 0
    s.dg = -s.g / d;
    return s;
  }
  const double f1 = ForceNear(m, x0, d, f0, inv_x0);
  const double inv_d = 1.0 / d;
  s.g = (f1 * x1 * m.inv_alpha_plus_one - v0) * inv_d;
  s.dg = (f1 - s.g) * inv_d;
  s.f1 = f1;
  return s;
}

// Normal force for compression change d: F = G·P/Q with P = max(1 + μ d / h, 0), and dF/dd.
// Q = 1 - a (f(x1) - f(x0)), f = k x^α, a = μ C / (3h) (C: the step's normal compliance, so
// h²/(2C) is the mass the force moves over the step): G·P is the Hunt–Crossley force of the
// step's mean compression and mean rate, but the step's work needs the mean of their product;
// the two differ by μ times the covariance of f and ẋ over the step, which is second order and
// made most of the scheme's restitution error (it grew with μ·v). 1/Q corrects for it to leading
// order: on a rigid wall (10 g, k = 1e8, μ·v = 0.1 .. 1) the error at 2 sub-steps falls from
// 7.6e-4 to 1.5e-7 (contact_bench --front). Passive for any step: Δf has the sign of d, so
// Q <= 1 while compressing (F >= G, work >= ΔV) and Q >= 1 while releasing (F <= G, work >= ΔV
// as ΔV < 0); Q is held at kMinQ where a step is too coarse for the expansion (it stays <= 1).
// F stays nondecreasing in d (G, P rise, Q falls), as the monotone solve needs.
constexpr double kMinQ = 0.5;
struct NormalEval {
  double f = 0.0;
  double df = 0.0;
  double f1 = -1.0;  // k x1^α where the evaluation took it (x1 > 0), else -1
};
// `mu_over_h` = μ / h, `f0` = f(x0) (0 if x0 <= 0), `a` = μ C / (3h), `inv_x0`: 1 / x0 where the
// powers may come from PowRatio (ForceNear), else 0.
// Inlined: as a call, its 24-byte result went through memory on the Newton chain.
[[gnu::always_inline]] inline NormalEval NormalForce(const ImpactModel& m, double x0, double v0,
                                                     double d, double mu_over_h, double f0,
                                                     double a, double inv_x0) {
  const Secant s = PotentialSecant(m, x0, v0, d, f0, inv_x0);
  const double p = 1.0 + mu_over_h * d;
  NormalEval e;
  if (p <= 0.0) return e;  // separating faster than 1/μ: Hunt–Crossley would pull; clamp to 0
  const double x1 = x0 + d;
  double q = 1.0, dq = 0.0;
  if (a > 0.0) {
    // The secant's own k x1^α when it took one (one power per evaluation, not two).
    const double f1 = x1 > 0.0 ? (s.f1 >= 0.0 ? s.f1 : ForceNear(m, x0, d, f0, inv_x0)) : 0.0;
    q = 1.0 - a * (f1 - f0);
    if (x1 > 0.0) e.f1 = f1;
    if (q < kMinQ) {
      q = kMinQ;
    } else if (x1 > 0.0) {
      dq = -a * m.alpha * f1 / x1;
    }
  } else if (s.f1 >= 0.0) {
    e.f1 = s.f1;
  }
  const double inv_q = 1.0 / q;
  e.f = s.g * p * inv_q;
  e.df = (s.dg * p + s.g * mu_over_h) * inv_q - e.f * dq * inv_q;
  return e;
}

// Root of R(d) = d - c + s·F(d), F nondecreasing in d (so R is strictly increasing), starting
// from d_start. `force(d)` returns F(d) and dF/dd. Returns d and stores F(d) in *force_out.
// hi = c is an upper bound when F >= 0; the lower bound c - s·F(c) (where R <= 0) is only
// computed if a Newton step needs the safeguard (or d_start is not below hi).
template <class ForceFn>
double SolveMonotone(const ForceFn& force, double c, double compliance, double d_start,
                     double scale, double* force_out, double* slope_out = nullptr) {
  double hi = c;
  double lo = -std::numeric_limits<double>::infinity();
  bool lo_known = false;
  auto lower_bound = [&]() {
    const double f_hi = force(c).f;
    lo_known = true;
    return c - compliance * f_hi;  // F(lo) <= F(c), so R(lo) <= 0
  };
  double d = d_start;
  if (!(d < hi)) {
    lo = lower_bound();
    d = lo;
  }
  NormalEval e = force(d);
  double r = d - c + compliance * e.f;
  for (int iteration = 0; iteration < 100; ++iteration) {
    // Converged when the residual is at the rounding level of its terms.
    if (r == 0.0 || std::fabs(r) <= 4.0 * kEps * (std::fabs(c) + std::fabs(d))) break;
    if (r < 0.0) {
      lo = d;
      lo_known = true;
    } else {
      hi = d;
    }
    const double slope = 1.0 + compliance * e.df;
    double next = d - r / slope;
    // A Newton step at the rounding level of d: d is the root (keep d and its force, a consistent
    // pair, without another evaluation).
    if (std::fabs(next - d) <= 2.0 * kEps * scale) break;
    if (!(next > lo && next < hi)) {
      if (!lo_known) lo = std::min(lower_bound(), hi);
      next = (next > lo && next < hi) ? next : 0.5 * (lo + hi);
    }
    const double step = std::fabs(next - d);
    d = next;
    e = force(d);
    r = d - c + compliance * e.f;
    if (step <= 2.0 * kEps * scale || hi - lo <= 2.0 * kEps * scale) break;
  }
  *force_out = e.f;
  if (slope_out != nullptr) *slope_out = 1.0 + compliance * e.df;
  return d;
}

// Discrete-gradient normal solve of one step: F(d) = G(x0, x0 + d)·P(d)/Q(d) (NormalForce), root
// of d - c + C F(d) = 0 for the free compression change c. The coupled contact solve calls it
// several times per step with nearly equal c, so V(x0) and the start are computed once, and each
// call starts from the last root moved by the first-order change Δc / R'(d) (one Newton step from
// the answer).
class DiscreteGradientSolve {
 public:
  DiscreteGradientSolve(const ImpactModel& m, double x0, double compliance, double h)
      : m_(m),
        x0_(x0),
        compliance_(compliance),
        mu_over_h_(m.mu / h),
        a_(mu_over_h_ * compliance / 3.0),
        v0_(0.0) {
    if (x0 > 0.0) {
      f0_ = m.Force(x0);
      // V(x0) = Potential's own product k x0^α · x0 / (α + 1), from the same power (a pow for
      // the shapes without a fast path).
      v0_ = f0_ * x0 * m.inv_alpha_plus_one;
      if (m.has_pow_series) inv_x0_ = 1.0 / x0;
      const double df0 = m.alpha * f0_ / x0;  // f'(x0)
      slope0_ = 0.5 * df0 + f0_ * m.mu / h + f0_ * a_ * df0;
    }
  }
  // Returns d and stores F(d) in *force and dF/dc in *dforce_dc.
  double operator()(double c, double* force, double* dforce_dc) {
    *force = 0.0;
    *dforce_dc = 0.0;
    if (x0_ <= 0.0 && x0_ + c <= 0.0) return c;  // the free motion never reaches the surface
    // Start from the last root, or from the root of the problem linearised at d = 0 (resting
    // contact: already close), or, for a contact starting in this step, from the upper bound.
    double d = c;
    if (has_last_) {
      d = last_d_ + (c - last_c_) / last_slope_;
    } else if (x0_ > 0.0) {
      d = (c - compliance_ * f0_) / (1.0 + compliance_ * slope0_);
    }
    const double scale = std::max(std::fabs(x0_), std::fabs(c)) + 1e-300;
    double slope = 1.0;
    // The evaluation inlined into the solve: as a call, its 24-byte result went through memory.
    d = SolveMonotone(
        [&](double dd) __attribute__((always_inline)) {
          return NormalForce(m_, x0_, v0_, dd, mu_over_h_, f0_, a_, inv_x0_);
        },
        c,
        compliance_, d, scale, force, &slope);
    // R(d) = d - c + C F(d) = 0: dd/dc = 1 / R', dF/dc = F' / R' = (R' - 1) / (C R').
    if (slope > 0.0) *dforce_dc = (slope - 1.0) / (compliance_ * slope);
    if (std::isfinite(d) && slope > 0.0) {
      has_last_ = true;
      last_c_ = c;
      last_d_ = d;
      last_slope_ = slope;
    }
    return d;
  }

 private:
  const ImpactModel& m_;
  double x0_, compliance_, mu_over_h_, a_, v0_;
  double f0_ = 0.0, slope0_ = 0.0, inv_x0_ = 0.0;
  bool has_last_ = false;
  double last_c_ = 0.0, last_d_ = 0.0, last_slope_ = 1.0;
};

// Hunt–Crossley force f(x, ẋ) = k x₊^α max(1 + μ ẋ, 0) (never pulls) and its partial derivatives.
struct HuntCrossley {
  double f = 0.0, df_dx = 0.0, df_dxdot = 0.0;
};
HuntCrossley HuntCrossleyForce(const ImpactModel& m, double x, double xdot) {
  HuntCrossley out;
  if (x <= 0.0) return out;
  const double p = 1.0 + m.mu * xdot;
  if (p <= 0.0) return out;
  const double elastic = m.k * m.PowAlpha(x);
  out.f = elastic * p;
  out.df_dx = m.alpha * elastic / x * p;
  out.df_dxdot = elastic * m.mu;
  return out;
}

// Passivity guard shared by the explicit and trapezoid schemes (contact.h): the largest force
// F >= 0 whose work keeps the contact's received energy non-negative, E + F (c - C F) >= 0.
double PassiveForceLimit(double c, double compliance, double energy) {
  const double e = std::max(energy, 0.0);
  return (c + std::sqrt(c * c + 4.0 * compliance * e)) / (2.0 * compliance);
}

// The normal solve of each scheme for a free compression change c (friction coupling included):
// the held force, the compression change and the scheme's contact state after the step.
struct NormalStep {
  double force = 0.0;
  double dforce_dc = 0.0;  // dF/dc at the root (0 where unknown: the search then holds F)
  double dx = 0.0;
  double aux = 0.0;
  double energy_j = 0.0;
};

NormalStep DiscreteGradientNormal(const ImpactModel& m, DiscreteGradientSolve& solve, double x0,
                                  double c) {
  NormalStep s;
  s.dx = solve(c, &s.force, &s.dforce_dc);
  s.energy_j = m.Potential(x0 + s.dx);
  return s;
}

// Applies the passivity guard to a force F >= 0 and books its work into the contact energy.
NormalStep GuardedNormal(const ContactStepInput& in, double c, double force) {
  NormalStep s;
  const double e0 = in.x0 > 0.0 ? std::max(in.aux0, 0.0) : 0.0;  // an open contact holds nothing
  s.force = std::clamp(force, 0.0, PassiveForceLimit(c, in.normal_compliance, e0));
  s.dx = c - in.normal_compliance * s.force;
  // Released energy is dissipated when the contact opens.
  s.aux = in.x0 + s.dx > 0.0 ? std::max(e0 + s.force * s.dx, 0.0) : 0.0;
  s.energy_j = s.aux;
  return s;
}

NormalStep ExplicitNormal(const ImpactModel& m, const ContactStepInput& in, double c) {
  return GuardedNormal(in, c, HuntCrossleyForce(m, in.x0, in.xdot0).f);
}

NormalStep TrapezoidNormal(const ImpactModel& m, const ContactStepInput& in, double c) {
  const double f0 = HuntCrossleyForce(m, in.x0, in.xdot0).f;
  const double h = in.h;
  if (in.x0 + c - in.normal_compliance * 0.5 * f0 <= 0.0) {
    return GuardedNormal(in, c, 0.5 * f0);  // ends open: only the start-of-step half acts
  }
  // R(d) = d - c + C (½ f0 + ½ f1(d)) = d - c_eff + C ½ f1(d), f1(d) = f(x0 + d, 2d/h - ẋ0):
  // ½ f1 is nondecreasing and convex in d, so SolveMonotone applies with c_eff.
  auto half_end_force = [&](double d) {
    const HuntCrossley end = HuntCrossleyForce(m, in.x0 + d, 2.0 * d / h - in.xdot0);
    return NormalEval{0.5 * end.f, 0.5 * (end.df_dx + 2.0 / h * end.df_dxdot)};
  };
  const double compliance = in.normal_compliance;
  const double c_eff = c - compliance * 0.5 * f0;
  // Start from the root of the residual linearised at d = 0.
  const NormalEval at0 = half_end_force(0.0);
  const double d_start = (c_eff - compliance * at0.f) / (1.0 + compliance * at0.df);
  const double scale = std::max(std::fabs(in.x0), std::fabs(c)) + 1e-300;
  double half_f1 = 0.0;
  SolveMonotone(half_end_force, c_eff, compliance, d_start, scale, &half_f1);
  return GuardedNormal(in, c, 0.5 * f0 + half_f1);
}

NormalStep QuadratisedNormal(const ImpactModel& m, const ContactStepInput& in, double c) {
  NormalStep s;
  const double compliance = in.normal_compliance;
  // ψ belongs to one contact: dropped (dissipated) when the step starts open.
  const double psi0 = in.x0 > 0.0 ? in.aux0 : 0.0;
  // Predicted step: the free motion under the previous step's force (second-order accurate).
  const double d_pred = c - compliance * std::max(in.normal_guess_n, 0.0);
  const double x_pred = in.x0 + d_pred;
  double g = 0.0, damping = 0.0;
  if (in.x0 > 0.0 || x_pred > 0.0) {
    // g: the secant of Ψ(x) = √(2 V(x)) over the predicted step (dψ/dx = √(k(α+1)/2) x^((α-1)/2)
    // at a mid-step point; the secant stays accurate where that derivative is singular, x -> 0,
    // and across the onset). The loss λ x^α ẋ as μ G Δx / h with G the secant of V (the
    // discrete-gradient form of the damping).
    const double v0 = m.Potential(in.x0), v1 = m.Potential(x_pred);
    if (std::fabs(d_pred) > 1e-6 * std::max(std::fabs(in.x0), std::fabs(x_pred))) {
      g = (std::sqrt(2.0 * v1) - std::sqrt(2.0 * v0)) / d_pred;
      damping = m.mu * (v1 - v0) / d_pred / in.h;
    } else {
      const double x = in.x0 + 0.5 * d_pred;  // tiny step: the derivative at its midpoint
      const double elastic = m.k * m.PowAlpha(x);
      g = std::sqrt(0.5 * (m.alpha + 1.0) * elastic / x);
      damping = m.mu * elastic / in.h;
    }
  }
  // F = g ψ0 + a Δx, Δx = c - C F: one linear solve.
  const double a = 0.5 * g * g + damping;
  s.force = (g * psi0 + a * c) / (1.0 + a * compliance);
  if (s.force >= 0.0) {
    s.dx = c - compliance * s.force;
    s.aux = psi0 + g * s.dx;
  } else {
    // The contact would pull: no force, and |ψ| may only shrink (the step dissipates).
    s.force = 0.0;
    s.dx = c;
    s.aux = std::clamp(psi0 + g * c, -std::fabs(psi0), std::fabs(psi0));
  }
  s.energy_j = 0.5 * s.aux * s.aux;
  return s;
}

// Root of a continuous slip residual r(u) that tends to ±∞ with u (not monotone where the
// Stribeck curve falls), searched from the predictor a with r(a) = r_a. `residual(u)` evaluates
// r. Secant steps started with `slope0` (the elastic, sticking slope, close to the true one unless
// the bristle saturates) usually converge in 2-3 evaluations; if they do not, the root is
// bracketed by expansion and found by Illinois regula falsi (superlinear, never leaves the
// bracket). Returns the root; the caller re-evaluates there if it was not the last point tried.
// df/du of the friction step while the bristle sticks (elastic: mean z = z0 + u/2, z1 = z0 + u):
// σ0/2 + (σ1 + σ2)/h. The slip solves start from it where nothing better is known.
double StickingFrictionSlope(const FrictionModel& friction, double inv_h) {
  return 0.5 * friction.sigma0 + (friction.sigma1 + friction.sigma2) * inv_h;
}

template <class Residual>
double SolveSlip(const Residual& residual, double a, double r_a, double slope0,
                 double* slope_out = nullptr) {
  if (r_a == 0.0) return a;
  {
    double u_prev = a, r_prev = r_a;
    double u = a - r_a / slope0;
    for (int i = 0; i < 8; ++i) {
      const double r = residual(u);
      if (r == 0.0) return u;
      const double secant = (r - r_prev) / (u - u_prev);
      if (slope_out != nullptr && std::isfinite(secant) && secant > 0.0) *slope_out = secant;
      const double step = r * (u - u_prev) / (r - r_prev);
      if (!std::isfinite(step)) break;
      // Converged: the next step is at the rounding level of u, so u itself (the last point
      // evaluated) is kept and no further evaluation is needed.
      if (std::fabs(step) <= 4.0 * kEps * std::fabs(u)) return u;
      u_prev = u;
      r_prev = r;
      u -= step;
    }
  }
  double delta = 2.0 * std::fabs(r_a) + 1e-30;
  double lo = a, hi = a, r_lo = r_a, r_hi = r_a;
  bool bracketed = false;
  for (int i = 0; i < 200 && !bracketed; ++i) {
    if (r_a > 0.0) {
      lo = a - delta;
      r_lo = residual(lo);
      bracketed = r_lo <= 0.0;
    } else {
      hi = a + delta;
      r_hi = residual(hi);
      bracketed = r_hi >= 0.0;
    }
    delta *= 2.0;
  }
  if (!bracketed) return a;
  if (r_lo == 0.0) return lo;
  if (r_hi == 0.0) return hi;
  const double scale = std::max({std::fabs(lo), std::fabs(hi), 1e-300});
  int side = 0;
  double u = lo;
  for (int iteration = 0; iteration < 200; ++iteration) {
    u = (lo * r_hi - hi * r_lo) / (r_hi - r_lo);
    if (!(u > lo && u < hi)) u = 0.5 * (lo + hi);
    const double r = residual(u);
    if (r == 0.0) return u;
    if (r < 0.0) {
      lo = u;
      r_lo = r;
      if (side == -1) r_hi *= 0.5;
      side = -1;
    } else {
      hi = u;
      r_hi = r;
      if (side == 1) r_lo *= 0.5;
      side = 1;
    }
    if (hi - lo <= 4.0 * kEps * scale) break;
  }
  return u;
}

}  // namespace

bool IsContactSchemeImplemented(ContactScheme scheme) {
  switch (scheme) {
    case ContactScheme::kExplicitPassive:
    case ContactScheme::kTrapezoidNewton:
    case ContactScheme::kDiscreteGradient:
    case ContactScheme::kEnergyQuadratised:
      return true;
  }
  return false;
}

void ImpactModel::Set(const ImpactParams& params) {
  enabled = params.enabled;
  k = params.stiffness;
  mu = params.dissipation_s_per_m;
  alpha = params.shape_alpha;
  inv_alpha_plus_one = 1.0 / (alpha + 1.0);
  shape_ = alpha == 1.0   ? Shape::kOne
           : alpha == 1.5 ? Shape::kThreeHalves
           : alpha == 2.0 ? Shape::kTwo
                          : Shape::kOther;
  double c = 1.0;
  for (int n = 1; n <= 6; ++n) {
    c *= (alpha - (n - 1)) / n;
    binomial_[n - 1] = c;
  }
  // The first term left out bounds the rest (|C(α, n+1) / C(α, n)| < 1 past n = α, and the reach
  // is small): keep it under 1e-17, a twentieth of an ulp of 1.
  const double next = c * (alpha - 6.0) / 7.0;
  has_pow_series = shape_ == Shape::kOther && alpha > 0.0 && alpha < 7.0 &&
                   std::fabs(next) * std::pow(kPowSeriesReach, 7.0) <= 1e-17;
}

double ImpactModel::Potential(double x) const {
  if (x <= 0.0) return 0.0;
  return k * PowAlpha(x) * x * inv_alpha_plus_one;
}

double ImpactModel::Force(double x) const {
  if (x <= 0.0) return 0.0;
  return k * PowAlpha(x);
}

void FrictionModel::Set(const FrictionParams& params) {
  enabled = params.enabled;
  sigma0 = params.bristle_stiffness;
  sigma1 = params.bristle_damping;
  sigma2 = params.viscous_friction;
  sigma3 = params.noise_coefficient;
  mu_s = params.static_coefficient;
  mu_d = params.dynamic_coefficient;
  v_s = params.stribeck_velocity_mps;
  c_ba = params.breakaway_ratio;
  bristle_update = params.bristle_update;
  inv_v_s = 1.0 / v_s;
  inv_sigma0 = 1.0 / sigma0;
  // |(μ_s - μ_d) f_N e^-s| < 2^-55 |μ_d f_N| for s beyond the cutoff: a quarter of an ulp of the
  // sum's first term (ulp(x) >= |x| 2^-53, also for subnormals), so the rounded sum is that term,
  // with or without a fused multiply-add, and the cutoff's one unit of margin covers the rounding
  // of the Stribeck term and of the exp itself. Equal coefficients: the term is always 0.
  const double spread = std::fabs(mu_s - mu_d);
  if (spread == 0.0) {
    stribeck_negligible_sq = -std::numeric_limits<double>::infinity();
  } else if (std::fabs(mu_d) > 0.0) {
    stribeck_negligible_sq = 55.0 * std::numbers::ln2 + std::log(spread / std::fabs(mu_d)) + 1.0;
  } else {
    stribeck_negligible_sq = std::numeric_limits<double>::infinity();
  }
  if (!(stribeck_negligible_sq == stribeck_negligible_sq)) {  // NaN coefficients: never skip
    stribeck_negligible_sq = std::numeric_limits<double>::infinity();
  }
}

double FrictionModel::SteadyDeflection(double v_mps, double fn) const {
  const double ratio = v_mps * inv_v_s;
  const double ratio_sq = ratio * ratio;
  // Past the cutoff the sum below rounds to its first term (Set): the same value, bit for bit.
  if (ratio_sq > stribeck_negligible_sq) return (mu_d * fn) * inv_sigma0;
  return (mu_d * fn + (mu_s - mu_d) * fn * std::exp(-ratio_sq)) * inv_sigma0;
}

double FrictionModel::SteadySlidingForce(double v_mps, double fn) const {
  return sigma0 * SteadyDeflection(std::fabs(v_mps), fn) + sigma2 * std::fabs(v_mps);
}

namespace {

// Dupont et al.'s α(z, v) for a deflection w >= 0 along the slip (friction.md): 0 in the elastic
// range w <= z_ba, a sine ramp up to z_ss, 1 beyond.
double BristleAlpha(double w, double z_ss, double z_ba) {
  if (w >= z_ss || !(z_ss > z_ba)) return 1.0;
  if (w <= z_ba) return 0.0;
  return 0.5 * (1.0 + std::sin(std::numbers::pi * (w - 0.5 * (z_ss + z_ba)) / (z_ss - z_ba)));
}

}  // namespace

namespace {

// AdvanceBristleAt's body, inlined into the contact solves (a call, with its 80-byte result
// returned through memory, sat on the Newton iteration's dependency chain).
// kAtStart: the caller made `limits` with CacheStart(z0) for this very z0 (the contact solves,
// whose every evaluation starts from the step's deflection), so the cache's check reduces to
// whether the first piece starts at z0. The result is the same either way (a NaN z0, which fails
// the check, recomputes α each time as the cache's NaN marker does).
template <bool kAtStart = false>
[[gnu::always_inline]] inline BristleStep StepBristle(const FrictionModel& model, double z0,
                                                      double du, const BristleLimits& limits) {
  BristleStep out;
  if (!limits.contact) return out;  // no normal force: no contact, the bristle is relaxed
  if (du == 0.0) {
    out.z1 = z0;
    out.mean_z = z0;
    return out;
  }
  // Work along the slip: w = z·sgn(du) so the slip is positive; with z_ss frozen over the step,
  // dz/du = 1 - α(z) z / z_ss is an autonomous ODE in the slip.
  const double sign = du > 0.0 ? 1.0 : -1.0;
  const double total = std::fabs(du);
  const double z_ss = limits.z_ss;
  const double z_ba = limits.z_ba;
  const double inv_z_ss = limits.inv_z_ss;
  double w = sign * z0;
  if (model.bristle_update == BristleUpdate::kExplicitEuler) {
    // Forward Euler over the whole slip, force from the deflection at the start (explicit).
    // Unstable once total / z_ss > 2: kept for the benchmark's comparison only.
    out.z1 = sign * (w + total * (1.0 - BristleAlpha(w, z_ss, z_ba) * w / z_ss));
    out.mean_z = z0;
    return out;
  }
  double left = total;
  double integral = 0.0;  // ∫ w dslip
  // Elastic (presliding) part: α = 0 while w <= z_ba (this includes w < 0, sgn z ≠ sgn v).
  if (w < z_ba) {
    const double piece = std::min(left, z_ba - w);
    integral += (w + 0.5 * piece) * piece;
    w += piece;
    left -= piece;
    if (left <= 0.0) {  // all elastic: z1 = z0 + du, mean = z0 + du / 2 (no division)
      out.z1 = sign * w;
      out.mean_z = z0 + 0.5 * du;
      out.slope = BristleStep::Slope::kElastic;
      return out;
    }
  }
  // Elasto-plastic and plastic parts: exact exponential relaxation with α frozen per piece.
  const bool start_known =
      (kAtStart || (limits.start_cached && limits.start_z == z0)) && left == total;
  for (int i = 0; i < 64 && left > 0.0; ++i) {
    double alpha = 1.0;
    if (i == 0 && start_known) {
      double& cached = sign > 0.0 ? limits.start_alpha_positive : limits.start_alpha_negative;
      if (std::isnan(cached)) cached = w < z_ss ? BristleAlpha(w, z_ss, z_ba) : 1.0;
      alpha = cached;
    } else if (w < z_ss) {
      alpha = BristleAlpha(w, z_ss, z_ba);
    }
    double piece = left;
    if (alpha < 1.0 && i < 63) piece = std::min(left, 0.25 * z_ss / (1.0 - alpha + 1e-3));
    const double r = alpha * piece * inv_z_ss;
    double p1 = 0.0, p2 = 0.0;
    Phis(r, &p1, &p2);
    const double piece_mean = piece * p2 + w * p1;  // mean of w over the piece
    const double w_next = w + (piece - alpha * w * piece * inv_z_ss) * p1;
    if (i == 0 && piece == total) {
      // One piece over the whole slip (the usual step): BristleSlope can give the derivatives
      // from these, and the mean is the piece's own, without the division below.
      out.slope = BristleStep::Slope::kOnePiece;
      out.piece_r = r;
      out.piece_phi1 = p1;
      out.piece_phi2 = p2;
      out.piece_w = w;
      out.piece_alpha = alpha;
      out.mean_z = sign * piece_mean;
      out.z1 = sign * w_next;
      return out;
    }
    integral += piece * piece_mean;
    w = w_next;
    left -= piece;
  }
  out.z1 = sign * w;
  out.mean_z = sign * integral / total;
  return out;
}

}  // namespace

BristleStep AdvanceBristleAt(const FrictionModel& model, double z0, double du,
                             const BristleLimits& limits) {
  return StepBristle(model, z0, du, limits);
}

void BristleLimits::CacheStart(double z0) {
  start_cached = true;
  start_z = z0;
  start_alpha_positive = std::numeric_limits<double>::quiet_NaN();
  start_alpha_negative = std::numeric_limits<double>::quiet_NaN();
}

namespace {

// BristleSlope's body, inlined into the closed sliding step's Newton loop (as a call its two
// results went through memory).
[[gnu::always_inline]] inline bool SlopeOfStep(const BristleStep& step, const BristleLimits& limits,
                                               double* dz1_du, double* dmean_du) {
  switch (step.slope) {
    case BristleStep::Slope::kElastic:  // z1 = z0 + du, mean = z0 + du / 2
      *dz1_du = 1.0;
      *dmean_du = 0.5;
      return true;
    case BristleStep::Slope::kOnePiece: {
      // One piece over the whole slip p = |du| with α frozen: w1 = w + p (1 - α w / z_ss) φ1(r),
      // mean = p φ2(r) + w φ1(r), r = α p / z_ss, so (with ' = d/dr)
      //   dw1/dp = (1 - α w / z_ss)(φ1 + r φ1'),  dmean/dp = φ2 + r φ2' + w φ1' α / z_ss,
      //   φ1' = (e^-r - φ1) / r = (1 - (1 + r) φ1) / r,  φ2' = (φ1 - 2 φ2) / r
      // (series below r = 1/8, where those differences cancel; 1e-8 is plenty for a Newton slope).
      // Along the slip and in z the signs cancel: dz1/du = dw1/dp, dmean_z/du = dmean_w/dp.
      const double r = step.piece_r, p1 = step.piece_phi1, p2 = step.piece_phi2;
      double d1 = 0.0, d2 = 0.0;
      if (r < 0.125) {
        d1 = -0.5 + r * (1.0 / 3.0 - r * (1.0 / 8.0 - r * (1.0 / 30.0 - r / 144.0)));
        d2 = -1.0 / 6.0 + r * (1.0 / 12.0 - r * (1.0 / 40.0 - r * (1.0 / 180.0 - r / 1008.0)));
      } else {
        d1 = (1.0 - (1.0 + r) * p1) / r;
        d2 = (p1 - 2.0 * p2) / r;
      }
      const double alpha_w = step.piece_alpha * limits.inv_z_ss;
      *dz1_du = (1.0 - alpha_w * step.piece_w) * (p1 + r * d1);
      *dmean_du = p2 + r * d2 + step.piece_w * d1 * alpha_w;
      return true;
    }
    case BristleStep::Slope::kUnknown:
    default:
      return false;
  }
}

}  // namespace

bool BristleSlope(const BristleStep& step, const BristleLimits& limits, double* dz1_du,
                  double* dmean_du) {
  return SlopeOfStep(step, limits, dz1_du, dmean_du);
}

BristleLimits FrictionModel::Limits(double slip_velocity_mps, double fn) const {
  BristleLimits limits;
  limits.contact = fn > 0.0;
  if (!limits.contact) return limits;
  limits.z_ss = SteadyDeflection(std::fabs(slip_velocity_mps), fn);
  limits.inv_z_ss = 1.0 / limits.z_ss;
  limits.z_ba = c_ba * mu_d * fn * inv_sigma0;
  return limits;
}

BristleStep AdvanceBristle(const FrictionModel& model, double z0, double du, double h, double fn) {
  return AdvanceBristleAt(model, z0, du, model.Limits(std::fabs(du) / h, fn));
}

double FrictionStepForce(const FrictionModel& model, double z0, const BristleStep& step, double du,
                         double inv_h, double noise_n) {
  const double dz = step.z1 - z0;
  // σ1 acts only while the bristle deflects with the slip (Dupont et al.'s passivity condition).
  const double damping = dz * du >= 0.0 ? model.sigma1 * dz * inv_h : 0.0;
  return model.sigma0 * step.mean_z + damping + model.sigma2 * du * inv_h + noise_n;
}

namespace {

// Normal force (one scheme's NormalStep for a given free compression change) and friction,
// coupled through the shared resonator, solved as ONE scalar equation in the slip u: a slip u
// gives the friction force f(u) (bristle advanced along u, z_ss frozen at the predicted slip
// speed), f gives the normal force F (the scheme's normal solve with Δx = c0 + coupling·f - C·F),
// and the residual is r(u) = u - [free_du + coupling·(F - f)]. At the root the held forces F and
// f, the compression change and the slip all belong to one step, so each interaction's work
// identity holds with the bodies' actual motion: no energy can be created by the coupling (a
// block Gauss–Seidel between the two solves ends with forces from different iterations, and did
// create energy in strongly coupled sets). Where a dedicated step is cheaper (no friction, no
// impact, a rigid body) it is taken.
template <class NormalFn>
ContactStepOutput SolveCoupled(const FrictionModel& friction, const ContactStepInput& in,
                               const NormalFn& normal) {
  ContactStepOutput out;
  const bool friction_on = in.friction_on && in.friction_normal_n > 0.0;
  NormalStep ns;
  double f = 0.0;
  if (!friction_on) {
    if (in.impact_on) ns = normal(in.free_dx);
  } else {
    // z_ss frozen at the predicted slip speed: the free slip plus the previous normal force's
    // coupling (the friction's own coupling correction is small, and any z_ss is passive).
    const double predicted =
        in.free_du + (in.impact_on ? in.coupling * std::max(in.normal_guess_n, 0.0) : 0.0);
    BristleLimits limits = friction.Limits(predicted / in.h, in.friction_normal_n);
    limits.CacheStart(in.z0);
    const double inv_h = 1.0 / in.h;
    double last_u = std::numeric_limits<double>::quiet_NaN();
    // Only the end deflection of the last step tried is kept: each evaluation's BristleStep stays
    // a local the compiler can keep in registers (a captured one was written out, all 80 bytes,
    // on every evaluation).
    double bristle_z1 = 0.0;
    auto evaluate = [&](double u) {  // f(u), F(f) and the residual r(u)
      last_u = u;
      const BristleStep bristle = StepBristle<true>(friction, in.z0, u, limits);
      bristle_z1 = bristle.z1;
      f = FrictionStepForce(friction, in.z0, bristle, u, inv_h, in.noise_n);
      if (in.impact_on) ns = normal(in.free_dx + in.coupling * f);
      return u - in.free_du - in.coupling * (ns.force - f);
    };
    double u = in.free_du;
    if (in.coupling > 0.0) {
      const double a = in.impact_on ? predicted : in.free_du;
      const double r_a = evaluate(a);
      // While searching, the normal force follows f to first order (F' = dF/dc at the first
      // solve: the friction moves c by coupling·Δf, tiny against the compression change), which
      // saves a normal solve per iteration; the final evaluation below solves it exactly, so the
      // step that is taken is consistent.
      const double f_a = f, force_a = ns.force;
      const double dforce_dc = ns.dforce_dc;
      auto search = [&](double uu) {
        last_u = uu;
        const BristleStep bristle = StepBristle<true>(friction, in.z0, uu, limits);
        bristle_z1 = bristle.z1;
        f = FrictionStepForce(friction, in.z0, bristle, uu, inv_h, in.noise_n);
        const double force =
            in.impact_on ? std::max(force_a + dforce_dc * in.coupling * (f - f_a), 0.0) : 0.0;
        return uu - in.free_du - in.coupling * (force - f);
      };
      // First step: the residual's slope found by the previous step (the state changes little
      // from one step to the next), else the elastic (sticking) slope.
      const double slope0 = in.slip_slope_guess > 0.0
                                ? in.slip_slope_guess
                                : 1.0 + in.coupling * StickingFrictionSlope(friction, inv_h);
      out.slip_slope = slope0;
      u = SolveSlip(search, a, r_a, slope0, &out.slip_slope);
    }
    if (u == last_u) {
      // The bristle and f(u) are those of the last point tried: only F is solved exactly for f.
      if (in.impact_on) ns = normal(in.free_dx + in.coupling * f);
    } else {
      evaluate(u);
    }
    if (in.impact_on && in.coupling > 0.0) {
      // Where F does not follow f linearly (a scheme without dF/dc, the passivity guard, the
      // contact opening), the slip left by the search is not yet the bodies' slip: finish the
      // search with the exact residual.
      const double r = u - in.free_du - in.coupling * (ns.force - f);
      const double scale =
          std::fabs(u) + std::fabs(in.free_du) + in.coupling * (std::fabs(ns.force) + std::fabs(f));
      if (std::fabs(r) > 1e-12 * scale) {
        u = SolveSlip(evaluate, u, r, 1.0 + in.coupling * StickingFrictionSlope(friction, inv_h));
        if (!(u == last_u)) evaluate(u);
      }
    }
    out.z1 = bristle_z1;
  }
  out.normal_n = ns.force;
  out.friction_n = f;
  out.aux1 = ns.aux;
  out.contact_energy_j = ns.energy_j;
  out.dx = in.free_dx - in.normal_compliance * ns.force + in.coupling * f;
  out.du = in.free_du - in.coupling * f + in.coupling * ns.force;
  return out;
}

}  // namespace

namespace {

// The discrete-gradient step of a closed, sliding contact solved in the compression change d
// alone: F(d) = G(x0, x0 + d)·P(d)/Q(d) is explicit, the slip the bodies make is then explicit too,
// u(d) = free_du + free_dx - d - (h²/2m) F(d) (the two affine maps combined), and so is the
// friction force f(u(d)); d is the root of ρ(d) = free_dx + coupling·f - C·F - d. One force and one
// bristle evaluation per iteration, no inner solves. Newton on ρ with the friction's slope dF/du
// taken from a secant (the friction term is small against 1 + C F': the coupling is a compliance),
// stopping when ρ is at 1e-13 of its terms (the energy the step could be off by is F·ρ and f·ρ).
// The friction's load is the step's own normal force (friction_load_share of it), taken at the
// linearised start below and frozen for the iteration (z_ss then stays fixed, so the step stays
// passive). The previous sub-step's force lags a plate ringing against the tip: on glass
// (k = 1e8) the error budget's rub at 40 mm/s came out +1.8 dB louder than the fine-step
// reference at one sub-step per sample, +0.3 dB with the step's own force; it costs nothing more.
// Returns false (and the general solve takes over) for a contact that opens or closes within the
// step, or if the iteration does not settle quickly.
bool SolveClosedSlidingStep(const ImpactModel& m, const FrictionModel& friction,
                            const ContactStepInput& in, double predicted_slip,
                            ContactStepOutput* out) {
  if (!(in.x0 > 0.0) || !(in.coupling > 0.0)) return false;
  const double compliance = in.normal_compliance;
  const double probe_part = compliance - in.coupling;  // h² / (2 m)
  const double inv_h = in.inv_h > 0.0 ? in.inv_h : 1.0 / in.h;
  const double mu_h = m.mu * inv_h;
  const double f0_over_x0 = m.k * m.PowAlphaMinusOne(in.x0);  // k x0^(α-1)
  const double f0 = f0_over_x0 * in.x0;
  const double v0 = f0 * in.x0 * m.inv_alpha_plus_one;  // V(x0) = k x0^(α+1) / (α+1)
  const double inv_x0 = m.has_pow_series ? 1.0 / in.x0 : 0.0;
  // Start: the normal problem linearised at d = 0 with the previous step's friction force.
  const double a = mu_h * compliance / 3.0;  // NormalForce's covariance correction
  const double c = in.free_dx + in.coupling * in.friction_guess_n;
  double d =
      (c - compliance * f0) /
      (1.0 + compliance * (0.5 * m.alpha * f0_over_x0 + f0 * mu_h + f0 * a * m.alpha * f0_over_x0));
  double slope_f = 0.0;  // df/du: analytic where the bristle step gives it, else secant or guess
  double u_prev = 0.0, f_prev = 0.0;
  BristleLimits limits;
  for (int iteration = 0; iteration < 6; ++iteration) {
    if (!(in.x0 + d > 0.0)) return false;  // opening: the general solve handles the clamp
    const NormalEval e = NormalForce(m, in.x0, v0, d, mu_h, f0, a, inv_x0);
    if (iteration == 0) {
      double load = in.friction_normal_n;
      if (in.friction_load_share > 0.0) {
        if (!(e.f > 0.0)) return false;
        load = in.friction_load_share * e.f;
      }
      limits = friction.Limits(predicted_slip * inv_h, load);
      limits.CacheStart(in.z0);
    }
    const double u = in.free_du + in.free_dx - d - probe_part * e.f;
    const BristleStep b = StepBristle<true>(friction, in.z0, u, limits);
    const double f = FrictionStepForce(friction, in.z0, b, u, inv_h, in.noise_n);
    const double rho = in.free_dx + in.coupling * f - compliance * e.f - d;
    const double scale = std::fabs(d) + std::fabs(in.free_dx) + compliance * std::fabs(e.f) +
                         in.coupling * std::fabs(f);
    if (std::fabs(rho) <= 1e-10 * scale) {
      out->normal_n = e.f;
      out->friction_n = f;
      out->z1 = b.z1;
      out->aux1 = 0.0;
      // V(x1) = k x1^α · x1 / (α + 1) from the evaluation's own k x1^α (the same product).
      out->contact_energy_j =
          e.f1 >= 0.0 ? e.f1 * (in.x0 + d) * m.inv_alpha_plus_one : m.Potential(in.x0 + d);
      out->slip_slope = 1.0 + in.coupling * slope_f;
      out->dx = in.free_dx - compliance * e.f + in.coupling * f;
      out->du = in.free_du - in.coupling * f + in.coupling * e.f;
      return true;
    }
    double dz1_du = 0.0, dmean_du = 0.0;
    if (SlopeOfStep(b, limits, &dz1_du, &dmean_du)) {
      // df/du of FrictionStepForce: σ0 mean' + σ1 z1' / h (while the damping acts) + σ2 / h.
      const double dz = b.z1 - in.z0;
      slope_f = friction.sigma0 * dmean_du +
                (dz * u >= 0.0 ? friction.sigma1 * dz1_du * inv_h : 0.0) + friction.sigma2 * inv_h;
    } else if (iteration > 0 && u != u_prev) {
      const double secant = (f - f_prev) / (u - u_prev);
      if (std::isfinite(secant)) slope_f = secant;
    } else if (iteration == 0) {
      slope_f = in.slip_slope_guess > 0.0 ? (in.slip_slope_guess - 1.0) / in.coupling
                                          : StickingFrictionSlope(friction, inv_h);
    }
    u_prev = u;
    f_prev = f;
    // dρ/dd = -(1 + C F') + coupling · f'(u) · du/dd,  du/dd = -(1 + (h²/2m) F').
    const double drho =
        -(1.0 + compliance * e.df) - in.coupling * slope_f * (1.0 + probe_part * e.df);
    if (!(drho < 0.0)) return false;
    d -= rho / drho;
  }
  return false;
}

}  // namespace

ContactStepOutput SolveContactStep(const ImpactModel& impact, const FrictionModel& friction,
                                   const ContactStepInput& in) {
  if (in.impact_on && in.friction_on && in.friction_normal_n > 0.0) {
    ContactStepOutput fast;
    const double predicted = in.free_du + in.coupling * std::max(in.normal_guess_n, 0.0);
    if (SolveClosedSlidingStep(impact, friction, in, predicted, &fast)) {
      return fast;
    }
  }
  if (!in.impact_on) {
    // Friction alone (a rub with the impact model off): no normal solve is ever asked for, so
    // the normal solver's set-up (a power and two divisions) is not made.
    return SolveCoupled(friction, in, [](double) { return NormalStep{}; });
  }
  DiscreteGradientSolve solve(impact, in.x0, in.normal_compliance, in.h);
  return SolveCoupled(friction, in,
                      [&](double c) { return DiscreteGradientNormal(impact, solve, in.x0, c); });
}

ContactStepOutput SolveContactStepTrapezoid(const ImpactModel& impact,
                                            const FrictionModel& friction,
                                            const ContactStepInput& in) {
  return SolveCoupled(friction, in, [&](double c) { return TrapezoidNormal(impact, in, c); });
}

ContactStepOutput SolveContactStepExplicit(const ImpactModel& impact, const FrictionModel& friction,
                                           const ContactStepInput& in) {
  return SolveCoupled(friction, in, [&](double c) { return ExplicitNormal(impact, in, c); });
}

ContactStepOutput SolveContactStepQuadratised(const ImpactModel& impact,
                                              const FrictionModel& friction,
                                              const ContactStepInput& in) {
  return SolveCoupled(friction, in, [&](double c) { return QuadratisedNormal(impact, in, c); });
}

double RigidWallContactTime(double mass_kg, double k, double alpha, double v_in) {
  const double x_max =
      std::pow((alpha + 1.0) * mass_kg * v_in * v_in / (2.0 * k), 1.0 / (alpha + 1.0));
  const double b = 1.0 / (alpha + 1.0);
  return 2.0 * (x_max / v_in) * std::sqrt(std::numbers::pi) * std::tgamma(1.0 + b) /
         std::tgamma(0.5 + b);
}

int ChooseContactOversample(const ImpactParams& impact, double probe_mass_kg,
                            double sample_rate_hz) {
  if (impact.oversample > 0) return std::min(impact.oversample, 1024);
  if (!impact.enabled || !(impact.stiffness > 0.0)) return 1;
  const double samples =
      RigidWallContactTime(probe_mass_kg, impact.stiffness, impact.shape_alpha, 1.0) *
      sample_rate_hz;
  if (!(samples > 0.0)) return kMaxOversample;
  // A policy that names its sustained count gets it even where impacts need fewer (a material
  // without one keeps the count it was tuned with).
  const double n = std::max(std::ceil(ContactTargetSamples(impact) / samples),
                            static_cast<double>(impact.sustained_substeps));
  return static_cast<int>(std::clamp(n, 1.0, static_cast<double>(kMaxOversample)));
}

double ContactTargetSamples(const ImpactParams& impact) {
  return impact.target_contact_samples > 0.0 ? impact.target_contact_samples
                                             : TargetContactSamples(impact.scheme);
}

int SustainedContactSubsteps(const ImpactParams& impact) {
  return impact.sustained_substeps > 0 ? impact.sustained_substeps : kSustainedContactSubsteps;
}

int ContactSubstepsForSpeed(const ImpactParams& impact, double probe_mass_kg, double sample_rate_hz,
                            double v_mps) {
  if (!impact.enabled || !(impact.stiffness > 0.0) || !(v_mps > 0.0)) return 1;
  // Sub-steps per contact for the 1e-4 rule: TargetContactSamples carries a factor 1/0.8 so that
  // a fixed count covers 3 m/s; here the actual speed is known.
  const double relax = std::max(1.0, kAbsoluteSpeedFloor / v_mps);  // tolerance / 1e-4
  const double base = 0.8 * ContactTargetSamples(impact);
  const double required = impact.scheme == ContactScheme::kExplicitPassive
                              ? base / relax              // first order
                              : base / std::sqrt(relax);  // second order
  const double samples =
      RigidWallContactTime(probe_mass_kg, impact.stiffness, impact.shape_alpha, v_mps) *
      sample_rate_hz;
  if (!(samples > 0.0)) return kMaxOversample;
  return static_cast<int>(
      std::clamp(std::ceil(required / samples), 1.0, static_cast<double>(kMaxOversample)));
}

double MaxSpeedForSubsteps(const ImpactParams& impact, double probe_mass_kg, double sample_rate_hz,
                           int substeps) {
  // ContactSubstepsForSpeed grows with v: bisect on log v.
  double lo = 1e-9, hi = 1e4;
  if (ContactSubstepsForSpeed(impact, probe_mass_kg, sample_rate_hz, lo) > substeps) return 0.0;
  if (ContactSubstepsForSpeed(impact, probe_mass_kg, sample_rate_hz, hi) <= substeps) return hi;
  for (int i = 0; i < 100; ++i) {
    const double mid = std::sqrt(lo * hi);
    if (ContactSubstepsForSpeed(impact, probe_mass_kg, sample_rate_hz, mid) <= substeps) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return lo;
}

double EquilibriumEnergy(const ImpactModel& impact, double push_n) {
  if (!impact.enabled || !(push_n > 0.0) || !(impact.k > 0.0)) return 0.0;
  const double x_eq = std::pow(push_n / impact.k, 1.0 / impact.alpha);
  return -impact.alpha / (impact.alpha + 1.0) * push_n * x_eq;
}

ImpactRunResult SimulateRigidWallImpact(double mass_kg, double k, double mu, double alpha,
                                        double v_in, double sample_rate_hz, ContactScheme scheme,
                                        int oversample, double onset_phase,
                                        const std::function<bool()>& keep_going) {
  ImpactParams params;
  params.enabled = true;
  params.scheme = scheme;
  params.stiffness = k;
  params.dissipation_s_per_m = mu;
  params.shape_alpha = alpha;
  params.oversample = oversample;
  return SimulateRigidWallImpact(params, mass_kg, v_in, sample_rate_hz, onset_phase, keep_going);
}

ImpactRunResult SimulateRigidWallImpact(ImpactParams params, double mass_kg, double v_in,
                                        double sample_rate_hz, double onset_phase,
                                        const std::function<bool()>& keep_going) {
  // A value outside the enumeration runs the default; the result says which scheme ran.
  const ContactScheme used =
      IsContactSchemeImplemented(params.scheme) ? params.scheme : kDefaultContactScheme;
  params.enabled = true;
  params.scheme = used;
  ContactKernelConfig config;
  config.scheme = used;
  config.impact.Set(params);
  config.friction.enabled = false;
  config.probe_mass_kg = mass_kg;
  config.SetTiming(sample_rate_hz, ChooseContactOversample(params, mass_kg, sample_rate_hz));
  ModalState modes;  // none: a rigid, immovable body
  const bool adaptive = params.oversample <= 0;
  modes.Prepare(ResonatorParams{}, sample_rate_hz, config.substeps, false, adaptive);
  config.adaptive = adaptive && modes.level_count > 1;
  config.SetLevels(params, modes, sample_rate_hz);
  ProbeDynamics probe;
  probe.active = true;
  const double period = 1.0 / sample_rate_hz;
  probe.height_m = onset_phase * v_in * period;  // first touch onset_phase of a sample from now
  probe.velocity_mps = -v_in;
  SampleDrive drive;  // flat surface at height 0, no push, no sliding

  ImpactRunResult result;
  result.oversample = 1;
  result.scheme_used = used;
  double time = 0.0, touch_time = -1.0;
  bool in_contact = false;
  // Within a step the force is constant, so the scheme's own trajectory is a parabola; its peak
  // and zero crossings give the maximum compression and the contact time without sampling bias.
  auto observe = [&](double h, double x0, double x1, double v0, double v1) {
    const double xd0 = -v0, xd1 = -v1;  // compression rate (the wall does not move)
    const double acc = (xd1 - xd0) / h;
    if (xd0 > 0.0 && xd1 <= 0.0) {
      const double t_peak = xd0 / (xd0 - xd1) * h;
      result.max_compression_m = std::max(result.max_compression_m, x0 + 0.5 * xd0 * t_peak);
    }
    result.max_compression_m = std::max({result.max_compression_m, x0, x1});
    auto crossing = [&](double sign) {  // root of x0 + xd0 t + acc t²/2 in [0, h]
      const double disc = std::max(xd0 * xd0 - 2.0 * acc * x0, 0.0);
      const double q = -0.5 * (xd0 + sign * std::sqrt(disc));
      double t = q != 0.0 ? x0 / -q : 0.0;  // stable form of the quadratic root
      if (!(t >= 0.0 && t <= h)) t = acc != 0.0 ? q / (0.5 * acc) : h;
      if (!(t >= 0.0 && t <= h)) t = x0 / (x0 - x1) * h;
      return t;
    };
    if (!in_contact && x0 <= 0.0 && x1 > 0.0) {
      in_contact = true;
      touch_time = time + crossing(1.0);
    } else if (in_contact && x0 > 0.0 && x1 <= 0.0) {
      in_contact = false;
      result.separated = true;
      result.contact_time_s = time + crossing(-1.0) - touch_time;
    } else if (!in_contact && !result.separated && x0 <= 0.0 && x1 <= 0.0 && xd1 < xd0 &&
               xd1 < 0.0) {
      // A whole contact inside one step (an under-resolved stiff impact): the force acted, but
      // the step starts and ends apart. Its time is where the step's parabola is above 0.
      result.separated = true;
      const double disc = xd0 * xd0 - 2.0 * acc * x0;
      result.contact_time_s = disc > 0.0 && acc < 0.0 ? std::sqrt(disc) / -acc * 2.0 : 0.0;
      result.max_compression_m = std::max(result.max_compression_m, 0.0);
    }
    time += h;
  };
  const long max_samples = static_cast<long>(10.0 * sample_rate_hz);
  for (long n = 0; n < max_samples; ++n) {
    if (keep_going && (n & 4095) == 0 && n > 0 && !keep_going()) {
      result.stopped = true;
      break;
    }
    StepContactSample(config, modes, probe, drive, observe);
    result.oversample = std::max(result.oversample, probe.substeps_used);
    if (result.separated && probe.compression_m < 0.0) break;
  }
  result.exit_velocity_mps = std::fabs(probe.velocity_mps);
  result.samples_per_contact = result.contact_time_s * sample_rate_hz;
  return result;
}

}  // namespace sas::synth
