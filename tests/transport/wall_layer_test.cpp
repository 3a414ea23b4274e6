// The wall layer of a half-space thermal wall from the wall model alone (transport/wall_layer.hpp):
// against the exact solution of its particles' channel alone, and against an independent
// implementation for the default cavity's walls.

#include <gtest/gtest.h>

#include <cmath>

#include "transport/laws.hpp"
#include "transport/wall_layer.hpp"

using twinflow::transport::solve_wall_layer;
using twinflow::transport::WallLayerInput;

namespace {
// The default cavity's fluid and walls (cases/heated_cavity_2d.prm) at a wall of temperature T
// with fluid of density n, conductivity kappa, factor f.
WallLayerInput default_wall(double n, double T, double kappa, double f) {
  WallLayerInput in;
  in.dim = 2, in.density = n, in.temperature = T, in.kappa = kappa;
  in.kappa_pair = 0.262 * n * n; // rho^2/4 lambda int r^2 w_H d^2r, g = 1 (000:(3.25))
  in.diffusion = 0.263 * std::pow(T / 0.814, 1.36) * (4 / n);
  in.pair_conductance = 10; // kappa0 c_v^2 (seed 002's coefficient)
  in.heat_capacity = 10;
  in.heat_weight = {1, 2}, in.friction_weight = {1, 2};
  in.wall_density = 4, in.wall_factor = f;
  in.gamma = 9 / (2 * T); // sigma^2 / (2 T)
  return in;
}
} // namespace

// With the particles' channel alone (no pair terms, no friction) the layer is the conservative
// Milne problem of the exponential kernel exp(-|s|/ell) / (2 ell), whose solution is exactly
// linear, theta ~ h + ell: the extrapolation length is ell.
TEST(WallLayer, ParticlesAloneExtrapolateByTheirEnergyLength) {
  for (const double ell : {0.2, 0.7}) {
    WallLayerInput in = default_wall(4, 1, 20, 0);
    in.kappa_pair = 0, in.pair_conductance = 0, in.gamma = 0, in.energy_length = ell;
    const auto layer = solve_wall_layer(in);
    EXPECT_NEAR(layer.extrapolation_length, ell, 0.01 * ell) << ell;
  }
}

// The default walls against an independent implementation (a Python prototype with its own
// kernels and grid, extrapolated to zero spacing from dh = 0.01 and 0.005, where it converges at
// first order): a stronger wall shortens b, and from f ~ 3 on the cold dense side holds its
// layer at T_w (b < 0). The tolerance is the prototype's own remaining discretisation error.
TEST(WallLayer, DefaultWallsAgreeWithAnIndependentImplementation) {
  struct Row {
    double f, hot, cold;
  };
  for (const Row& r :
       {Row{1, 0.5601, 0.2428}, Row{10, 0.1776, -0.1963}, Row{100, -0.0764, -0.4642}}) {
    const double hot = solve_wall_layer(default_wall(2.8, 1.4, 21.0, r.f)).extrapolation_length;
    const double cold = solve_wall_layer(default_wall(6.3, 0.6, 20.4, r.f)).extrapolation_length;
    EXPECT_NEAR(hot, r.hot, 0.015) << "f " << r.f;
    EXPECT_NEAR(cold, r.cold, 0.015) << "f " << r.f;
  }
}

namespace {
// The slip layer of the default fluid's walls (sigma = 3, w_D = (1 - r)^2) at (n, T) with eta,
// the wall material at the fluid's density.
twinflow::transport::SlipLayerInput default_slip(double n, double T, double eta, bool diffuse) {
  twinflow::transport::SlipLayerInput in;
  in.dim = 2, in.density = n, in.temperature = T, in.viscosity = eta;
  in.gamma = in.wall_gamma = 9 / (2 * T); // sigma^2 / (2 T), 000:(2.37) at T_w = T
  in.wall_density = n, in.friction_weight = {1, 2}, in.diffuse = diffuse;
  return in;
}
} // namespace

// The particles' channel alone: beside a diffuse wall the Milne problem of the exponential kernel
// (slip length ell, exactly); a bounce-back wall's image moves at -u, so the odd continuation of
// the bulk's line solves the balance: no slip, exactly.
TEST(SlipLayer, ParticlesAloneSlipByTheirLengthOrNotAtAll) {
  for (const double ell : {0.2, 0.7}) {
    auto in = default_slip(4, 1, 1.5, true);
    in.gamma = in.wall_gamma = 0, in.momentum_length = ell;
    EXPECT_NEAR(twinflow::transport::solve_slip_layer(in).slip_length, ell, 0.01 * ell) << ell;
    in.diffuse = false;
    EXPECT_NEAR(twinflow::transport::solve_slip_layer(in).slip_length, 0, 0.01 * ell) << ell;
  }
}

// The channels' states against the Python prototype
// (docs/notebook/scripts/2026-11-28-slip-layer.py, its own kernels and grid, dh = 0.05; its
// elimination's band is too narrow below): the
// dilute hot fluid slips far at a diffuse wall (its eta almost all kinetic), little at a
// bounce-back one; the dense cold fluid's pair friction, missing its partners beyond the plane,
// gives both a slip of ~0.1.
TEST(SlipLayer, ChannelStatesAgreeWithThePrototype) {
  struct Row {
    double n, T, eta;
    bool diffuse;
    double b;
  };
  for (const Row& r : {Row{2.4, 1.45, 1.485, true, 0.648}, Row{2.4, 1.45, 1.512, false, 0.016},
                       Row{5.6, 0.77, 1.587, true, 0.136}, Row{5.6, 0.77, 1.559, false, 0.084}}) {
    const auto layer =
        twinflow::transport::solve_slip_layer(default_slip(r.n, r.T, r.eta, r.diffuse));
    EXPECT_NEAR(layer.slip_length, r.b, 0.01) << r.n << (r.diffuse ? " diffuse" : " bounce-back");
  }
}
