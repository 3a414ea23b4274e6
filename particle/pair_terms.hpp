#pragma once
// The physics of one pair, as small value types with their parameters reduced once per run.
// An absent term is an empty type with `active = false`; `if constexpr` removes it from the loop.
// Notation and equations: docs/theory.md; k = 1.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

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
  // The same for a block of distances, 0 at r >= rc; the loops vectorise for the common exponents.
  void eval(std::size_t count, const double* r, double* w, double* sqrt_w) const {
    auto x = [&](std::size_t k) { return std::max(1 - r[k] * inv_rc, 0.0); };
    switch (kind) {
    case 1:
      for (std::size_t k = 0; k < count; ++k)
        sqrt_w[k] = std::sqrt(std::sqrt(x(k))), w[k] = sqrt_w[k] * sqrt_w[k];
      break;
    case 2:
      for (std::size_t k = 0; k < count; ++k) sqrt_w[k] = std::sqrt(x(k)), w[k] = x(k);
      break;
    case 3:
      for (std::size_t k = 0; k < count; ++k) sqrt_w[k] = x(k), w[k] = x(k) * x(k);
      break;
    default:
      for (std::size_t k = 0; k < count; ++k)
        w[k] = std::pow(x(k), n), sqrt_w[k] = std::pow(x(k), 0.5 * n);
    }
  }
};

// Philox4x32-10 (Salmon et al., SC'11; the constants of Random123's philox.h), written out on
// plain 32/64-bit integers so that a loop over pairs vectorises. Returns output words 0 and 1;
// bitwise equal to r123::Philox4x32 (tested).
inline void philox4x32_10(std::uint32_t c0, std::uint32_t c1, std::uint32_t c2, std::uint32_t c3,
                          std::uint32_t k0, std::uint32_t k1, std::uint32_t& r0,
                          std::uint32_t& r1) {
  for (int round = 0; round < 10; ++round) {
    if (round > 0) k0 += 0x9E3779B9u, k1 += 0xBB67AE85u; // Weyl key schedule
    const std::uint64_t p0 = std::uint64_t{0xD2511F53u} * c0;
    const std::uint64_t p1 = std::uint64_t{0xCD9E8D57u} * c2;
    const auto hi0 = static_cast<std::uint32_t>(p0 >> 32), lo0 = static_cast<std::uint32_t>(p0);
    const auto hi1 = static_cast<std::uint32_t>(p1 >> 32), lo1 = static_cast<std::uint32_t>(p1);
    c0 = hi1 ^ c1 ^ k0, c1 = lo1, c2 = hi0 ^ c3 ^ k1, c3 = lo0;
  }
  r0 = c0, r1 = c1;
}

// Bit-level helpers of box_muller: they keep its loop free of branches and of conversions that
// AVX2 lacks (uint32 or int64 to double), so that it vectorises on every x86-64 level with the
// same bits.
inline double from_bits(std::uint64_t bits) {
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}
inline std::uint64_t to_bits(double d) {
  std::uint64_t bits;
  std::memcpy(&bits, &d, sizeof bits);
  return bits;
}
// yes where mask is all ones, no where it is all zeros.
inline double pick(std::uint64_t mask, double yes, double no) {
  return from_bits((to_bits(yes) & mask) | (to_bits(no) & ~mask));
}
// a, exactly, through int32 (a - 2^31 + 2^31).
inline double exact_double(std::uint32_t a) {
  return static_cast<double>(static_cast<std::int32_t>(a ^ 0x80000000u)) + 2147483648.0;
}

// Box-Muller from two 32-bit words, without libm so that it vectorises: g1, g2 independent
// standard Gaussians. Radius sqrt(-2 ln u1), u1 = (a + 1/2) 2^-32, with ln from exponent and an
// atanh series (relative error < 1e-15); angle uniform on [0, 2 pi): 29 bits give phi in
// [0, pi/4), Taylor sin/cos (error < 2e-14), 3 bits pick the octant by reflection and rotation.
inline void box_muller(std::uint32_t a, std::uint32_t b, double& g1, double& g2) {
  const std::uint64_t bits = to_bits(exact_double(a) + 0.5);
  double e = static_cast<double>(static_cast<std::int32_t>(bits >> 52) - 1023);
  double m = from_bits((bits & 0xfffffffffffffull) | 0x3ff0000000000000ull);
  // m in [sqrt(1/2), sqrt(2)) after the shift
  const std::uint64_t big = -static_cast<std::uint64_t>(m > 1.4142135623730951);
  m = pick(big, 0.5 * m, m);
  e = pick(big, e + 1, e);
  const double s = (m - 1) / (m + 1), s2 = s * s; // ln m = 2 atanh(s) = 2 (s + s^3/3 + ...)
  const double series =
      1 + s2 * (1.0 / 3 +
                s2 * (1.0 / 5 +
                      s2 * (1.0 / 7 +
                            s2 * (1.0 / 9 +
                                  s2 * (1.0 / 11 +
                                        s2 * (1.0 / 13 + s2 * (1.0 / 15 + s2 * (1.0 / 17))))))));
  const double ln_u1 = e * 0.6931471805599453 + 2 * s * series - 22.18070977791825; // - 32 ln 2
  const double radius = std::sqrt(-2 * ln_u1);
  const double phi = (static_cast<double>(static_cast<std::int32_t>(b & 0x1fffffffu)) + 0.5) *
                     (0.7853981633974483 / 536870912.0);
  const double p2 = phi * phi;
  const double sin_phi =
      phi *
      (1 + p2 * (-1.0 / 6 +
                 p2 * (1.0 / 120 +
                       p2 * (-1.0 / 5040 + p2 * (1.0 / 362880 + p2 * (-1.0 / 39916800 +
                                                                      p2 * (1.0 / 6227020800)))))));
  const double cos_phi =
      1 + p2 * (-0.5 + p2 * (1.0 / 24 +
                             p2 * (-1.0 / 720 +
                                   p2 * (1.0 / 40320 + p2 * (-1.0 / 3628800 +
                                                             p2 * (1.0 / 479001600 +
                                                                   p2 * (-1.0 / 87178291200)))))));
  const std::uint64_t octant = b >> 29;
  const std::uint64_t odd = -(octant & 1), second = -((octant >> 1) & 1);
  const double c1 = pick(odd, sin_phi, cos_phi), s1 = pick(odd, cos_phi, sin_phi);
  const double c2 = pick(second, -s1, c1), s2q = pick(second, c1, s1); // + pi/2
  const double r = from_bits(to_bits(radius) ^ ((octant & 4) << 61));  // + pi: the sign bit
  g1 = r * c2, g2 = r * s2q;
}

// Unit-variance uniform on (-sqrt 3, sqrt 3) from one 32-bit word: the noise of Groot & Warren
// (1997); the fluctuation-dissipation relations fix only the variance (000:(2.37), (2.38)).
inline double uniform_unit(std::uint32_t a) {
  return ((a + 0.5) * (2.0 / 4294967296.0) - 1) * 1.7320508075688772;
}

// Pair noise from Philox4x32-10 keyed by (seed, step, stream) with counter (min id, max id):
// xi_ij = xi_ji and zeta_ij = -zeta_ji whoever computes the pair. Standard Gaussians, or
// unit-variance uniforms (`uniform`) where the equilibrium allows it (tested).
class PairNoise {
public:
  enum Stream : std::uint32_t { Pair = 0, Initial = 1, Wall = 2 };
  PairNoise(std::uint64_t seed, std::uint64_t step, Stream stream, bool uniform = false)
      : k0_(static_cast<std::uint32_t>(seed)), k1_(static_cast<std::uint32_t>(seed >> 32)),
        step_lo_(static_cast<std::uint32_t>(step)),
        step_hi_(static_cast<std::uint32_t>((step >> 32) & 0xffff) | (stream << 16)),
        uniform_(uniform) {}

  // xi (symmetric) and zeta (antisymmetric, sign taken from i's side).
  void pair(std::uint32_t id_i, std::uint32_t id_j, double& xi, double& zeta) const {
    if (uniform_)
      draw<true>(id_i, id_j, xi, zeta);
    else
      draw<false>(id_i, id_j, xi, zeta);
  }

  // The same for a block of pairs (i[k], j[k]) of storage indices with ids `id`: vectorises.
  void pairs(std::size_t n, const std::uint32_t* i, const std::uint32_t* j, const std::uint32_t* id,
             double* xi, double* zeta) const {
    if (uniform_)
      for (std::size_t k = 0; k < n; ++k) draw<true>(id[i[k]], id[j[k]], xi[k], zeta[k]);
    else
      for (std::size_t k = 0; k < n; ++k) draw<false>(id[i[k]], id[j[k]], xi[k], zeta[k]);
  }

  // Two independent standard Gaussians for particle `id` (initial velocities and the like).
  void particle_gaussians(std::uint32_t id, std::uint32_t index, double& g1, double& g2) const {
    std::uint32_t r0, r1;
    philox4x32_10(id, index, step_lo_, step_hi_, k0_, k1_, r0, r1);
    box_muller(r0, r1, g1, g2);
  }

private:
  template <bool Uniform>
  void draw(std::uint32_t id_i, std::uint32_t id_j, double& xi, double& zeta) const {
    std::uint32_t r0, r1;
    philox4x32_10(std::min(id_i, id_j), std::max(id_i, id_j), step_lo_, step_hi_, k0_, k1_, r0, r1);
    if constexpr (Uniform)
      xi = uniform_unit(r0), zeta = uniform_unit(r1);
    else
      box_muller(r0, r1, xi, zeta);
    // zeta from the side of the lower id; the sign bit flipped, not a branch (AVX2 vectorises)
    zeta = from_bits(to_bits(zeta) ^ (static_cast<std::uint64_t>(!(id_i < id_j)) << 63));
  }
  std::uint32_t k0_, k1_, step_lo_, step_hi_;
  bool uniform_;
};

// ---- conservative force F^C = a_ij w_C e_ij, phi = a_ij rc/2 (1 - r/rc)^2 (docs/theory.md)
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
  double strength(double, double) const { return a0; } // a_ij
};
struct TemperatureRepulsion {
  static constexpr bool active = true;
  double a0, rc, inv_rc, inv_2tref;
  void eval(double r, double th_i, double th_j, double& f, double& phi) const {
    const double a = strength(th_i, th_j);
    const double x = 1 - r * inv_rc;
    f = a * x;
    phi = 0.5 * a * rc * x * x;
  }
  double strength(double th_i, double th_j) const {
    return a0 * (th_i + th_j) * inv_2tref; // a^T_ij = a0 (T_i + T_j)/(2 T-bar), 002 II.C
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
  // gamma(Theta_ij) = sigma^2 (th_i + th_j) / (4 th_i th_j), one division (000:(2.37), 003)
  double ito_gamma(double th_i, double th_j) const {
    return sigma * sigma * (th_i + th_j) / (4 * th_i * th_j);
  }
  // Against a wall partner (infinite heat capacity): the same, sigma does not depend on u.
  double wall_ito_gamma(double th_i, double th_w) const { return ito_gamma(th_i, th_w); }
  // gamma a for a factor a known before the temperatures: the constants multiplied first, so
  // the Shardlow sweep's chain of dependent operations through th is short.
  double ito_gamma_times(double th_i, double th_j, double a) const {
    return (0.25 * sigma * sigma * a) * (th_i + th_j) / (th_i * th_j); // 000:(2.37), as above
  }
  // Shardlow's implicit half: rhs / (1 + gamma' c), c = w_D dt/m, with the one division.
  double implicit_half(double rhs, double th_i, double th_j, double c) const {
    const double p = th_i * th_j; // 1 + gamma c = (p + sigma^2 c (th_i + th_j)/4) / p
    return rhs * p / std::fma(0.25 * sigma * sigma * c, th_i + th_j, p);
  }
  static double harmonic(double a, double b) { return 2 * a * b / (a + b); } // Theta_ij, 003
};
struct ConstantGamma {
  double implicit_half(double rhs, double th_i, double th_j, double c) const {
    return rhs / (1 + ito_gamma(th_i, th_j) * c);
  }
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
  // Against a wall partner of infinite heat capacity only d/du_i acts: xi = gamma [1 + k/2
  // dTheta/du_i] (003:(18) with the partner's term left out).
  double wall_ito_gamma(double th_i, double th_w) const {
    const double s = th_i + th_w;
    return gamma_ * (1 + th_w * th_w / (cv * s * s));
  }
  double ito_gamma_times(double th_i, double th_j, double a) const {
    return ito_gamma(th_i, th_j) * a;
  }
  static double harmonic(double a, double b) { return 2 * a * b / (a + b); }
};
struct IsothermalFriction { // seed 001: fixed T in the FDT, no internal energy
  double implicit_half(double rhs, double th_i, double th_j, double c) const {
    return rhs / (1 + ito_gamma(th_i, th_j) * c);
  }
  static constexpr bool isothermal = true;
  double gamma_, sigma;
  Weight w;
  double gamma(double) const { return gamma_; }
  double sigma_of(double) const { return sigma; }
  double ito_gamma(double, double) const { return gamma_; }
  double wall_ito_gamma(double, double) const { return gamma_; }
  double ito_gamma_times(double, double, double a) const { return gamma_ * a; }
  static double harmonic(double, double) { return 1; }
};

// ---- heat conduction q_ij = rate + amplitude zeta/sqrt(dt) (heat into i; docs/theory.md)
struct NoHeat {
  static constexpr bool active = false;
};
struct InverseConstantHeat {
  static constexpr bool active = true;
  double kappa0;
  Weight w;
  // rate includes the Ito drift (zero here); amplitude^2 = 2 k kappa_ij w_H, 000:(2.38); from
  // the weights w_H(r), sqrt(w_H(r)) (heat_terms: from r)
  void eval_w(double wh, double sqrt_wh, double th_i, double th_j, double& rate,
              double& amplitude) const {
    rate = kappa0 * wh * (th_j - th_i) / (th_i * th_j); // 002:(7): 1/th_i - 1/th_j
    amplitude = std::sqrt(2 * kappa0) * sqrt_wh;
  }
  // Against a wall partner of infinite heat capacity at th_w: the Ito drift is 1/2 d/du_i
  // Lambda^2 alone (docs/theory.md), zero here.
  void eval_wall(double wh, double sqrt_wh, double th_i, double th_w, double& rate,
                 double& amplitude) const {
    eval_w(wh, sqrt_wh, th_i, th_w, rate, amplitude);
  }
};
struct InverseSeed002Heat {
  static constexpr bool active = true;
  double kappa0, cv;
  Weight w;
  void eval_w(double wh, double sqrt_wh, double th_i, double th_j, double& rate,
              double& amplitude) const {
    const double s = th_i + th_j;
    const double kappa =
        kappa0 * cv * cv * s * s * 0.25; // kappa^A_ij = kappa0 c_v^2 (T_i+T_j)^2/4k, 002 II.B
    rate = kappa * wh * (th_j - th_i) / (th_i * th_j); // 002:(7); drift (d_i - d_j) Lambda^2 = 0
    amplitude = std::sqrt(2 * kappa) * sqrt_wh;        // (alpha^A)^2 = 2 k kappa^A, 002 II.B
  }
  // Against a wall partner of infinite heat capacity: 1/2 d/du_i Lambda^2 = W kappa0 c_v (th_i +
  // th_w) / 2 (Lambda^2 = 2 k kappa^A W, d kappa^A / du_i = kappa0 c_v (th_i + th_w) / 2).
  void eval_wall(double wh, double sqrt_wh, double th_i, double th_w, double& rate,
                 double& amplitude) const {
    eval_w(wh, sqrt_wh, th_i, th_w, rate, amplitude);
    rate += 0.5 * wh * kappa0 * cv * (th_i + th_w);
  }
};
struct LinearHeat {
  static constexpr bool active = true;
  double kappa, cv,
      noise_factor; // kappa_ij = c_v kappa0; noise_factor 2 (FDT) or 1 (002 as printed)
  Weight w;
  void eval_w(double wh, double sqrt_wh, double th_i, double th_j, double& rate,
              double& amplitude) const {
    const double dt = th_j - th_i;
    // 002:(8) plus the Ito drift 1/2 (d/du_i - d/du_j) Lambda^2 = k kappa w_H (th_j - th_i)/c_v
    rate = kappa * wh * dt * (1 + (noise_factor * 0.5) / cv);
    amplitude = std::sqrt(noise_factor * kappa * th_i * th_j) * sqrt_wh; // 000:(2.38)
  }
  // Against a wall partner of infinite heat capacity at th_w: the drift 1/2 d/du_i Lambda^2 =
  // (factor/2) kappa W th_w / c_v alone.
  void eval_wall(double wh, double sqrt_wh, double th_i, double th_w, double& rate,
                 double& amplitude) const {
    rate = kappa * wh * ((th_w - th_i) + (noise_factor * 0.5) * th_w / cv);
    amplitude = std::sqrt(noise_factor * kappa * th_i * th_w) * sqrt_wh; // 000:(2.38)
  }
};

// A heat law's terms at distance r: its weights w_H(r), sqrt(w_H(r)), then its eval_w.
template <class Heat>
void heat_terms(const Heat& heat, double r, double th_i, double th_j, double& rate,
                double& amplitude) {
  double wh, sqrt_wh;
  heat.w.eval(r, wh, sqrt_wh);
  heat.eval_w(wh, sqrt_wh, th_i, th_j, rate, amplitude);
}

} // namespace twinflow::particle
