#pragma once
// A wall of material (docs/theory.md, "Walls"): the half-space beyond the wall plane filled with
// wall particles at density rho_w, at rest, at the wall's temperature. A fluid particle at distance
// h from the plane sees the sum of its pair terms with all of them, here integrated once into
// functions of h:
//   friction and noise: Gamma(h) = gamma(Theta) G(h), G = rho_w int w_D e e^T dV, diagonal for a
//     flat wall: G_n (normal) and G_t (each tangent); the noise the sum of independent pair
//     noises, covariance 2 k Theta gamma G dt (000:(2.37) pair by pair, so the FDT holds);
//   heat: W_H(h) = f_w rho_w int w_H dV: q = kappa(theta_i, T_w) W_H (1/theta_i - 1/T_w) +
//     noise of variance 2 k kappa W_H dt (000:(2.38) pair by pair), plus the Ito drift of a
//     partner of infinite heat capacity (pair_terms.hpp, eval_wall); f_w (Particle/Walls/Heat
//     conduction) scales the wall material's heat-conduction strength against the fluid's own:
//     most of the fluid's heat flux is carried by diffusing particles, which no wall can take
//     over, so a wall that holds its temperature conducts better than the fluid;
//   repulsion: a(theta_i, T_w) F(h) along the inward normal, F = rho_w int w_C (e.n) dV, with the
//     potential a Phi(h), Phi = rho_w int rc/2 w_C^2 dV (the pair potential of docs/theory.md).

#include <functional>
#include <vector>

#include "particle/parameters.hpp"

namespace twinflow::particle {

// f(h) on [0, range], tabulated and interpolated by cubics through the four nearest nodes; 0 at
// and beyond `range`.
class WallTable {
public:
  WallTable() = default;
  WallTable(const std::function<double(double)>& f, double range, int intervals = 1024);
  double operator()(double h) const;
  double range() const { return range_; }

private:
  double range_ = 0, inv_step_ = 0;
  std::vector<double> values_;
};

// int over the wall's half-space, at distance h from its plane, of f(r) times an angular factor
// of e (the unit vector from a wall point to the particle), per unit wall density, for r < rc:
enum class WallMoment {
  Volume,    // 1
  Normal,    // e.n
  NormalSq,  // (e.n)^2
  TangentSq, // (e.t)^2, one tangent direction
};
double half_space_integral(int dim, double h, double rc, const std::function<double(double)>& f,
                           WallMoment moment);

// I_d = int_{r.n > 0} (r.n) w_D(r) (e.t)^2 d^d r for w_D = (1 - r/rc)^s: G_t / rho_w integrated
// over the distance h from the plane, in closed form (references.md, "Kinetic slip at a particle
// wall"): the wall friction per area on a fluid of density n moving along it is n rho_w gamma I_d.
double tangent_friction_moment(int dim, double cutoff, double exponent);

struct HalfSpaceWall {
  WallTable friction_normal, friction_tangent; // G_n, G_t
  WallTable heat;                              // W_H
  WallTable repulsion, repulsion_potential;    // F, Phi per unit a (empty without a force)
  double range = 0;                            // the largest of their cutoffs
};
HalfSpaceWall make_half_space_wall(const ParticleParameters& p);

} // namespace twinflow::particle
