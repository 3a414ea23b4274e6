#include "particle/wall_weights.hpp"

#include <algorithm>
#include <cmath>

namespace twinflow::particle {

WallTable::WallTable(const std::function<double(double)>& f, double range, int intervals)
    : range_(range), inv_step_(intervals / range), values_(intervals + 1) {
  for (int k = 0; k <= intervals; ++k) values_[k] = f(k * range / intervals);
}

double WallTable::operator()(double h) const {
  if (!(h < range_)) return 0;
  const int last = static_cast<int>(values_.size()) - 1;
  const double x = std::max(h, 0.0) * inv_step_;
  const int k = std::clamp(static_cast<int>(x) - 1, 0, last - 3); // nodes k .. k + 3
  const double t = x - k;                                         // in [0, 3]
  // Lagrange cubic through the nodes 0, 1, 2, 3
  const double l0 = -(t - 1) * (t - 2) * (t - 3) / 6, l1 = t * (t - 2) * (t - 3) / 2;
  const double l2 = -t * (t - 1) * (t - 3) / 2, l3 = t * (t - 1) * (t - 2) / 6;
  return l0 * values_[k] + l1 * values_[k + 1] + l2 * values_[k + 2] + l3 * values_[k + 3];
}

namespace {
// The part of the sphere (circle) of radius r around the particle that lies in the wall, with
// c = h / r = cos of its half-opening angle, integrated with the moment's factor.
double angular(int dim, double c, WallMoment moment) {
  if (dim == 3) {
    switch (moment) {
    case WallMoment::Volume:
      return 2 * M_PI * (1 - c);
    case WallMoment::Normal:
      return M_PI * (1 - c * c);
    case WallMoment::NormalSq:
      return 2 * M_PI / 3 * (1 - c * c * c);
    case WallMoment::TangentSq:
      return M_PI * ((1 - c) - (1 - c * c * c) / 3);
    }
  }
  const double a = std::acos(c), s = std::sqrt(std::max(0.0, 1 - c * c));
  switch (moment) {
  case WallMoment::Volume:
    return 2 * a;
  case WallMoment::Normal:
    return 2 * s;
  case WallMoment::NormalSq:
    return a + s * c;
  case WallMoment::TangentSq:
    return a - s * c;
  }
  return 0;
}

// int_a^b g(r) dr by tanh-sinh (double exponential) quadrature: exact to ~1e-14 also with the
// endpoint singularities of these integrands (sqrt at r = h in 2D, (1 - r/rc)^n at rc).
double tanh_sinh(const std::function<double(double)>& g, double a, double b) {
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b), step = 1.0 / 32;
  double sum = 0;
  for (int k = -32 * 4; k <= 32 * 4; ++k) {
    const double t = k * step, u = 0.5 * M_PI * std::sinh(t);
    const double x = std::tanh(u), w = 0.5 * M_PI * std::cosh(t) / (std::cosh(u) * std::cosh(u));
    const double r = mid + half * x;
    if (r <= a || r >= b) continue; // the weights vanish there to double precision
    sum += w * g(r);
  }
  return sum * half * step;
}
} // namespace

double half_space_integral(int dim, double h, double rc, const std::function<double(double)>& f,
                           WallMoment moment) {
  if (h >= rc) return 0;
  return tanh_sinh(
      [&](double r) {
        const double measure = dim == 3 ? r * r : r;
        return f(r) * angular(dim, h / r, moment) * measure;
      },
      h, rc);
}

double tangent_friction_moment(int dim, double cutoff, double exponent) {
  // int_0^rc r^d w_D dr = rc^(d+1) B(d + 1, s + 1) times the angular part int (e.n) (e.t)^2
  // over the half circle (2/3) or the half sphere (pi/4)
  const double beta =
      std::tgamma(dim + 1.0) * std::tgamma(exponent + 1) / std::tgamma(dim + exponent + 2);
  return (dim == 3 ? M_PI / 4 : 2.0 / 3.0) * std::pow(cutoff, dim + 1) * beta;
}

HalfSpaceWall make_half_space_wall(const ParticleParameters& p) {
  HalfSpaceWall w;
  const double rho = p.wall_material_density();
  // rho_w scale int (1 - r/rc)^power (moment) dV, tabulated over h < rc
  const auto table = [&](const WeightParameters& weight, WallMoment moment, double power,
                         double scale = 1) {
    const auto f = [&](double r) { return std::pow(1 - r / weight.cutoff, power); };
    return WallTable(
        [&](double h) {
          return scale * rho * half_space_integral(p.dim, h, weight.cutoff, f, moment);
        },
        weight.cutoff);
  };
  w.friction_normal = table(p.dissipation, WallMoment::NormalSq, p.dissipation.exponent);
  w.friction_tangent = table(p.dissipation, WallMoment::TangentSq, p.dissipation.exponent);
  w.range = p.dissipation.cutoff;
  if (p.heat != HeatLaw::None && p.energy == EnergyModel::Dpde) {
    w.heat =
        table(p.heat_weight, WallMoment::Volume, p.heat_weight.exponent); // per unit conduction
    w.range = std::max(w.range, p.heat_weight.cutoff);
  }
  if (p.conservative != ConservativeForce::None) {
    const WeightParameters c{p.conservative_cutoff, 1.0}; // w_C = 1 - r/rc
    w.repulsion = table(c, WallMoment::Normal, 1.0);
    w.repulsion_potential = table(c, WallMoment::Volume, 2.0, 0.5 * c.cutoff);
    w.range = std::max(w.range, p.conservative_cutoff);
  }
  return w;
}

} // namespace twinflow::particle
