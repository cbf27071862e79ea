#pragma once
// Closed-form results for a point mass m hitting a rigid wall through a Hunt–Crossley contact
// f = -k x^α - λ x^α ẋ (x > 0). Used as test oracles and by the `impact` calibration command.
// Sources: Hunt & Crossley, "Coefficient of restitution interpreted as damping in vibroimpact",
// J. Appl. Mech. 42(2), 1975; closed forms via the Lambert W function as in Papetti, Avanzini &
// Rocchesso, IEEE TASLP 19(7), 2011; phase-plane trajectory from Avanzini & Rocchesso,
// "Modeling collision sounds: non-linear contact force", DAFx 2001. μ = λ / k.

namespace sas::synth {

struct ImpactClosedForm {
  double restitution = 0.0;        // e = |v_out| / v_in, depends only on μ·v_in
  double exit_speed_mps = 0.0;     // |v_out|
  double max_compression_m = 0.0;  // x at v = 0
  double contact_time_s = 0.0;     // first touch to separation
};

// Coefficient of restitution for u_in = μ·v_in >= 0. Solves u_out - ln(1 + u_out) = u_in -
// ln(1 + u_in) on u_out ∈ (-1, 0) with a bracketed Newton iteration; avoids Lambert W near its
// branch point, where it is ill-conditioned.
double HuntCrossleyRestitution(double mu_times_v_in);

// Maximum compression for mass_kg, stiffness k (N/m^α), μ (s/m), shape α, entry speed v_in > 0.
double HuntCrossleyMaxCompression(double mass_kg, double k, double mu, double alpha, double v_in);

// Compression along the phase-plane trajectory at velocity v (v_out <= v <= v_in).
double HuntCrossleyCompressionAt(double mass_kg, double k, double mu, double alpha, double v_in,
                                 double v);

// Contact time. λ = 0: the Gamma-function closed form; λ > 0: the 1-D quadrature
// t_c = ∫ m dv / (x(v)^α (k + λ v)) from v_out to v_in, with the endpoint singularities (x -> 0)
// removed by the substitution v = v_end ∓ w^(α+1) and Gauss–Legendre on each half.
double HuntCrossleyContactTime(double mass_kg, double k, double mu, double alpha, double v_in);

ImpactClosedForm HuntCrossleyImpact(double mass_kg, double k, double mu, double alpha, double v_in);

}  // namespace sas::synth
