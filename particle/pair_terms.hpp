#pragma once
// The physics of one pair, as small value types with their parameters reduced once per run.
// An absent term is an empty type with `active = false`; `if constexpr` removes it from the loop.
// Notation and equations: shared/docs/physics.md; k = 1.

#include <Random123/philox.h>

#include <cmath>
#include <cstdint>

namespace twinflow::particle {

// w(r) = (1 - r/rc)^n and its square root, without pow for the common exponents.
struct Weight {
  double rc = 1, inv_rc = 1, n = 1;
  int kind = 0; // 0: general, 1: n = 0.5, 2: n = 1, 3: n = 2
  Weight() = default;
  Weight(double cutoff, double exponent) : rc(cutoff), inv_rc(1 / cutoff), n(exponent) {
    kind = exponent == 0.5 ? 1 : exponent == 1 ? 2 : exponent == 2 ? 3 : 0;
  }
  // w and sqrt(w) at distance r < rc.
  void eval(double r, double& w, double& sqrt_w) const {
    const double x = 1 - r * inv_rc;
    switch (kind) { // one kind per run: a perfectly predicted branch
    case 1:
      sqrt_w = std::sqrt(std::sqrt(x)), w = sqrt_w * sqrt_w;
      break;
    case 2:
      sqrt_w = std::sqrt(x), w = x;
      break;
    case 3:
      sqrt_w = x, w = x * x;
      break;
    default:
      w = std::pow(x, n), sqrt_w = std::pow(x, 0.5 * n);
    }
  }
};

// Gaussian pair noise from Philox4x32-10 keyed by (seed, step, stream) with counter
// (min id, max id): xi_ij = xi_ji and zeta_ij = -zeta_ji whoever computes the pair.
class PairNoise {
public:
  enum Stream : std::uint32_t { Pair = 0, Initial = 1, Wall = 2 };
  PairNoise(std::uint64_t seed, std::uint64_t step, Stream stream)
      : key_{{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)}},
        step_lo_(static_cast<std::uint32_t>(step)),
        step_hi_(static_cast<std::uint32_t>((step >> 32) & 0xffff) | (stream << 16)) {}

  // xi (symmetric) and zeta (antisymmetric, sign taken from i's side).
  void gaussians(std::uint32_t id_i, std::uint32_t id_j, double& xi, double& zeta) const {
    const bool i_first = id_i < id_j;
    r123::Philox4x32::ctr_type c = {
        {i_first ? id_i : id_j, i_first ? id_j : id_i, step_lo_, step_hi_}};
    const auto r = r123::Philox4x32()(c, key_);
    box_muller(r[0], r[1], xi, zeta);
    if (!i_first) zeta = -zeta;
  }

  // Two independent standard Gaussians for particle `id` (initial velocities and the like).
  void particle_gaussians(std::uint32_t id, std::uint32_t index, double& g1, double& g2) const {
    r123::Philox4x32::ctr_type c = {{id, index, step_lo_, step_hi_}};
    const auto r = r123::Philox4x32()(c, key_);
    box_muller(r[0], r[1], g1, g2);
  }

private:
  static void box_muller(std::uint32_t a, std::uint32_t b, double& g1, double& g2) {
    constexpr double two_m32 = 2.3283064365386963e-10; // 2^-32
    const double u1 = (a + 0.5) * two_m32;             // in (0, 1)
    const double u2 = b * two_m32;
    const double radius = std::sqrt(-2 * std::log(u1));
    const double angle = 6.283185307179586 * u2;
    g1 = radius * std::cos(angle);
    g2 = radius * std::sin(angle);
  }
  r123::Philox4x32::key_type key_;
  std::uint32_t step_lo_, step_hi_;
};

// ---- conservative force F^C = a_ij w_C e_ij, phi = a_ij rc/2 (1 - r/rc)^2 (physics.md)
struct NoConservative {
  static constexpr bool active = false;
};
struct ConstantRepulsion {
  static constexpr bool active = true;
  double a0, rc, inv_rc;
  // Force along e_ij and pair potential at distance r < rc.
  void eval(double r, double, double, double& f, double& phi) const {
    const double x = 1 - r * inv_rc;
    f = a0 * x; // 002:(3)
    phi = 0.5 * a0 * rc * x * x;
  }
};
struct TemperatureRepulsion {
  static constexpr bool active = true;
  double a0, rc, inv_rc, inv_2tref;
  void eval(double r, double th_i, double th_j, double& f, double& phi) const {
    const double a = a0 * (th_i + th_j) * inv_2tref; // a^T_ij = a0 (T_i + T_j)/(2 T-bar), 002 II.C
    const double x = 1 - r * inv_rc;
    f = a * x;
    phi = 0.5 * a * rc * x * x;
  }
};

// ---- dissipative and random forces, F^D = -gamma_ij w_D (e.v) e, F^R = sigma_ij w_R xi e/sqrt(dt)
// gamma(Theta) and sigma(Theta) at the pair's harmonic-mean temperature Theta.
struct ConstantSigma {
  static constexpr bool isothermal = false;
  double sigma;
  Weight w;
  double gamma(double theta) const { return sigma * sigma / (2 * theta); } // 000:(2.37)
  double sigma_of(double) const { return sigma; }
  // Friction of the Ito (pre-point) update: sigma does not depend on u, no drift correction.
  double ito_gamma(double th_i, double th_j) const { return gamma(harmonic(th_i, th_j)); }
  static double harmonic(double a, double b) { return 2 * a * b / (a + b); } // Theta_ij, 003
};
struct ConstantGamma {
  static constexpr bool isothermal = false;
  double gamma_, cv;
  Weight w;
  double gamma(double) const { return gamma_; }
  double sigma_of(double theta) const { return std::sqrt(2 * theta * gamma_); } // 000:(2.37)
  // 003:(18): xi = gamma [1 + k/2 (d/du_i + d/du_j) Theta_ij], dTheta/du_i = 2 th_j^2/(c_v
  // (th_i+th_j)^2)
  double ito_gamma(double th_i, double th_j) const {
    const double s = th_i + th_j;
    return gamma_ * (1 + (th_i * th_i + th_j * th_j) / (cv * s * s));
  }
  static double harmonic(double a, double b) { return 2 * a * b / (a + b); }
};
struct IsothermalFriction { // seed 001: fixed T in the FDT, no internal energy
  static constexpr bool isothermal = true;
  double gamma_, sigma;
  Weight w;
  double gamma(double) const { return gamma_; }
  double sigma_of(double) const { return sigma; }
  double ito_gamma(double, double) const { return gamma_; }
  static double harmonic(double, double) { return 1; }
};

// ---- heat conduction q_ij = rate + amplitude zeta/sqrt(dt) (heat into i; physics.md)
struct NoHeat {
  static constexpr bool active = false;
};
struct InverseConstantHeat {
  static constexpr bool active = true;
  double kappa0;
  Weight w;
  // rate includes the Ito drift (zero here); amplitude^2 = 2 k kappa_ij w_H, 000:(2.38)
  void eval(double r, double th_i, double th_j, double& rate, double& amplitude) const {
    double wh, sqrt_wh;
    w.eval(r, wh, sqrt_wh);
    rate = kappa0 * wh * (1 / th_i - 1 / th_j); // 002:(7)
    amplitude = std::sqrt(2 * kappa0) * sqrt_wh;
  }
};
struct InverseSeed002Heat {
  static constexpr bool active = true;
  double kappa0, cv;
  Weight w;
  void eval(double r, double th_i, double th_j, double& rate, double& amplitude) const {
    double wh, sqrt_wh;
    w.eval(r, wh, sqrt_wh);
    const double s = th_i + th_j;
    const double kappa =
        kappa0 * cv * cv * s * s * 0.25;       // kappa^A_ij = kappa0 c_v^2 (T_i+T_j)^2/4k, 002 II.B
    rate = kappa * wh * (1 / th_i - 1 / th_j); // 002:(7); drift (d_i - d_j) Lambda^2 = 0
    amplitude = std::sqrt(2 * kappa) * sqrt_wh; // (alpha^A)^2 = 2 k kappa^A, 002 II.B
  }
};
struct LinearHeat {
  static constexpr bool active = true;
  double kappa, cv,
      noise_factor; // kappa_ij = c_v kappa0; noise_factor 2 (FDT) or 1 (002 as printed)
  Weight w;
  void eval(double r, double th_i, double th_j, double& rate, double& amplitude) const {
    double wh, sqrt_wh;
    w.eval(r, wh, sqrt_wh);
    const double dt = th_j - th_i;
    // 002:(8) plus the Ito drift 1/2 (d/du_i - d/du_j) Lambda^2 = k kappa w_H (th_j - th_i)/c_v
    rate = kappa * wh * dt * (1 + (noise_factor * 0.5) / cv);
    amplitude = std::sqrt(noise_factor * kappa * th_i * th_j) * sqrt_wh; // 000:(2.38)
  }
};

} // namespace twinflow::particle
