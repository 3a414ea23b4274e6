#pragma once
// The layer of fluid beside a half-space thermal wall, from the particle wall model alone
// (docs/theory.md, "The wall layer"): a one-dimensional mean-field balance of the energy that
// reaches the wall, steady, with a fixed heat flux far from it. Four channels:
//   - the fluid's pair conduction, nonlocal over the pair weight w_H (both partners in the fluid:
//     near the wall it loses its partners beyond the plane);
//   - the particles' own transport of energy, nonlocal over the length ell = sqrt(D tau_u) a
//     particle moves while its internal energy relaxes (tau_u = c_v / its pair conductance to its
//     neighbours): an exchange kernel A exp(-|s|/ell) with rho c D's conductivity; the wall's
//     re-emission at T_w is the same kernel reaching into the wall, held at T_w;
//   - the wall material's pair conduction, f rho_w int w_H over the half-space, on every
//     particle within rc_H of the plane;
//   - the wall's friction and noise, which pull a particle's kinetic temperature toward the
//     pair's harmonic temperature (000:(2.37)); the wall keeps half the work (physics of
//     particle/walls.tpp): 1/4 gamma W_D (T_w - T) per particle, linearised.
// The answer is the extrapolation length b: the bulk's straight profile reaches T_w at a distance
// b beyond the plane (b > 0: a Kapitza jump b dT/dn; b < 0: the layer is held at T_w and the
// bulk reaches T_w |b| inside the fluid), and the conductance kappa / b the continuum twin's
// Robin condition takes.

#include "particle/parameters.hpp"

namespace twinflow::transport {

struct WallLayerInput {
  int dim = 2;
  double density = 1;          // n of the fluid at the wall
  double temperature = 1;      // T_w (the linearisation's temperature)
  double kappa = 1;            // the fluid's whole conductivity at (n, T_w)
  double kappa_pair = 0;       // its pair part (theory's, with g)
  double diffusion = 0;        // D at (n, T_w)
  double pair_conductance = 0; // lambda: a pair's heat rate per unit temperature difference
                               // per unit w_H, linearised at T_w (kappa_ij w_H / T^2 etc.)
  double heat_capacity = 1;    // c_v per particle (internal energy)
  particle::WeightParameters heat_weight, friction_weight;
  double wall_density = 1; // rho_w
  double wall_factor = 1;  // f: Particle/Walls/Heat conduction
  double gamma = 0;        // the friction coefficient against the wall at T_w
  bool thermal = true;
  bool no_slip = true;      // the wall's friction acts along it too
  double energy_length = 0; // > 0: ell given (tests), else sqrt(D tau_u)
};

struct WallLayer {
  double extrapolation_length = 0; // b (rc)
  double conductance = 0;          // kappa / b (infinite at b = 0)
  double ell = 0;                  // the particles' energy length used
};

WallLayer solve_wall_layer(const WallLayerInput& in);

// The same balance for the tangential momentum beside a no-slip half-space wall, steady, a shear
// rate fixed far away (docs/theory.md, "The slip layer"): the fluid's pair friction, nonlocal over
// w_D (e.t)^2 with the partners beyond the plane missing; the particles' own momentum transport,
// an exchange kernel of length ell = sqrt(D_K tau_v) (D_K = 2 eta_K / (n m) from the kinetic part
// of eta, tau_v the pair friction's time) with a diffuse wall a reservoir at rest, a bounce-back
// wall a mirror (the image of the fluid moves at -u); the wall material's friction,
// n rho_w gamma_w G_t(h). The answer is the slip length b: the bulk's straight profile reaches
// u = 0 a distance b beyond the plane (Navier's condition eta du/dn = (eta / b) u).
struct SlipLayerInput {
  int dim = 2;
  double density = 1;     // n of the fluid at the wall
  double temperature = 1; // T of the fluid at the wall
  double viscosity = 1;   // the fluid's whole eta at (n, T)
  double mass = 1;
  double gamma = 0;      // the fluid's pair friction coefficient at T
  double wall_gamma = 0; // the friction against the wall material, gamma(T, T_w)
  double wall_density = 1;
  particle::WeightParameters friction_weight;
  bool diffuse = true;        // re-emission at the wall (else bounce-back)
  double momentum_length = 0; // > 0: ell given (tests), else sqrt(D_K tau_v)
};

struct SlipLayer {
  double slip_length = 0;    // b (rc)
  double viscosity_pair = 0; // the pair part of eta the layer's kernel holds
  double ell = 0;            // the particles' momentum length used
};

SlipLayer solve_slip_layer(const SlipLayerInput& in);

} // namespace twinflow::transport
