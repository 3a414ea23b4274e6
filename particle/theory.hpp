#pragma once
// Closed-form predictions used to check and guide particle runs.

#include "particle/parameters.hpp"

namespace twinflow::particle {

// [w^n] = integral over d-dimensional space of (1 - r/rc)^n for r < rc.
double weight_integral(int dim, double rc, double exponent);

// 001 eq. (25): T of isothermal DPD under the Euler update at finite dt (mean field).
double marsh_yeomans_temperature(const ParticleParameters& p);
// 001 eq. (28): the dt beyond which that update is unstable.
double marsh_yeomans_critical_dt(const ParticleParameters& p);
// The pair friction gamma between particles at one temperature T: constant gamma (and isothermal
// DPD's), or sigma^2 / (2 k T) for constant sigma (000:(2.37)).
double pair_friction(const ParticleParameters& p, double T);
// 000:(3.34): sqrt(B C dt*) (4 pi/3 r*^3) rho* (should be << 1); d = 2 uses pi r*^2.
double fluctuation_stability_number(const ParticleParameters& p);

// Energy equation of state of the ideal DPDE fluid: E/N = (d/2) k T + (c_v + k) T (000:(3.21)).
double ideal_dpde_temperature(const ParticleParameters& p, double energy_per_particle);

} // namespace twinflow::particle
