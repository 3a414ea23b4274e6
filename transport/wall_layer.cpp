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
} // namespace

WallLayer solve_wall_layer(const WallLayerInput& in) {
  const double n = in.density;
  // tau_u: a particle's internal energy relaxes by pair conduction with its neighbours,
  // n lambda int w_H dV per unit temperature, against its heat capacity c_v.
  const double pair_rate = n * in.pair_conductance * half_space(in.dim, 0, in.heat_weight) * 2;
  const double tau_u = pair_rate > 0 ? in.heat_capacity / pair_rate : HUGE_VAL;
  WallLayer out;
  out.ell = in.energy_length > 0 ? in.energy_length
                                 : std::sqrt(std::max(in.diffusion, 1e-12) * std::min(tau_u, 1e6));
  const double ell = std::max(out.ell, 1e-3);
  const double rc = std::max(in.heat_weight.cutoff, in.friction_weight.cutoff);
  const double dh = std::max(std::min(0.02 * rc, ell / 10), 0.005 * rc);
  const double H = std::max(8 * rc, 14 * ell);
  const int N = static_cast<int>(std::ceil(H / dh));
  const double kappa_particles = in.kappa - in.kappa_pair;
  // Cell k holds h_k = (k + 1/2) dh; the unknown theta = T - T_w; a flux q = kappa g far away,
  // g = 1: the balance of each cell, inflow positive, A theta = rhs.
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(N, N);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(N);
  const double g = 1;
  const auto h_of = [&](int k) { return (k + 0.5) * dh; };
  // Exchange between cells k and l at conductance c; beyond the domain the bulk's line
  // continues (theta_{N-1} + g (h_l - h_{N-1})).
  const auto exchange = [&](int k, int l, double c) {
    A(k, k) -= c;
    if (l < N) {
      A(k, l) += c, A(l, l) -= c, A(l, k) += c;
    } else {
      A(k, N - 1) += c;
      rhs(k) -= c * g * (l - (N - 1)) * dh;
    }
  };
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
  const double a_kin = kappa_particles / (2 * ell * ell * ell) * dh * dh;
  const int kin_reach = static_cast<int>(std::ceil(14 * ell / dh));
  for (int k = 0; k < N; ++k) {
    for (int d = 1; d <= pair_reach; ++d) exchange(k, k + d, pair_scale * kernel[d]);
    for (int d = 1; d <= kin_reach; ++d) exchange(k, k + d, a_kin * std::exp(-d * dh / ell));
    // the wall: re-emission through the particles' kernel, its pair conduction, its friction
    double to_wall = kappa_particles / (2 * ell * ell) * std::exp(-h_of(k) / ell) * dh;
    if (in.thermal) {
      to_wall += n * dh * in.wall_factor * in.pair_conductance * in.wall_density *
                 half_space(in.dim, h_of(k), in.heat_weight);
      // friction along the normal, and along the wall where it is no-slip
      const double friction = in.no_slip ? half_space(in.dim, h_of(k), in.friction_weight)
                                         : half_space(in.dim, h_of(k), in.friction_weight,
                                                      particle::WallMoment::NormalSq);
      to_wall += n * dh * 0.25 * in.gamma * in.wall_density * friction;
    }
    A(k, k) -= to_wall;
  }
  const Eigen::VectorXd theta = A.partialPivLu().solve(rhs);
  // The bulk's line, fitted beyond two interaction ranges and short of the domain's end.
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int k = 0; k < N; ++k) {
    const double h = h_of(k);
    if (h < std::max(2 * rc, 4 * ell) || h > H - std::max(2 * rc, 4 * ell)) continue;
    sw += 1, sx += h, sy += theta(k), sxx += h * h, sxy += h * theta(k);
  }
  const double slope = (sw * sxy - sx * sy) / (sw * sxx - sx * sx);
  const double intercept = (sy - slope * sx) / sw;
  out.extrapolation_length = intercept / slope;
  out.conductance = in.kappa / out.extrapolation_length;
  return out;
}

} // namespace twinflow::transport
