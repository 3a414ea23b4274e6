#pragma once
// Theory estimates of the DPDE fluid's transport coefficients at density rho and temperature T
// (docs/theory.md, "Transport coefficients"; seed 002 sections III.D-E; seed 000 section 3.1).

#include <string>
#include <vector>

#include "io/json.hpp"
#include "particle/parameters.hpp"

namespace twinflow::transport {

// g(r) on [0, rc_max]: tabulated (from a particle run's rdf.csv) or ideal (g = 1).
class PairDistribution {
public:
  static PairDistribution ideal() { return {}; }
  static PairDistribution from_csv(const std::string& rdf_csv); // "r,g" rows
  double operator()(double r) const;
  bool is_ideal() const { return r_.empty(); }

private:
  std::vector<double> r_, g_;
};

struct Estimates {
  double temperature = 1, density = 3;
  double collision_time = 0;        // tau_c, 002:(17)
  double diffusion = 0;             // D = k T tau_c / m, 002:(25)
  double viscosity_kinetic = 0;     // rho m D / 2
  double viscosity_dissipative = 0; // gamma rho^2/(2d(d+2)) int r^2 g w_D
  double viscosity = 0;
  double conductivity_diffusion = 0;  // rho c_v D, 002:(21)
  double conductivity_conduction = 0; // rho^2/(2d) int r^2 g lambda_eff (000:(3.25))
  double conductivity = 0;
  double conductivity_002_eq22 = 0;  // 002's printed conduction integral (1 - h^2/rc^2)
  double i1_002 = 0, i2 = 0, i3 = 0; // 002:(14), (17), (26) (3D)
  double expansion = 0;              // alpha, ideal gas 1/T (000:(4.2))
  double heat_capacity_v = 0, heat_capacity_p = 0; // per particle, c_v + k + (d/2) k; c_p + k
  double kinematic_viscosity = 0, diffusivity = 0; // nu = eta/(rho m), chi = kappa/(rho c_p)
  double prandtl = 0, schmidt = 0;
  double prandtl_002 = 0; // 002's convention: Pr = mu c_v / kappa_eq22 (C_P ~ c_v)
  io::Json json() const;
};

// lambda_eff: a pair's heat rate per unit temperature difference per unit w_H, linearised at
// equal temperatures T (docs/theory.md, "Heat conduction between particles"); 0 without heat.
double pair_conductance(const particle::ParticleParameters& p, double T);

Estimates estimate(const particle::ParticleParameters& p, double temperature,
                   const PairDistribution& g);

// Ra = g alpha dT H^3 / (nu chi).
double rayleigh(const Estimates& e, double gravity, double delta_t, double height);

// A convection scene's dimensionless numbers from the estimates at the mean wall temperature
// (docs/theory.md, "What a convection scene costs"): stratification g H / c^2, dT/T, Ra, Pr and a
// free-fall Mach number. Null when the scene has no gravity or no pair of thermal walls at
// different temperatures. max_speed > 0 adds the Mach number of that measured speed.
io::Json convection_numbers(const particle::ParticleParameters& p, double max_speed = 0);

} // namespace twinflow::transport
