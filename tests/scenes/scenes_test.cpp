// The shipped scene cases, shrunk: what each reports is there and physically sound.
#include "scene_run.hpp"

#include <algorithm>

#include "io/csv.hpp"

using namespace twinflow::testing;

// Ideal DPDE fluid between thermal walls at T = 1.1: no potential, so the density is uniform and
// the force on each wall per area is the bulk pressure rho k T (000:(3.20)), T the fluid's.
TEST(Scenes, WallsEquilibriumPressureIsRhoKT) {
  const auto r = run_case("walls_equilibrium", "--threads 1");
  const double rho = 0.35355339;
  const double t = number(r, "T_internal"), t_se = number(r, "T_internal_stderr");
  for (const char* wall : {"walls.x_lower", "walls.x_upper"}) {
    const double p = number(r, std::string(wall) + ".pressure");
    const double se = std::hypot(number(r, std::string(wall) + ".pressure_stderr"), rho * t_se);
    EXPECT_LT(std::fabs(p - rho * t), 4 * se) << wall << ": " << p << " +- " << se;
  }
  EXPECT_NEAR(t, 1.1, 0.02) << "relaxes towards the walls' temperature";
}

// The same fluid at equilibrium against repulsive no-slip walls (a_w = 5): an ideal gas, so the
// density in the wall's layer is Boltzmann's, n(h) = n_ref exp(-U(h) / k T) with U = a_w range/2
// (1 - h/range)^2 (docs/theory.md). The wall's Gibbs depth and its tangential friction per area
// (constant gamma: gamma n_ref exp(-U/kT) w_D(h) over the layer) follow as sums over the same
// slices; each measured value within 4 of its block standard errors.
TEST(Scenes, WallLayerFollowsBoltzmann) {
  const auto dir = fresh_dir("scenes", "wall_layer");
  const Result run = run_twinflow(
      "particle " + case_path("walls_equilibrium") + " --out " + dir.string() +
      " --threads 1 --set Scene/Temperature=1.1 --set 'Particle/Initial velocities=maxwell' "
      "--set Particle/Walls/Repulsion=5 --set 'Scene/x boundaries/Slip=no-slip' "
      "--set 'Particle/Equilibration steps=2000' --set Particle/Steps=8000");
  ASSERT_EQ(run.code, 0) << run.output;
  const twinflow::io::Json summary = twinflow::io::read_json(dir / "particle" / "summary.json");
  const twinflow::io::Json& r = *twinflow::io::find(summary, {"results"});
  const double a = 5, range = 1.7536, gamma = 1, kT = number(r, "T_kinetic");
  const int slices = 20; // per range, as the particle stage samples them
  double depth = 0, friction = 0;
  for (int j = 0; j < slices; ++j) {
    const double h = (j + 0.5) * range / slices, c = 1 - h / range;
    const double boltzmann = std::exp(-0.5 * a * range * c * c / kT);
    depth += (1 - boltzmann) * range / slices;
    friction += gamma * boltzmann * c * c * range / slices; // w_D = (1 - h/range)^2
  }
  for (const char* wall : {"walls.x_lower", "walls.x_upper"}) {
    const std::string w(wall);
    const double d = number(r, w + ".effective_position");
    EXPECT_NEAR(d, depth, 4 * number(r, w + ".effective_position_stderr")) << wall;
    const double n_ref = number(r, w + ".layer_reference_density");
    const double zeta = number(r, w + ".friction_per_area");
    const double se = std::hypot(number(r, w + ".friction_per_area_stderr"),
                                 friction * number(r, w + ".layer_reference_density_stderr"));
    EXPECT_NEAR(zeta, n_ref * friction, 4 * se) << wall;
    std::cout << wall << ": depth " << d << " (Boltzmann " << depth << "), friction " << zeta
              << " (" << n_ref * friction << ")\n";
  }
}

// The relaxing heat and transverse momentum modes decay; the fits' chi and nu are positive with
// finite errors, and the decays hold at the smaller box's faster rates. eta = rho m nu near the
// reverse-Poiseuille 1.54 of the same fluid (docs/validation.md, "Particle scenes"), loosely:
// one short run, fit errors only.
TEST(Scenes, ThermalRelaxationFitsHeatAndShearDecayRates) {
  const auto r = run_case("thermal_relaxation", "--threads 1 --set 'Scene/Box size=10, 5, 5' "
                                                "--set Particle/Steps=5000");
  const double chi = number(r, "relaxation.chi"), se = number(r, "relaxation.chi_stderr");
  EXPECT_GT(chi, 0.1);
  EXPECT_LT(chi, 0.5);
  EXPECT_GT(se, 0);
  EXPECT_LT(se, 0.2 * chi);
  const double nu = number(r, "shear_relaxation.nu");
  const double nu_se = number(r, "shear_relaxation.nu_stderr");
  EXPECT_GT(nu_se, 0);
  EXPECT_LT(nu_se, 0.3 * nu);
  EXPECT_NEAR(number(r, "shear_relaxation.viscosity"), 3 * nu, 1e-9 * nu); // rho m nu
  EXPECT_GT(3 * nu, 0.5 * 1.54);
  EXPECT_LT(3 * nu, 2.0 * 1.54);
}

// The continuum twin takes eta, kappa, c_p and alpha from the transport stage's summary when the
// case says so; without that summary it refuses (exit 2) and names the command to run.
TEST(Scenes, ContinuumTakesCoefficientsFromTheTransportStage) {
  const auto dir = fresh_dir("scenes", "coefficients");
  // the estimates only (the default case also measures kappa and eta, and kappa between walls:
  // minutes)
  const std::string c = case_path("heated_cavity_2d") +
                        " --set 'Transport/Measure kappa and eta=false' --set "
                        "'Transport/Kappa from walls=false' --set Transport/Source=estimated";
  const std::string from = " --set Continuum/Coefficients/Source=transport";
  const Result missing = run_twinflow("continuum " + c + " --out " + dir.string() + from);
  EXPECT_EQ(missing.code, 2) << missing.output;
  EXPECT_NE(missing.output.find("twinflow transport"), std::string::npos) << missing.output;
  ASSERT_EQ(run_twinflow("transport " + c + " --out " + dir.string() + " --threads 1").code, 0);
  const Result r = run_twinflow("continuum " + c + " --out " + dir.string() + from);
  ASSERT_EQ(r.code, 0) << r.output;
  const auto transport = twinflow::io::read_json(dir / "transport" / "summary.json");
  const double eta = twinflow::io::find(transport, {"results", "estimated_measured_g", "viscosity"})
                         ->get<double>();
  std::ostringstream expected;
  expected << "eta = " << eta << " (estimated";
  EXPECT_NE(r.output.find(expected.str()), std::string::npos) << r.output;
  // The ideal DPDE fluid's measured equation of state: alpha = 1/T and c_p - c_v = k, within
  // 4 of their standard errors (propagated from the pressure runs' block errors).
  const auto& m = *twinflow::io::find(transport, {"results", "measured"});
  const double t = twinflow::io::find(m, {"temperature_kinetic"})->get<double>();
  EXPECT_NEAR(twinflow::io::find(m, {"thermal_expansion"})->get<double>(), 1 / t,
              4 * twinflow::io::find(m, {"thermal_expansion_stderr"})->get<double>());
  EXPECT_NEAR(twinflow::io::find(m, {"heat_capacity_cp_minus_cv"})->get<double>(), 1.0,
              4 * twinflow::io::find(m, {"heat_capacity_cp_minus_cv_stderr"})->get<double>());
}

// Measured power laws reach the twin at its own reference temperature: kappa(T_m) (T_ref /
// T_m)^n, with the error of both the value and the exponent carried along, and the twin's heat
// flux response to those errors recorded. The transport summary is written by hand here, so the
// expected numbers are independent of any particle run.
TEST(Scenes, ContinuumRescalesMeasuredPowerLawsToItsReferenceTemperature) {
  namespace fs = std::filesystem;
  const auto dir = fresh_dir("scenes", "power_laws");
  fs::create_directories(dir / "transport");
  const double t_m = 0.8, kappa = 16, kappa_se = 1.0, n = -0.5, n_se = 0.2, eta = 1.2;
  std::ostringstream s;
  s << R"({"results": {"state_point": {"density": 4, "temperature": 0.8, "measured_temperature": )"
    << t_m << R"(}, "estimated_measured_g": {"viscosity": 0.86, "conductivity": 8.75,
    "heat_capacity_p_per_particle": 13, "thermal_expansion": 1.24}, "measured": {"viscosity": )"
    << eta << R"(, "viscosity_stderr": 0.1, "conductivity": )" << kappa
    << R"(, "conductivity_stderr": )" << kappa_se << R"(, "conductivity_exponent": )" << n
    << R"(, "conductivity_exponent_stderr": )" << n_se << R"(, "thermal_expansion": 1.24}}})";
  twinflow::io::write_file_atomically(dir / "transport" / "summary.json", s.str());
  const Result r = run_twinflow("continuum " + case_path("heated_cavity_2d") +
                                " --set Transport/Source=measured --set "
                                "Continuum/Coefficients/Source=transport --out " +
                                dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto summary = twinflow::io::read_json(dir / "continuum" / "summary.json");
  const auto& law = *twinflow::io::find(summary, {"continuum_parameters", "conductivity"});
  const double t_ref =
      twinflow::io::find(summary, {"continuum_parameters", "reference_temperature"})->get<double>();
  EXPECT_NEAR(twinflow::io::find(law, {"exponent"})->get<double>(), n, 1e-12);
  EXPECT_NEAR(twinflow::io::find(law, {"value_at_reference"})->get<double>(),
              kappa * std::pow(t_ref / t_m, n), 1e-9 * kappa);
  const auto& u = *twinflow::io::find(summary, {"coefficient_uncertainty"});
  const double scale = std::pow(t_ref / t_m, n), log_ratio = std::log(t_ref / t_m);
  EXPECT_NEAR(twinflow::io::find(u, {"conductivity", "stderr"})->get<double>(),
              scale * std::hypot(kappa_se, kappa * log_ratio * n_se), 1e-9);
  EXPECT_NEAR(twinflow::io::find(u, {"viscosity", "stderr"})->get<double>(), 0.1,
              1e-12); // no exponent: as is
  // More kappa carries more heat; kappa's power of T moves by its error too (its value at the
  // reference held); the combined error is the three responses in quadrature.
  const double dk =
      twinflow::io::find(u, {"conductivity", "heat_flux_relative_change"})->get<double>();
  const double de =
      twinflow::io::find(u, {"viscosity", "heat_flux_relative_change"})->get<double>();
  EXPECT_NEAR(twinflow::io::find(u, {"conductivity_exponent", "stderr"})->get<double>(), n_se,
              1e-12);
  const double dn =
      twinflow::io::find(u, {"conductivity_exponent", "heat_flux_relative_change"})->get<double>();
  EXPECT_NE(dn, 0);
  EXPECT_EQ(twinflow::io::find(u, {"viscosity_exponent"}), nullptr); // eta has no law in T here
  EXPECT_GT(dk, 0);
  EXPECT_NEAR(twinflow::io::find(u, {"heat_flux_relative_stderr"})->get<double>(),
              std::sqrt(dk * dk + de * de + dn * dn), 1e-12);
  // Each input's response bin by bin, for compare: the three inputs, every bin once, not all
  // zero.
  const auto responses = twinflow::io::parse_csv(
      twinflow::io::read_file(dir / "continuum" / "coefficient_responses.csv"));
  const auto& bins = *twinflow::io::find(summary, {"continuum_parameters", "bins"});
  const std::size_t per_input = bins[0].get<std::size_t>() * bins[1].get<std::size_t>();
  ASSERT_EQ(responses.rows.size(), 3 * per_input);
  const std::size_t input = responses.column("input", "coefficient_responses.csv");
  const std::size_t T = responses.column("T", "coefficient_responses.csv");
  EXPECT_EQ(responses.rows.front()[input], "conductivity");
  EXPECT_EQ(responses.rows.back()[input], "conductivity_exponent");
  double largest = 0;
  for (const auto& row : responses.rows) largest = std::max(largest, std::fabs(std::stod(row[T])));
  EXPECT_GT(largest, 1e-5);
}
