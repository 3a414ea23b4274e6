#include "particle/theory.hpp"

#include <cmath>
#include <sstream>

#include "particle/simulation.hpp"

namespace twinflow::particle {

double weight_integral(int dim, double rc, double n) {
  // 3D: 4 pi rc^3 * 2/((n+1)(n+2)(n+3)); 2D: 2 pi rc^2 / ((n+1)(n+2)) (Beta functions)
  if (dim == 3) return 4 * M_PI * rc * rc * rc * 2 / ((n + 1) * (n + 2) * (n + 3));
  return 2 * M_PI * rc * rc / ((n + 1) * (n + 2));
}

namespace {
struct MarshYeomans {
  double a1, a2, a3;
};
MarshYeomans coefficients(const ParticleParameters& p) {
  const double rc = p.dissipation.cutoff, n = p.dissipation.exponent, d = p.dim, m = p.mass;
  const double sigma2 = 2 * p.temperature * p.gamma;                   // sigma^2 = 2 k T gamma
  const double a1 = p.gamma * weight_integral(p.dim, rc, n) / (m * d); // 001:(22)
  const double a2 = 2 * p.gamma * p.gamma * weight_integral(p.dim, rc, 2 * n) / (m * m * d);
  const double a3 = sigma2 * weight_integral(p.dim, rc, n) / d; // [w_R^2] = [w_D]
  return {a1, a2, a3};
}
} // namespace

double marsh_yeomans_temperature(const ParticleParameters& p) {
  const auto c = coefficients(p);
  // 001:(25): m k T = A3 / (A1 (2 - A1 n dt) - A2 dt)
  return c.a3 / (c.a1 * (2 - c.a1 * p.density * p.dt) - c.a2 * p.dt) / p.mass;
}

double marsh_yeomans_critical_dt(const ParticleParameters& p) {
  const auto c = coefficients(p);
  return 2 * c.a1 / (p.density * c.a1 * c.a1 + c.a2); // 001:(28)
}

double pair_friction(const ParticleParameters& p, double T) {
  return p.energy == EnergyModel::Isothermal || p.friction == Friction::ConstantGamma
             ? p.gamma
             : p.sigma * p.sigma / (2 * T); // 000:(2.37)
}

double fluctuation_stability_number(const ParticleParameters& p) {
  const double T = p.temperature;
  const double zeta0 = pair_friction(p, T);
  double l0 = p.kappa0; // 000's L_0^(q): lambda_ij = L0 / (theta_i theta_j)
  if (p.heat == HeatLaw::Inverse && p.heat_coefficient == HeatCoefficient::Seed002)
    l0 = p.kappa0 * p.cv * p.cv * T * T;
  if (p.heat == HeatLaw::Linear) l0 = p.cv * p.kappa0 * T * T;
  const double b = 1 / p.cv;                             // 000:(3.31)
  const double c = p.mass * l0 / (zeta0 * p.cv * T * T); // 000:(3.32)
  const double l = std::sqrt(2 * p.mass * T) / zeta0;    // 000 section 3.1 length unit
  const double r = p.heat_weight.cutoff / l, dt = p.dt * zeta0 / p.mass;
  const double rho = p.density * std::pow(l, p.dim);
  const double volume = p.dim == 3 ? 4 * M_PI / 3 * r * r * r : M_PI * r * r;
  return std::sqrt(b * c * dt) * volume * rho; // 000:(3.34)
}

double ideal_dpde_temperature(const ParticleParameters& p, double e) {
  return e / (0.5 * p.dim + p.cv + 1); // 000:(3.21) for general d
}

std::string stability_hint(const ParticleParameters& p) {
  std::ostringstream s;
  if (p.energy == EnergyModel::Isothermal) {
    s << "Stability: 001 eq. (28) gives dt_c = " << marsh_yeomans_critical_dt(p)
      << " for this case (dt = " << p.dt << ").";
  } else {
    s << "Stability: 000:(3.34) gives sqrt(B C dt*) (4 pi/3) r*^3 rho* = "
      << fluctuation_stability_number(p)
      << " (should be << 1); lower dt, raise c_v or lower the heat-conduction strength.";
  }
  return s.str();
}

} // namespace twinflow::particle
