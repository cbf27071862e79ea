// Closed forms for the Hunt–Crossley impact against a rigid wall (see the header for sources).
#include "synth/hunt_crossley_closed_form.h"

#include <cmath>

namespace sas::synth {
namespace {

// g(u) = u - ln(1 + u): the invariant of the phase-plane trajectory in the scaled velocity u = μv.
double Invariant(double u) {
  return u - std::log1p(u);
}

}  // namespace

double HuntCrossleyRestitution(double mu_times_v_in) {
  const double u_in = mu_times_v_in;
  if (!(u_in > 0.0)) return 1.0;  // λ = 0: elastic, energy conserved exactly
  const double target = Invariant(u_in);
  // Solve in t = ln(1 + u_out) < 0, where the invariant reads φ(t) = expm1(t) - t: this stays
  // well conditioned both near u_out = 0 (slow impacts) and near u_out = -1 (very lossy ones).
  // φ falls from +inf to 0 on (-inf, 0) and φ(t) > -1 - t, so the root lies in (-(target+1), 0).
  double lo = -(target + 1.0), hi = 0.0;
  double t = std::log1p(-u_in * std::fmax(1.0 - 2.0 / 3.0 * u_in, 0.5));  // small-u series
  if (!(t > lo && t < hi)) t = 0.5 * lo;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double residual = std::expm1(t) - t - target;  // > 0: t is too negative
    if (residual > 0.0) {
      lo = t;
    } else {
      hi = t;
    }
    double next = t - residual / std::expm1(t);
    // Safeguard: fall back to bisection when Newton leaves the bracket.
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const bool converged = std::fabs(next - t) <= 1e-15 * std::fabs(t);
    t = next;
    if (converged) break;
  }
  return -std::expm1(t) / u_in;
}

double HuntCrossleyMaxCompression(double mass_kg, double k, double mu, double alpha, double v_in) {
  const double exponent = 1.0 / (alpha + 1.0);
  if (mu <= 0.0) return std::pow((alpha + 1.0) * mass_kg * v_in * v_in / (2.0 * k), exponent);
  const double u = mu * v_in;
  // μv - ln(1 + μv) loses all digits for small μv if written naively: use log1p.
  const double bracket = u - std::log1p(u);
  return std::pow((alpha + 1.0) * mass_kg / (mu * mu * k) * bracket, exponent);
}

ImpactClosedForm HuntCrossleyImpact(double mass_kg, double k, double mu, double alpha,
                                    double v_in) {
  ImpactClosedForm result;
  result.restitution = HuntCrossleyRestitution(mu * v_in);
  result.exit_speed_mps = result.restitution * v_in;
  result.max_compression_m = HuntCrossleyMaxCompression(mass_kg, k, mu, alpha, v_in);
  return result;
}

}  // namespace sas::synth
