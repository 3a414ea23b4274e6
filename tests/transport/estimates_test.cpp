// Transport estimates against seed 002's printed coefficients and seed 000's closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../particle/helpers.hpp"
#include "particle/run.hpp"
#include "transport/estimates.hpp"

using namespace twinflow;
using namespace twinflow::transport;

namespace {
// The paper prints 2-3 digits: allow half a unit of the last digit plus 1% for our g(r)
// (a 10 tau run, 50 bins) and the paper's own numerical integration.
void expect_printed(double ours, double paper, double last_digit, const char* what) {
  EXPECT_NEAR(ours, paper, 0.5 * last_digit + 0.01 * std::fabs(paper)) << what;
}

void print(const Estimates& e, const char* g) {
  std::printf("%s: I1 %.4f I2 %.4f I3 %.4f kappa(22) %.1f kappa %.1f eta %.3f D %.4f "
              "Pr(002) %.2f Pr %.2f Sc %.2f\n",
              g, e.i1_002, e.i2, e.i3, e.conductivity_002_eq22, e.conductivity, e.viscosity,
              e.diffusion, e.prandtl_002, e.prandtl, e.schmidt);
}
} // namespace

// With g = 1 the integrals are Beta functions: I2 = B(3, 3/2), I3 = B(5, 3/2),
// I1 = B(5, 3/2) - B(7, 3/2)/3 (002:(14) with the order of integration swapped).
TEST(TransportEstimates, Seed002IdealIntegralsAreBetaFunctions) {
  const auto p = particle::testing::seed002(particle::Integrator::EcVerlet, 0.005);
  const Estimates e = estimate(p, 1.0, PairDistribution::ideal());
  auto beta = [](double a, double b) {
    return std::exp(std::lgamma(a) + std::lgamma(b) - std::lgamma(a + b));
  };
  EXPECT_NEAR(e.i2, beta(3, 1.5), 1e-6);
  EXPECT_NEAR(e.i3, beta(5, 1.5), 1e-6);
  EXPECT_NEAR(e.i1_002, beta(5, 1.5) - beta(7, 1.5) / 3, 1e-6);
  print(e, "g = 1");
  // 002 section III.E: "Pr = 2.1 and Sc = 4.1 ... with g(r) = 1"
  expect_printed(e.prandtl_002, 2.1, 0.1, "Pr (g = 1)");
  expect_printed(e.schmidt, 4.1, 0.1, "Sc (g = 1)");
}

// With the measured g(r) of 002's fluid: I1 = 0.058, I2 = 0.131, I3 = 0.073, kappa = 146 from
// eq. (22), Pr = 2.0, Sc = 3.57 (002 sections III.D-E).
TEST(TransportEstimates, Seed002WithMeasuredPairDistribution) {
  auto p = particle::testing::seed002(particle::Integrator::EcVerlet, 0.01);
  p.equilibration_steps = 500;
  p.steps = 1000;
  p.rdf_bins = 50;
  const auto run = particle::run_particles(p);
  const Estimates e = estimate(p, 1.0, PairDistribution::from_csv(run.rdf_csv));
  print(e, "measured g");
  expect_printed(e.i1_002, 0.058, 0.001, "I1");
  expect_printed(e.i2, 0.131, 0.001, "I2");
  expect_printed(e.i3, 0.073, 0.001, "I3");
  expect_printed(e.conductivity_002_eq22, 146, 1, "kappa, 002 eq. (22)");
  expect_printed(e.prandtl_002, 2.0, 0.1, "Pr");
  expect_printed(e.schmidt, 3.57, 0.01, "Sc");
}

// 000:(3.27)-(3.28): with g = 1 and w_D = w_H = (1 - r/rc)^2 the dissipative viscosity and the
// conduction part of kappa are 2 pi rho^2 zeta0 rc^5 / 1575 and (2 pi/315)(rho^2/T^2) L0 rc^5.
TEST(TransportEstimates, Seed000ClosedForms) {
  particle::ParticleParameters p;
  p.dim = 3;
  p.density = 1.7;
  p.friction = particle::Friction::ConstantGamma;
  p.gamma = 2.3;
  p.dissipation = {1.24, 2.0};
  p.heat = particle::HeatLaw::Inverse;
  p.heat_coefficient = particle::HeatCoefficient::Constant;
  p.kappa0 = 0.7;
  p.heat_weight = {1.24, 2.0};
  const double T = 1.3, rc5 = std::pow(1.24, 5), rho2 = 1.7 * 1.7;
  const Estimates e = estimate(p, T, PairDistribution::ideal());
  EXPECT_NEAR(e.viscosity_dissipative / (2 * M_PI * rho2 * 2.3 * rc5 / 1575), 1, 1e-9);
  EXPECT_NEAR(e.conductivity_conduction / (2 * M_PI / 315 * rho2 / (T * T) * 0.7 * rc5), 1, 1e-9);
}
