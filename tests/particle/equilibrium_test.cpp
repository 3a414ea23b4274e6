// Equilibrium of the ideal DPDE fluid (000 section 3.1): Gaussian velocities with variance kT/m,
// Gamma-law internal energies, T from the energy equation of state, p = rho k T, T_K = T_I.
// Tolerances: z = 4 standard errors from block averages, plus the stated time-step bias.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numeric>

#include "helpers.hpp"
#include "particle/run.hpp"
#include "particle/simulation.hpp"
#include "particle/theory.hpp"

using namespace twinflow::particle;
using namespace twinflow::particle::testing;

namespace {

constexpr double kZ = 4.0;      // two-sided significance ~6e-5 per check
constexpr double kBias = 0.003; // stated relative time-step bias at dt = 0.005: docs/validation.md

struct Measured {
  Estimate t_kin, t_int, pressure, u_var, kurtosis, gamma_ratio;
  double t_eos;
  double chi2_velocity, chi2_energy;
  int bins_velocity, bins_energy;
};

// chi^2 of a histogram against probabilities `expected`, each bin's error from block means.
double block_chi2(const std::vector<std::vector<double>>& block_fractions,
                  const std::vector<double>& expected, int& used) {
  const int blocks = static_cast<int>(block_fractions.size());
  double chi2 = 0;
  used = 0;
  for (std::size_t b = 0; b < expected.size(); ++b) {
    std::vector<double> f(blocks);
    for (int k = 0; k < blocks; ++k) f[k] = block_fractions[k][b];
    const double mean = std::accumulate(f.begin(), f.end(), 0.0) / blocks;
    double var = 0;
    for (const double x : f) var += (x - mean) * (x - mean);
    const double se2 = var / (blocks - 1) / blocks;
    if (expected[b] < 0.005 || se2 <= 0) continue; // sparse tails
    chi2 += (mean - expected[b]) * (mean - expected[b]) / se2;
    ++used;
  }
  return chi2;
}

template <int D, class F, class H>
Measured measure(const ParticleParameters& p, const F& friction, const H& heat) {
  using M = Model<D, NoConservative, F, H>;
  Simulation<M> sim(M{{}, friction, heat, p.mass, p.cv, 1.0}, p);
  const std::size_t n = sim.state().size();
  Measured m;
  m.t_eos = ideal_dpde_temperature(p, sim.total_energy() / n); // 000:(3.21)
  if (p.walls[0].present) m.t_eos = p.walls[0].temperature[0]; // the walls set it
  for (int s = 0; s < 2000; ++s) sim.step();                   // equilibrate (10 tau)
  const int blocks = 20, per_block = 40, every = 10;
  const int vbins = 24, ubins = 24;
  const double T = m.t_eos, vmax = 4 * std::sqrt(T),
               umax = p.cv * T * (1 + 6 / std::sqrt(p.cv + 1));
  const double umin = std::max(0.0, p.cv * T * (1 - 6 / std::sqrt(p.cv + 1)));
  std::vector<std::vector<double>> vfrac(blocks, std::vector<double>(vbins)), ufrac = vfrac;
  std::vector<double> tk, ti, pr, uv, ku, gr;
  double volume = 1;
  for (int d = 0; d < D; ++d) volume *= p.box[d];
  for (int b = 0; b < blocks; ++b) {
    for (int k = 0; k < per_block; ++k) {
      for (int s = 0; s < every; ++s) sim.step();
      const auto& st = sim.state();
      const double kin = sim.kinetic_energy();
      tk.push_back(2 * kin / (D * (n - 1.0)));
      pr.push_back(2 * kin / (D * volume)); // ideal gas: kinetic virial only
      double inv = 0, mu = 0, mu2 = 0;
      for (const double u : st.u) inv += p.cv / u, mu += u, mu2 += u * u;
      ti.push_back(n / inv);
      mu /= n;
      uv.push_back(mu2 / n - mu * mu);
      // Shape of the laws: velocity kurtosis <v^4>/<v^2>^2 = 3 (Gaussian); Gamma law of u:
      // Var(u) = (c_v/k + 1)(k T)^2 with T = T_I (000:(2.4), docs/theory.md)
      double v2 = 0, v4 = 0;
      for (int d = 0; d < D; ++d)
        for (const double v : st.v[d]) v2 += v * v, v4 += v * v * v * v;
      v2 /= D * n, v4 /= D * n;
      ku.push_back(v4 / (v2 * v2));
      gr.push_back(uv.back() / ((p.cv + 1) * ti.back() * ti.back()));
      for (int d = 0; d < D; ++d)
        for (const double v : st.v[d]) {
          const int bin = static_cast<int>((v + vmax) / (2 * vmax) * vbins);
          if (bin >= 0 && bin < vbins) vfrac[b][bin] += 1.0 / (D * n * per_block);
        }
      for (const double u : st.u) {
        const int bin = static_cast<int>((u - umin) / (umax - umin) * ubins);
        if (bin >= 0 && bin < ubins) ufrac[b][bin] += 1.0 / (n * per_block);
      }
    }
  }
  m.t_kin = block_average(tk, blocks);
  m.t_int = block_average(ti, blocks);
  m.pressure = block_average(pr, blocks);
  m.u_var = block_average(uv, blocks);
  m.kurtosis = block_average(ku, blocks);
  m.gamma_ratio = block_average(gr, blocks);
  // Expected bin probabilities: Gaussian of variance T; Gamma(shape c_v + 1, scale T) (000:(3.36))
  std::vector<double> ev(vbins), eu(ubins);
  for (int b = 0; b < vbins; ++b) {
    const double a = -vmax + 2 * vmax * b / vbins, c = a + 2 * vmax / vbins;
    ev[b] = 0.5 * (std::erf(c / std::sqrt(2 * T)) - std::erf(a / std::sqrt(2 * T)));
  }
  auto gamma_cdf = [&](double u) { // regularised lower incomplete gamma by series
    const double shape = p.cv + 1, x = u / T;
    if (x <= 0) return 0.0;
    double term = 1 / shape, sum = term;
    for (int k = 1; k < 5000 && term > sum * 1e-17; ++k) term *= x / (shape + k), sum += term;
    return std::exp(shape * std::log(x) - x - std::lgamma(shape)) * sum;
  };
  for (int b = 0; b < ubins; ++b) {
    const double a = umin + (umax - umin) * b / ubins, c = a + (umax - umin) / ubins;
    eu[b] = gamma_cdf(c) - gamma_cdf(a);
  }
  m.chi2_velocity = block_chi2(vfrac, ev, m.bins_velocity);
  m.chi2_energy = block_chi2(ufrac, eu, m.bins_energy);
  return m;
}

void expect_equilibrium(const Measured& m, const std::string& label, bool shapes = true) {
  const double T = m.t_eos;
  std::printf("%-38s T_eos %.5f T_K %.5f+-%.5f T_I %.5f+-%.5f kurt %.4f+-%.4f "
              "Var(u)/Gamma %.4f+-%.4f chi2_v %.0f/%d chi2_u %.0f/%d\n",
              label.c_str(), T, m.t_kin.mean, m.t_kin.stderr_, m.t_int.mean, m.t_int.stderr_,
              m.kurtosis.mean, m.kurtosis.stderr_, m.gamma_ratio.mean, m.gamma_ratio.stderr_,
              m.chi2_velocity, m.bins_velocity, m.chi2_energy, m.bins_energy);
  EXPECT_NEAR(m.t_kin.mean, T, kZ * m.t_kin.stderr_ + kBias * T) << label << ": T_K vs E.o.S.";
  EXPECT_NEAR(m.t_int.mean, T, kZ * m.t_int.stderr_ + kBias * T) << label << ": T_I vs E.o.S.";
  const double dtki = std::hypot(m.t_kin.stderr_, m.t_int.stderr_);
  EXPECT_NEAR(m.t_kin.mean, m.t_int.mean, kZ * dtki + kBias * T) << label << ": T_K = T_I";
  if (!shapes) return;
  EXPECT_NEAR(m.kurtosis.mean, 3.0, kZ * m.kurtosis.stderr_ + 3 * kBias)
      << label << ": Gaussian velocities";
  EXPECT_NEAR(m.gamma_ratio.mean, 1.0, kZ * m.gamma_ratio.stderr_ + kBias)
      << label << ": Gamma law";
}

template <int D>
void run_case(Integrator integrator, double cv, bool constant_gamma, bool linear,
              bool shapes = true, bool from_rest = false, double linear_noise = 2.0) {
  auto p = ideal(D, integrator, cv);
  if (from_rest) p.initial_velocities = InitialVelocities::Rest;
  const Weight wd(1, 2), wh(1, 2);
  const std::string label = std::to_string(D) + "D " + to_string(integrator) +
                            " c_v=" + std::to_string(static_cast<int>(cv)) +
                            (constant_gamma ? " gamma" : " sigma") +
                            (linear ? " linear" : " inverse");
  // Heat conduction scaled with c_v, so that internal-energy fluctuations relax in ~1.6 tau
  // (kappa rho [w_H] / c_v = 0.63 per tau), well inside the 10 tau of equilibration.
  auto go = [&](const auto& friction) {
    if (linear)
      expect_equilibrium(measure<D>(p, friction, LinearHeat{cv * 0.5, cv, linear_noise, wh}), label,
                         shapes);
    else
      expect_equilibrium(measure<D>(p, friction, InverseConstantHeat{cv * 0.5, wh}), label, shapes);
  };
  if (constant_gamma)
    go(ConstantGamma{p.gamma, cv, wd});
  else
    go(ConstantSigma{p.sigma, wd});
}

} // namespace

// A covering subset: every integrator, dimension, c_v, friction and heat form appears.
TEST(Equilibrium, IdealDpdeShardlow) {
  run_case<3>(Integrator::Shardlow, 10, false, false);
  run_case<2>(Integrator::Shardlow, 100, true, true);
}
// ec-verlet: temperatures only here. Its per-particle offset (002 Appendix A) hands each
// particle's kinetic change to its own internal energy; at small c_v that distorts the laws
// (measured: velocity kurtosis 2.925 +- 0.006 at c_v = 10 in 2D). The shape checks for it run
// under the validation label (EquilibriumShapes.EcVerlet) and are reported as not met.
// ec-verlet at c_v = 10 (2D, linear law) is not here: at dt = 0.005 it goes unstable (negative
// u) in 2-3 of 6 seeds, and on the others T_K - T_I = -0.015 +- 0.001, the offset's own stationary
// state (docs/validation.md); it runs in the validation grid. c_v = 100 is stable and unbiased.
TEST(Equilibrium, IdealDpdeEcVerletTemperatures) {
  run_case<3>(Integrator::EcVerlet, 100, true, false, false);
  run_case<2>(Integrator::EcVerlet, 100, false, true, false);
}
TEST(Equilibrium,
     DISABLED_EcVerletShapes) { // run by the validation target with --gtest_also_run_disabled_tests
  run_case<3>(Integrator::EcVerlet, 100, true, false);
  run_case<2>(Integrator::EcVerlet, 10, false, true);
}
TEST(Equilibrium, IdealDpdeEuler) {
  run_case<2>(Integrator::Euler, 10, true, false);
  run_case<3>(Integrator::Euler, 100, false, true);
}

// Half-space thermal walls (the default wall model, diffuse re-emission) at the fluid's
// temperature along x: the fluid stays in equilibrium with them, walls included in every
// average: T_K and T_I at T_w, Gaussian velocities, Gamma-law internal energies. Shardlow here;
// ec-verlet (c_v = 100) and euler measured so too (docs/validation.md), ~90 s each.
TEST(Equilibrium, HalfSpaceThermalWalls) {
  for (const auto& [integrator, cv] : {std::pair{Integrator::Shardlow, 10.0}}) {
    auto p = ideal(3, integrator, cv);
    p.box = {{8, 6, 6}};
    p.temperature = 1;
    p.walls[0] = WallPair{true, {{true, true}}, {{1.0, 1.0}}, true};
    p.initial_internal_energy = InitialInternalEnergy::Equilibrium;
    const std::string label = std::string("walls 3D ") + to_string(integrator);
    expect_equilibrium(measure<3>(p, ConstantSigma{p.sigma, Weight(1, 2)},
                                  InverseConstantHeat{cv * 0.5, Weight(1, 2)}),
                       label, integrator != Integrator::EcVerlet);
  }
}

// Unit-variance uniform pair noise (Particle/Noise = uniform) leaves the equilibrium unchanged.
// 3D shardlow at c_v = 10, where u fluctuates most, six seeds per law; errors from the scatter
// between the seeds (independent runs: one run's block errors understate it ~1.5x for Var(u)).
// Each observable agrees between the laws within z = 4 of the difference's error, and the uniform
// runs meet the theory: Gaussian velocities (kurtosis 3: each velocity sums many uniform kicks),
// the Gamma law of u, T_K = T_I = the energy equation of state's T.
TEST(Equilibrium, UniformPairNoiseAgainstGaussian) {
  constexpr int kSeeds = 6;
  const Weight wd(1, 2), wh(1, 2);
  struct Pooled {
    double mean, stderr_;
  };
  auto pool = [](const std::vector<double>& x) {
    const double mean = std::accumulate(x.begin(), x.end(), 0.0) / x.size();
    double var = 0;
    for (const double v : x) var += (v - mean) * (v - mean);
    return Pooled{mean, std::sqrt(var / (x.size() - 1) / x.size())};
  };
  std::vector<double> obs[2][4]; // [law][T_K / T_eos, T_I / T_eos, kurtosis, Var(u)/Gamma]
  for (int law = 0; law < 2; ++law)
    for (int seed = 1; seed <= kSeeds; ++seed) {
      auto p = ideal(3, Integrator::Shardlow, 10);
      p.uniform_noise = law == 1;
      p.seed = static_cast<std::uint64_t>(seed);
      const auto m = measure<3>(p, ConstantSigma{p.sigma, wd}, InverseConstantHeat{5, wh});
      const double x[4] = {m.t_kin.mean / m.t_eos, m.t_int.mean / m.t_eos, m.kurtosis.mean,
                           m.gamma_ratio.mean};
      for (int k = 0; k < 4; ++k) obs[law][k].push_back(x[k]);
    }
  const char* names[4] = {"T_K / T_eos", "T_I / T_eos", "kurtosis", "Var(u)/Gamma"};
  const double theory[4] = {1, 1, 3, 1};
  for (int k = 0; k < 4; ++k) {
    const Pooled g = pool(obs[0][k]), u = pool(obs[1][k]);
    std::printf("%-13s gaussian %.5f +- %.5f  uniform %.5f +- %.5f  theory %.5f\n", names[k],
                g.mean, g.stderr_, u.mean, u.stderr_, theory[k]);
    EXPECT_NEAR(u.mean, g.mean, kZ * std::hypot(g.stderr_, u.stderr_)) << names[k];
    const double bias = theory[k] * kBias;
    EXPECT_NEAR(u.mean, theory[k], kZ * u.stderr_ + bias) << names[k] << " (uniform) vs theory";
  }
}

// Seed 000's closed-system check: particles start at rest with theta_i = 1; the final T is the
// energy equation of state's E/N / (d/2 + c_v + 1) (000:(3.21)).
TEST(Equilibrium, ClosedSystemFromRest) {
  run_case<3>(Integrator::Shardlow, 10, true, false, true, true);
}

// Seed 002 prints the linear law's noise as (alpha^B)^2 = kappa T_i T_j; the general relation
// 000:(2.38) has 2k. The Gamma law decides: with 002's printed factor Var(u) comes out about half
// the Gamma law's (the noise is half as strong against the same friction).
TEST(Equilibrium, LinearHeatNoiseNormalisation) {
  auto p = ideal(2, Integrator::Shardlow, 10);
  const Weight wd(1, 2), wh(1, 2);
  const auto fdt = measure<2>(p, ConstantSigma{p.sigma, wd}, LinearHeat{5, 10, 2.0, wh});
  const auto printed = measure<2>(p, ConstantSigma{p.sigma, wd}, LinearHeat{5, 10, 1.0, wh});
  std::printf("linear law, Var(u)/Gamma: 2k (FDT) %.4f +- %.4f; 002 as printed %.4f +- %.4f\n",
              fdt.gamma_ratio.mean, fdt.gamma_ratio.stderr_, printed.gamma_ratio.mean,
              printed.gamma_ratio.stderr_);
  EXPECT_NEAR(fdt.gamma_ratio.mean, 1, kZ * fdt.gamma_ratio.stderr_ + kBias);
  EXPECT_GT(std::fabs(printed.gamma_ratio.mean - 1), kZ * printed.gamma_ratio.stderr_ + kBias);
}

// The whole grid (validation): both dimensions, c_v = 10 and 100, both frictions, both heat laws,
// every integrator (ec-verlet: temperatures only, see above).
TEST(Equilibrium, DISABLED_FullGrid) {
  for (const auto integrator : {Integrator::Shardlow, Integrator::Euler, Integrator::EcVerlet})
    for (const double cv : {10.0, 100.0})
      for (const bool constant_gamma : {false, true})
        for (const bool linear : {false, true}) {
          const bool shapes = integrator != Integrator::EcVerlet;
          run_case<2>(integrator, cv, constant_gamma, linear, shapes);
          run_case<3>(integrator, cv, constant_gamma, linear, shapes);
        }
}
