// The one reader of the transport stage's results: which coefficient a consumer takes.

#include <gtest/gtest.h>

#include <cmath>

#include "transport/coefficients.hpp"

using namespace twinflow;

namespace {
io::Json summary(bool with_power_law) {
  // (keys added to an ordered JSON object move their siblings: no references kept across)
  io::Json e = {{"viscosity", 1.0},
                {"conductivity", 20.0},
                {"heat_capacity_p_per_particle", 13.0},
                {"thermal_expansion", 1.25}};
  io::Json m = {{"viscosity", 1.2},
                {"viscosity_stderr", 0.05},
                {"conductivity", 18.0},
                {"conductivity_stderr", 0.3},
                {"thermal_expansion", std::nan("")}}; // not finite: the estimate stands
  if (with_power_law) m["conductivity_exponent"] = -1.5, m["conductivity_exponent_stderr"] = 0.1;
  io::Json s = io::Json::object();
  s["results"]["estimated_measured_g"] = e;
  s["results"]["measured"] = m;
  s["results"]["state_point"]["measured_temperature"] = 0.8;
  return io::Json::parse(s.dump()); // as read back from the file: NaN is null
}
} // namespace

TEST(TransportCoefficients, MeasuredWhereAskedAndPresentElseTheEstimate) {
  const auto k = transport::read_coefficients(summary(false), "measured", 0.8);
  EXPECT_EQ(k.viscosity.value, 1.2);
  EXPECT_TRUE(k.viscosity.measured);
  EXPECT_EQ(k.viscosity.stderr_, 0.05);
  EXPECT_EQ(k.conductivity.value, 18.0);
  EXPECT_EQ(k.thermal_expansion.value, 1.25);
  EXPECT_FALSE(k.thermal_expansion.measured);
  EXPECT_EQ(k.heat_capacity_p.value, 13.0);
  EXPECT_FALSE(std::isfinite(k.conductivity.exponent));
  const auto e = transport::read_coefficients(summary(false), "estimated", 0.8);
  EXPECT_EQ(e.viscosity.value, 1.0);
  EXPECT_FALSE(std::isfinite(e.viscosity.stderr_));
}

TEST(TransportCoefficients, APowerLawIsRescaledWithItsExponentsError) {
  const auto k = transport::read_coefficients(summary(true), "measured", 1.0);
  const double l = std::log(1.0 / 0.8), s = std::exp(-1.5 * l);
  EXPECT_DOUBLE_EQ(k.conductivity.value, 18.0 * s);
  EXPECT_DOUBLE_EQ(k.conductivity.exponent, -1.5);
  EXPECT_DOUBLE_EQ(k.conductivity.stderr_, s * std::hypot(0.3, 18.0 * l * 0.1));
  EXPECT_EQ(k.viscosity.value, 1.2); // no law: unchanged
}

TEST(TransportCoefficients, TheEquationOfStateIsReadWhenPresent) {
  const auto old = transport::read_coefficients(summary(false), "estimated", 0.8);
  EXPECT_FALSE(old.excess_pressure.found); // an older summary: none
  EXPECT_EQ(old.excess_pressure.b0, 0.0);
  io::Json s = summary(false);
  s["results"]["equation_of_state"] = {
      {"b0", 2.5}, {"b0_stderr", 0.01}, {"b1", -0.1},  {"b1_stderr", 0.02},
      {"b2", 0.1}, {"b2_stderr", 0.03}, {"n_ref", 3.0}};
  const auto k = transport::read_coefficients(s, "estimated", 0.8); // the pressure is measured
  EXPECT_TRUE(k.excess_pressure.found);
  EXPECT_TRUE(k.excess_pressure.fitted);
  EXPECT_EQ(k.excess_pressure.b0, 2.5);
  EXPECT_EQ(k.excess_pressure.b1_stderr, 0.02);
  EXPECT_EQ(k.excess_pressure.b2, 0.1);
  EXPECT_EQ(k.excess_pressure.n_ref, 3.0);
  s["results"]["equation_of_state"] = {{"b0", 0.0},        {"b0_stderr", 0.0}, {"b1", 0.0},
                                       {"b1_stderr", 0.0}, {"b2", 0.0},        {"b2_stderr", 0.0},
                                       {"n_ref", 3.0}};
  EXPECT_FALSE(transport::read_coefficients(s, "measured", 0.8).excess_pressure.fitted);
}
