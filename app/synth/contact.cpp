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

// φ1 = (1 - e^-r) / r and φ2 = (r - 1 + e^-r) / r², with their series where the closed forms
// lose digits.
void Phis(double r, double* phi1, double* phi2) {
  if (r < 1e-3) {
    *phi1 = 1.0 - r * (0.5 - r * (1.0 / 6.0 - r / 24.0));
    *phi2 = 0.5 - r * (1.0 / 6.0 - r * (1.0 / 24.0 - r / 120.0));
    return;
  }
  const double e = std::expm1(-r);
  *phi1 = -e / r;
  *phi2 = (r + e) / (r * r);
}

// Discrete gradient G(x0, x0 + d) of the contact potential and its derivative in d.
struct Secant {
  double g = 0.0;
  double dg = 0.0;
};
Secant PotentialSecant(const ImpactModel& m, double x0, double v0, double d) {
  const double x1 = x0 + d;
  Secant s;
  if (x0 <= 0.0 && x1 <= 0.0) return s;
  const double a = m.alpha;
  if (x0 > 0.0 && x1 > 0.0 && std::fabs(d) <= 1e-4 * std::min(x0, x1)) {
    // Midpoint expansion: the plain difference quotient cancels for tiny d.
    const double mid = x0 + 0.5 * d;
    const double d1 = m.k * m.PowAlpha(mid);  // first derivative of V: k x^α
    const double d2 = a * d1 / mid;           // second
    const double d3 = (a - 1.0) * d2 / mid;   // third
    s.g = d1 + d3 * d * d / 24.0;
    s.dg = 0.5 * d2 + d3 * d / 12.0;  // derivative of the expansion in d (x0 fixed)
    return s;
  }
  if (x1 <= 0.0) {
    s.g = -v0 / d;  // V(x1) = 0
    s.dg = -s.g / d;
    return s;
  }
  const double f1 = m.k * m.PowAlpha(x1);
  s.g = (f1 * x1 / (a + 1.0) - v0) / d;
  s.dg = (f1 - s.g) / d;
  return s;
}

// Normal force for compression change d: F = G·max(1 + μ d / h, 0), and dF/dd.
struct NormalEval {
  double f = 0.0;
  double df = 0.0;
};
NormalEval NormalForce(const ImpactModel& m, double x0, double v0, double d, double h) {
  const Secant s = PotentialSecant(m, x0, v0, d);
  const double p = 1.0 + m.mu * d / h;
  NormalEval e;
  if (p <= 0.0) return e;  // separating faster than 1/μ: Hunt–Crossley would pull; clamp to 0
  e.f = s.g * p;
  e.df = s.dg * p + s.g * m.mu / h;
  return e;
}

// Root of R(d) = d - c + s·F(d), F nondecreasing in d (so R is strictly increasing), starting
// from d_start. `force(d)` returns F(d) and dF/dd. Returns d and stores F(d) in *force_out.
// hi = c is an upper bound when F >= 0; the lower bound c - s·F(c) (where R <= 0) is only
// computed if a Newton step needs the safeguard (or d_start is not below hi).
template <class ForceFn>
double SolveMonotone(const ForceFn& force, double c, double compliance, double d_start,
                     double scale, double* force_out) {
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
  return d;
}

// Discrete-gradient normal solve: F(d) = G(x0, x0 + d)·max(1 + μ d / h, 0).
double SolveNormal(const ImpactModel& m, double x0, double c, double compliance, double h,
                   double* force) {
  *force = 0.0;
  if (x0 <= 0.0 && x0 + c <= 0.0) return c;  // the free motion never reaches the surface
  const double v0 = m.Potential(x0);
  // Start from the root of the problem linearised at d = 0 (resting contact: already close),
  // or, for a contact starting in this step, from the lower bound.
  double d = c;
  if (x0 > 0.0) {
    const double f0 = m.Force(x0);
    const double slope0 = 0.5 * m.alpha * f0 / x0 + f0 * m.mu / h;
    d = (c - compliance * f0) / (1.0 + compliance * slope0);
  }
  const double scale = std::max(std::fabs(x0), std::fabs(c)) + 1e-300;
  return SolveMonotone([&](double dd) { return NormalForce(m, x0, v0, dd, h); }, c, compliance, d,
                       scale, force);
}

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
  double dx = 0.0;
  double aux = 0.0;
  double energy_j = 0.0;
};

NormalStep DiscreteGradientNormal(const ImpactModel& m, const ContactStepInput& in, double c) {
  NormalStep s;
  s.dx = SolveNormal(m, in.x0, c, in.normal_compliance, in.h, &s.force);
  s.energy_j = m.Potential(in.x0 + s.dx);
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

double FrictionResidual(const FrictionModel& fm, double z0, double u, double a, double coupling,
                        double h, double fn, double noise) {
  const BristleStep b = AdvanceBristle(fm, z0, u, h, fn);
  return u - a + coupling * FrictionStepForce(fm, z0, b, u, h, noise);
}

// Root of R(u) = u - a + coupling·f(u): continuous, → ±∞, but not monotone where the Stribeck
// curve falls. Bracket by expansion, then secant steps safeguarded by bisection.
double SolveFriction(const FrictionModel& fm, double z0, double a, double coupling, double h,
                     double fn, double noise) {
  if (!(coupling > 0.0)) return a;
  double r_a = FrictionResidual(fm, z0, a, a, coupling, h, fn, noise);
  if (r_a == 0.0) return a;
  {
    // Fast path: secant iteration started with the slope of the elastic (sticking) regime. The
    // residual is nearly linear where the bristle is not saturating, so this usually converges
    // in 2–3 evaluations; if it does not, the bracketed solve below takes over.
    double u_prev = a, r_prev = r_a;
    double u = a - r_a / (1.0 + coupling * (0.5 * fm.sigma0 + (fm.sigma1 + fm.sigma2) / h));
    for (int i = 0; i < 8; ++i) {
      const double r = FrictionResidual(fm, z0, u, a, coupling, h, fn, noise);
      if (r == 0.0) return u;
      const double step = r * (u - u_prev) / (r - r_prev);
      if (!std::isfinite(step)) break;
      u_prev = u;
      r_prev = r;
      u -= step;
      if (std::fabs(step) <= 4.0 * kEps * (std::fabs(u) + std::fabs(u_prev))) return u;
    }
  }
  double delta = 2.0 * std::fabs(r_a) + 1e-30;
  double lo = a, hi = a, r_lo = r_a, r_hi = r_a;
  bool bracketed = false;
  for (int i = 0; i < 200 && !bracketed; ++i) {
    if (r_a > 0.0) {
      lo = a - delta;
      r_lo = FrictionResidual(fm, z0, lo, a, coupling, h, fn, noise);
      bracketed = r_lo <= 0.0;
    } else {
      hi = a + delta;
      r_hi = FrictionResidual(fm, z0, hi, a, coupling, h, fn, noise);
      bracketed = r_hi >= 0.0;
    }
    delta *= 2.0;
  }
  if (!bracketed) return a;
  if (r_lo == 0.0) return lo;
  if (r_hi == 0.0) return hi;
  const double scale = std::max({std::fabs(lo), std::fabs(hi), 1e-300});
  // Illinois regula falsi: superlinear, never leaves the bracket.
  int side = 0;
  double u = lo;
  for (int iteration = 0; iteration < 200; ++iteration) {
    u = (lo * r_hi - hi * r_lo) / (r_hi - r_lo);
    if (!(u > lo && u < hi)) u = 0.5 * (lo + hi);
    const double r = FrictionResidual(fm, z0, u, a, coupling, h, fn, noise);
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
  shape_ = alpha == 1.0   ? Shape::kOne
           : alpha == 1.5 ? Shape::kThreeHalves
           : alpha == 2.0 ? Shape::kTwo
                          : Shape::kOther;
}

double ImpactModel::Potential(double x) const {
  if (x <= 0.0) return 0.0;
  return k * PowAlpha(x) * x / (alpha + 1.0);
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
}

double FrictionModel::SteadyDeflection(double v_mps, double fn) const {
  const double ratio = v_mps / v_s;
  return (mu_d * fn + (mu_s - mu_d) * fn * std::exp(-ratio * ratio)) / sigma0;
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

BristleStep AdvanceBristle(const FrictionModel& model, double z0, double du, double h, double fn) {
  BristleStep out;
  if (!(fn > 0.0)) return out;  // no normal force: no contact, the bristle is relaxed
  if (du == 0.0) {
    out.z1 = z0;
    out.mean_z = z0;
    return out;
  }
  // Work along the slip: w = z·sgn(du) so the slip is positive; the velocity is frozen at
  // du / h over the step, so dz/du = 1 - α(z) z / z_ss is an autonomous ODE in the slip.
  const double sign = du > 0.0 ? 1.0 : -1.0;
  const double total = std::fabs(du);
  const double z_ss = model.SteadyDeflection(total / h, fn);
  const double z_ba = model.c_ba * model.mu_d * fn / model.sigma0;
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
  }
  // Elasto-plastic and plastic parts: exact exponential relaxation with α frozen per piece.
  for (int i = 0; i < 64 && left > 0.0; ++i) {
    const double alpha = w < z_ss ? BristleAlpha(w, z_ss, z_ba) : 1.0;
    double piece = left;
    if (alpha < 1.0 && i < 63) piece = std::min(left, 0.25 * z_ss / (1.0 - alpha + 1e-3));
    const double r = alpha * piece / z_ss;
    double p1 = 0.0, p2 = 0.0;
    Phis(r, &p1, &p2);
    integral += piece * (piece * p2 + w * p1);
    w += (piece - alpha * w * piece / z_ss) * p1;
    left -= piece;
  }
  out.z1 = sign * w;
  out.mean_z = sign * integral / total;
  return out;
}

double FrictionStepForce(const FrictionModel& model, double z0, const BristleStep& step, double du,
                         double h, double noise_n) {
  const double dz = step.z1 - z0;
  // σ1 acts only while the bristle deflects with the slip (Dupont et al.'s passivity condition).
  const double damping = dz * du >= 0.0 ? model.sigma1 * dz / h : 0.0;
  return model.sigma0 * step.mean_z + damping + model.sigma2 * du / h + noise_n;
}

namespace {

// Normal force (one scheme's NormalStep for a given free compression change) and friction,
// coupled through the shared resonator: block Gauss–Seidel on the friction force f -> Φ(f)
// (normal solve, then friction solve), accelerated by secant steps on the fixed-point residual
// Φ(f) - f for the first iterations (strong coupling: light modes, soft bristles), plain
// Gauss–Seidel after that.
template <class NormalFn>
ContactStepOutput SolveCoupled(const FrictionModel& friction, const ContactStepInput& in,
                               const NormalFn& normal) {
  ContactStepOutput out;
  const bool friction_on = in.friction_on && in.friction_normal_n > 0.0;
  double f = friction_on ? in.friction_guess_n : 0.0;
  NormalStep ns;
  double du = in.free_du;
  const bool coupled = in.impact_on && friction_on && in.coupling > 0.0;
  double f_prev = 0.0, g_prev = 0.0;
  constexpr int kMaxIterations = 24;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    if (in.impact_on) ns = normal(in.free_dx + in.coupling * f);
    if (!friction_on) break;
    du = SolveFriction(friction, in.z0, in.free_du + in.coupling * ns.force, in.coupling, in.h,
                       in.friction_normal_n, in.noise_n);
    const BristleStep b = AdvanceBristle(friction, in.z0, du, in.h, in.friction_normal_n);
    const double f_new = FrictionStepForce(friction, in.z0, b, du, in.h, in.noise_n);
    const double g = f_new - f;
    const bool converged = std::fabs(g) <= 1e-13 * (std::fabs(f_new) + 1e-9);
    out.z1 = b.z1;
    // Always leave with the f computed from the last normal force, so that f, z1 and F belong
    // to one consistent step.
    if (!coupled || converged || iteration + 1 == kMaxIterations) {
      f = f_new;
      break;
    }
    double next = f_new;
    if (iteration > 0 && iteration < 12 && g != g_prev) {
      const double secant = f - g * (f - f_prev) / (g - g_prev);
      if (std::isfinite(secant)) next = secant;
    }
    f_prev = f;
    g_prev = g;
    f = next;
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

ContactStepOutput SolveContactStep(const ImpactModel& impact, const FrictionModel& friction,
                                   const ContactStepInput& in) {
  return SolveCoupled(friction, in,
                      [&](double c) { return DiscreteGradientNormal(impact, in, c); });
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
  const double n = std::ceil(TargetContactSamples(impact.scheme) / samples);
  return static_cast<int>(std::clamp(n, 1.0, static_cast<double>(kMaxOversample)));
}

ImpactRunResult SimulateRigidWallImpact(double mass_kg, double k, double mu, double alpha,
                                        double v_in, double sample_rate_hz, ContactScheme scheme,
                                        int oversample, double onset_phase) {
  // A value outside the enumeration runs the default; the result says which scheme ran.
  const ContactScheme used = IsContactSchemeImplemented(scheme) ? scheme : kDefaultContactScheme;
  ImpactParams params;
  params.enabled = true;
  params.scheme = used;
  params.stiffness = k;
  params.dissipation_s_per_m = mu;
  params.shape_alpha = alpha;
  params.oversample = oversample;
  ContactKernelConfig config;
  config.scheme = used;
  config.impact.Set(params);
  config.friction.enabled = false;
  config.probe_mass_kg = mass_kg;
  config.SetTiming(sample_rate_hz, ChooseContactOversample(params, mass_kg, sample_rate_hz));
  ModalState modes;  // none: a rigid, immovable body
  ProbeDynamics probe;
  probe.active = true;
  const double period = 1.0 / sample_rate_hz;
  probe.height_m = onset_phase * v_in * period;  // first touch onset_phase of a sample from now
  probe.velocity_mps = -v_in;
  SampleDrive drive;  // flat surface at height 0, no push, no sliding

  ImpactRunResult result;
  result.oversample = config.substeps;
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
    StepContactSample(config, modes, probe, drive, observe);
    if (result.separated && probe.compression_m < 0.0) break;
  }
  result.exit_velocity_mps = std::fabs(probe.velocity_mps);
  result.samples_per_contact = result.contact_time_s * sample_rate_hz;
  return result;
}

}  // namespace sas::synth
