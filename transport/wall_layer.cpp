#include "transport/wall_layer.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

#include "particle/wall_weights.hpp"

namespace twinflow::transport {

namespace {
// int over a half-space at distance h of w(r) = (1 - r/rc)^e, per unit density (wall_weights.hpp).
double half_space(int dim, double h, const particle::WeightParameters& w,
                  particle::WallMoment moment = particle::WallMoment::Volume) {
  return particle::half_space_integral(
      dim, h, w.cutoff, [&](double r) { return std::pow(1 - r / w.cutoff, w.exponent); }, moment);
}

// Cells of width dh out to H from the wall; cell k holds h_k = (k + 1/2) dh.
struct LayerGrid {
  double ell, rc, dh, H;
  int N;
  double h(int k) const { return (k + 0.5) * dh; }
};

// The balance of each cell for theta = T - T_w, inflow positive: A theta = rhs, driven by a flux
// q = kappa g far away, g = 1.
struct LayerSystem {
  Eigen::MatrixXd A;
  Eigen::VectorXd rhs;
  // Exchange between cells k and l at conductance c; beyond the domain the bulk's line
  // continues (theta_{N-1} + g (h_l - h_{N-1})).
  void exchange(int k, int l, double c, const LayerGrid& grid) {
    const int N = grid.N;
    A(k, k) -= c;
    if (l < N) {
      A(k, l) += c, A(l, l) -= c, A(l, k) += c;
    } else {
      A(k, N - 1) += c;
      rhs(k) -= c * (l - (N - 1)) * grid.dh;
    }
  }
};

// The wall's share of cell k: re-emission through the particles' kernel, the wall's pair
// conduction, its friction (along the normal, and along the wall where it is no-slip).
double to_wall(const WallLayerInput& in, const LayerGrid& grid, int k) {
  const double n = in.density, h = grid.h(k), ell = grid.ell;
  double c = (in.kappa - in.kappa_pair) / (2 * ell * ell) * std::exp(-h / ell) * grid.dh;
  if (!in.thermal) return c;
  c += n * grid.dh * in.wall_factor * in.pair_conductance * in.wall_density *
       half_space(in.dim, h, in.heat_weight);
  const double friction =
      in.no_slip ? half_space(in.dim, h, in.friction_weight)
                 : half_space(in.dim, h, in.friction_weight, particle::WallMoment::NormalSq);
  return c + n * grid.dh * 0.25 * in.gamma * in.wall_density * friction;
}

// The pair exchange between fluid planes s = d dh apart, per unit of the pair's coefficient:
// k(s) = -d/ds of the half-space integral (the plane integral of w times the moment at normal
// distance s); index d = 1 ... rc / dh.
std::vector<double> plane_kernel(int dim, const particle::WeightParameters& w,
                                 particle::WallMoment moment, double dh) {
  const int reach = static_cast<int>(std::ceil(w.cutoff / dh));
  std::vector<double> kernel(reach + 1);
  for (int d = 1; d <= reach; ++d)
    kernel[d] = (half_space(dim, std::max(d * dh - dh / 2, 0.0), w, moment) -
                 half_space(dim, d * dh + dh / 2, w, moment)) /
                dh;
  return kernel;
}

LayerSystem assemble_layer(const WallLayerInput& in, const LayerGrid& grid) {
  const double n = in.density, dh = grid.dh, ell = grid.ell;
  LayerSystem sys{Eigen::MatrixXd::Zero(grid.N, grid.N), Eigen::VectorXd::Zero(grid.N)};
  // Pair conduction between fluid planes s apart: n^2 lambda k(s).
  const std::vector<double> kernel =
      plane_kernel(in.dim, in.heat_weight, particle::WallMoment::Volume, dh);
  const int pair_reach = static_cast<int>(kernel.size()) - 1;
  const double pair_scale = n * n * in.pair_conductance * dh * dh;
  // The particles' transport: A exp(-s/ell), A = kappa_particles / (2 ell^3) (its second moment
  // gives back rho c D's conductivity).
  const double a_kin = (in.kappa - in.kappa_pair) / (2 * ell * ell * ell) * dh * dh;
  const int kin_reach = static_cast<int>(std::ceil(14 * ell / dh));
  for (int k = 0; k < grid.N; ++k) {
    for (int d = 1; d <= pair_reach; ++d) sys.exchange(k, k + d, pair_scale * kernel[d], grid);
    for (int d = 1; d <= kin_reach; ++d)
      sys.exchange(k, k + d, a_kin * std::exp(-d * dh / ell), grid);
    sys.A(k, k) -= to_wall(in, grid, k);
  }
  return sys;
}

// The bulk's line, fitted beyond two interaction ranges and short of the domain's end: its
// extrapolation length intercept / slope.
double extrapolation_length(const Eigen::VectorXd& theta, const LayerGrid& grid) {
  const double margin = std::max(2 * grid.rc, 4 * grid.ell);
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int k = 0; k < grid.N; ++k) {
    const double h = grid.h(k);
    if (h < margin || h > grid.H - margin) continue;
    sw += 1, sx += h, sy += theta(k), sxx += h * h, sxy += h * theta(k);
  }
  const double slope = (sw * sxy - sx * sy) / (sw * sxx - sx * sx);
  const double intercept = (sy - slope * sx) / sw;
  return intercept / slope;
}

LayerGrid layer_grid(double ell, double rc) {
  LayerGrid grid;
  grid.ell = std::max(ell, 1e-3);
  grid.rc = rc;
  grid.dh = std::max(std::min(0.02 * grid.rc, grid.ell / 10), 0.005 * grid.rc);
  grid.H = std::max(8 * grid.rc, 14 * grid.ell);
  grid.N = static_cast<int>(std::ceil(grid.H / grid.dh));
  return grid;
}

// The momentum balance of each cell for u, the far shear rate 1: the fluid's pair friction
// (kernel over w_D (e.t)^2), the particles' exchange kernel A exp(-s/ell) with A = eta_K /
// (2 ell^3), the wall's share of each cell.
LayerSystem assemble_slip_layer(const SlipLayerInput& in, const LayerGrid& grid, double pair_scale,
                                double eta_kinetic) {
  const double n = in.density, dh = grid.dh, ell = grid.ell;
  LayerSystem sys{Eigen::MatrixXd::Zero(grid.N, grid.N), Eigen::VectorXd::Zero(grid.N)};
  const std::vector<double> kernel =
      plane_kernel(in.dim, in.friction_weight, particle::WallMoment::TangentSq, dh);
  const double a_kin = eta_kinetic / (2 * ell * ell * ell) * dh * dh;
  const int kin_reach = static_cast<int>(std::ceil(14 * ell / dh));
  for (int k = 0; k < grid.N; ++k) {
    for (std::size_t d = 1; d < kernel.size(); ++d)
      sys.exchange(k, k + static_cast<int>(d), pair_scale * kernel[d] * dh * dh, grid);
    for (int d = 1; d <= kin_reach; ++d)
      sys.exchange(k, k + d, a_kin * std::exp(-d * dh / ell), grid);
    const double h = grid.h(k);
    if (in.diffuse) // the kernel's reach beyond the plane: carriers re-emitted at rest
      sys.A(k, k) -= eta_kinetic / (2 * ell * ell) * std::exp(-h / ell) * dh;
    else // bounce-back: the carriers from cell l come back as its image, at -u_l
      for (int l = 0; l < grid.N; ++l) {
        const double c = a_kin * std::exp(-(h + grid.h(l)) / ell);
        sys.A(k, k) -= c, sys.A(k, l) -= c;
      }
    sys.A(k, k) -= n * dh * in.wall_density * in.wall_gamma *
                   half_space(in.dim, h, in.friction_weight, particle::WallMoment::TangentSq);
  }
  return sys;
}

} // namespace

WallLayer solve_wall_layer(const WallLayerInput& in) {
  // tau_u: a particle's internal energy relaxes by pair conduction with its neighbours,
  // n lambda int w_H dV per unit temperature, against its heat capacity c_v.
  const double pair_rate =
      in.density * in.pair_conductance * half_space(in.dim, 0, in.heat_weight) * 2;
  const double tau_u = pair_rate > 0 ? in.heat_capacity / pair_rate : HUGE_VAL;
  WallLayer out;
  out.ell = in.energy_length > 0 ? in.energy_length
                                 : std::sqrt(std::max(in.diffusion, 1e-12) * std::min(tau_u, 1e6));
  const LayerGrid grid =
      layer_grid(out.ell, std::max(in.heat_weight.cutoff, in.friction_weight.cutoff));
  const LayerSystem sys = assemble_layer(in, grid);
  const Eigen::VectorXd theta = sys.A.partialPivLu().solve(sys.rhs);
  out.extrapolation_length = extrapolation_length(theta, grid);
  out.conductance = in.kappa / out.extrapolation_length;
  return out;
}

SlipLayer solve_slip_layer(const SlipLayerInput& in) {
  const double n = in.density, m = in.mass, dh = 0.005 * in.friction_weight.cutoff;
  // The bulk pair viscosity of the kernel: n^2 gamma int_0^rc s^2 k_t(s) ds (000:(3.26) with g = 1)
  const std::vector<double> kernel =
      plane_kernel(in.dim, in.friction_weight, particle::WallMoment::TangentSq, dh);
  double moment = 0;
  for (std::size_t d = 1; d < kernel.size(); ++d) moment += kernel[d] * std::pow(d * dh, 2) * dh;
  // A particle's friction rate per velocity component and its mean-field D = T / (m zeta)
  // (002:(17)); the kinetic part is never below what that D carries, eta_K >= n m D / 2
  // (002:(26)): where the mean field's pair part would exceed eta (a dense cold wall) it is
  // scaled down to the rest.
  const double zeta = n * in.gamma * 2 *
                      half_space(in.dim, 0, in.friction_weight, particle::WallMoment::TangentSq) /
                      m;
  const double eta_kinetic_floor = zeta > 0 ? n * in.temperature / (2 * zeta) : 0.0;
  const double eta_pair_mean_field = n * n * in.gamma * moment;
  const double eta_pair = std::clamp(in.viscosity - eta_kinetic_floor, 0.0, eta_pair_mean_field);
  const double eta_kinetic = in.viscosity - eta_pair;
  SlipLayer out;
  out.viscosity_pair = eta_pair;
  // eta_K = n m D_K / 2 (002:(26)); the momentum a particle carries relaxes in tau_v = 1 / zeta
  out.ell = in.momentum_length > 0 ? in.momentum_length
                                   : std::sqrt(2 * eta_kinetic / (n * m) / std::max(zeta, 1e-12));
  const LayerGrid grid = layer_grid(out.ell, in.friction_weight.cutoff);
  const double pair_scale =
      eta_pair_mean_field > 0 ? n * n * in.gamma * eta_pair / eta_pair_mean_field : 0.0;
  const LayerSystem sys = assemble_slip_layer(in, grid, pair_scale, eta_kinetic);
  const Eigen::VectorXd u = sys.A.partialPivLu().solve(sys.rhs);
  out.slip_length = extrapolation_length(u, grid);
  return out;
}

} // namespace twinflow::transport
