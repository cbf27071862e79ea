// Closed forms for the Hunt–Crossley impact against a rigid wall (see the header for sources).
#include "synth/hunt_crossley_closed_form.h"

#include <cmath>

namespace sas::synth {
namespace {

// g(u) = u - ln(1 + u): the invariant of the phase-plane trajectory in the scaled velocity u = μv.
// For small |u| the difference cancels to u²/2; its series keeps full relative precision there.
double Invariant(double u) {
  if (std::fabs(u) < 1e-3) return u * u * (0.5 + u * (-1.0 / 3.0 + u * (0.25 - u * 0.2)));
  return u - std::log1p(u);
}

// φ(t) = expm1(t) - t = g(u) with t = ln(1 + u); series for small |t| as above.
double InvariantOfLog(double t) {
  if (std::fabs(t) < 1e-3) {
    return t * t * (0.5 + t * (1.0 / 6.0 + t * (1.0 / 24.0 + t / 120.0)));
  }
  return std::expm1(t) - t;
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
    const double residual = InvariantOfLog(t) - target;  // > 0: t is too negative
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

double HuntCrossleyCompressionAt(double mass_kg, double k, double mu, double alpha, double v_in,
                                 double v) {
  const double exponent = 1.0 / (alpha + 1.0);
  const double delta = v_in - v;  // >= 0 on the compression branch, up to v_in + |v_out|
  if (mu <= 0.0) {
    return std::pow(std::fmax((alpha + 1.0) * mass_kg * (v_in * v_in - v * v) / (2.0 * k), 0.0),
                    exponent);
  }
  // μΔ + ln((1 + μv)/(1 + μ v_in)) = y μ v_in + (y + ln(1 - y)) with y = μΔ / (1 + μ v_in);
  // the bracket loses every digit for small y, so use its series there.
  const double y = mu * delta / (1.0 + mu * v_in);
  double y_plus_log;
  if (y < 1e-3) {
    y_plus_log = -y * y * (0.5 + y * (1.0 / 3.0 + y * (0.25 + y * 0.2)));
  } else {
    y_plus_log = y + std::log1p(-y);
  }
  const double bracket = std::fmax(y * mu * v_in + y_plus_log, 0.0);
  return std::pow((alpha + 1.0) * mass_kg / (mu * mu * k) * bracket, exponent);
}

double HuntCrossleyContactTime(double mass_kg, double k, double mu, double alpha, double v_in) {
  const double x_max = HuntCrossleyMaxCompression(mass_kg, k, mu, alpha, v_in);
  const double beta = 1.0 / (alpha + 1.0);
  if (mu <= 0.0) {
    return 2.0 * (x_max / v_in) * std::sqrt(std::acos(-1.0)) * std::tgamma(1.0 + beta) /
           std::tgamma(0.5 + beta);
  }
  const double v_out = -HuntCrossleyRestitution(mu * v_in) * v_in;
  // dt = m dv / (k x^α (1 + μ v)) (deceleration while compressed). Near an end v_e the
  // compression behaves like |v - v_e|^(1/(α+1)), so x^α ~ |v - v_e|^(α/(α+1)); with
  // v = v_e ∓ w^(α+1) the integrand becomes smooth in w.
  static constexpr double kNodes[10] = {
      -0.9931285991850949, -0.9639719272779138, -0.9122344282513259, -0.8391169718222188,
      -0.7463319064601508, -0.6360536807265150, -0.5108670019508271, -0.3737060887154195,
      -0.2277858511416451, -0.0765265211334973};
  static constexpr double kWeights[10] = {
      0.0176140071391521, 0.0406014298003869, 0.0626720483341091, 0.0832767415767048,
      0.1019301198172404, 0.1181945319615184, 0.1316886384491766, 0.1420961093183820,
      0.1491729867929236, 0.1527533759548394};
  const double power = alpha + 1.0;
  // Integral over v in [v_end - span, v_end] (sign = +1) or [v_end, v_end + span] (sign = -1).
  const auto half = [&](double v_end, double span, double sign) {
    const double w_max = std::pow(span, 1.0 / power);
    const int panels = 64;
    double total = 0.0;
    for (int panel = 0; panel < panels; ++panel) {
      const double a = w_max * panel / panels, b = w_max * (panel + 1) / panels;
      const double mid = 0.5 * (a + b), radius = 0.5 * (b - a);
      for (int i = 0; i < 20; ++i) {
        const double node = i < 10 ? kNodes[i] : -kNodes[19 - i];
        const double weight = i < 10 ? kWeights[i] : kWeights[19 - i];
        const double w = mid + radius * node;
        const double v = v_end - sign * std::pow(w, power);
        const double x = HuntCrossleyCompressionAt(mass_kg, k, mu, alpha, v_in, v);
        const double dv_dw = power * std::pow(w, power - 1.0);
        const double integrand = mass_kg / (k * std::pow(x, alpha) * (1.0 + mu * v)) * dv_dw;
        total += weight * radius * integrand;
      }
    }
    return total;
  };
  return half(v_in, v_in, +1.0) + half(v_out, -v_out, -1.0);
}

ImpactClosedForm HuntCrossleyImpact(double mass_kg, double k, double mu, double alpha,
                                    double v_in) {
  ImpactClosedForm result;
  result.restitution = HuntCrossleyRestitution(mu * v_in);
  result.exit_speed_mps = result.restitution * v_in;
  result.max_compression_m = HuntCrossleyMaxCompression(mass_kg, k, mu, alpha, v_in);
  result.contact_time_s = HuntCrossleyContactTime(mass_kg, k, mu, alpha, v_in);
  return result;
}

}  // namespace sas::synth
