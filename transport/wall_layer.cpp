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

LayerSystem assemble_layer(const WallLayerInput& in, const LayerGrid& grid) {
  const double n = in.density, dh = grid.dh, ell = grid.ell;
  LayerSystem sys{Eigen::MatrixXd::Zero(grid.N, grid.N), Eigen::VectorXd::Zero(grid.N)};
  // Pair conduction between fluid planes s apart: n^2 lambda k(s), k(s) = -d/ds of the
  // half-space integral (the plane integral of w_H at normal distance s).
  const auto plane_kernel = [&](double s) {
    return (half_space(in.dim, std::max(s - dh / 2, 0.0), in.heat_weight) -
            half_space(in.dim, s + dh / 2, in.heat_weight)) /
           dh;
  };
  const int pair_reach = static_cast<int>(std::ceil(in.heat_weight.cutoff / dh));
  std::vector<double> kernel(pair_reach + 1);
  for (int d = 1; d <= pair_reach; ++d) kernel[d] = plane_kernel(d * dh);
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
  LayerGrid grid;
  grid.ell = std::max(out.ell, 1e-3);
  grid.rc = std::max(in.heat_weight.cutoff, in.friction_weight.cutoff);
  grid.dh = std::max(std::min(0.02 * grid.rc, grid.ell / 10), 0.005 * grid.rc);
  grid.H = std::max(8 * grid.rc, 14 * grid.ell);
  grid.N = static_cast<int>(std::ceil(grid.H / grid.dh));
  const LayerSystem sys = assemble_layer(in, grid);
  const Eigen::VectorXd theta = sys.A.partialPivLu().solve(sys.rhs);
  out.extrapolation_length = extrapolation_length(theta, grid);
  out.conductance = in.kappa / out.extrapolation_length;
  return out;
}

} // namespace twinflow::transport
