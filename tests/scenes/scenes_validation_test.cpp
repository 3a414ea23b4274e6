// Full-size scene validations against the papers (label validation).
#include "scene_run.hpp"

#include <algorithm>
#include <vector>

#include "io/csv.hpp"
#include "transport/measure.hpp"

using namespace twinflow::testing;

// Seed 000 section 3.1: N = 30000 between walls at T* = 1.1, B = 0.01, C = 17, r* = 1.24.
// U* = E/(c_v T_R) within 0.1% of 33825 (the paper: 33828 +- 1); P* = P 2^(3/2)/rho* reported
// against the paper's 1.137 +- 0.005 and the ideal 1.1.
TEST(ScenesValidation, WallsEquilibriumFullSize) {
  std::filesystem::path dir;
  const auto r = run_case("walls_equilibrium_full", "", &dir);
  const std::string thermo = twinflow::io::read_file(dir / "particle" / "thermo.csv");
  const std::size_t last = thermo.rfind('\n', thermo.size() - 2);
  std::istringstream row(thermo.substr(last + 1));
  std::string step, time, sampled, energy;
  std::getline(row, step, ','), std::getline(row, time, ','), std::getline(row, sampled, ',');
  std::getline(row, energy, ',');
  const double u_star = std::stod(energy) / 100; // c_v T_R = 100
  const double n = number(r, "N");
  std::cout << "U* = " << u_star << " (N = " << n << "; N T* (1 + 5B/2) = " << n * 1.1275
            << "; paper 33828 +- 1 for N = 30000)\n";
  EXPECT_NEAR(u_star / (n * 1.1275), 1, 1e-3);
  const double scale = std::pow(2.0, 1.5); // P* = P 2^(3/2) / rho*, rho* = 1
  for (const char* wall : {"walls.x_lower", "walls.x_upper"})
    std::cout << wall << ": P* = " << scale * number(r, std::string(wall) + ".pressure") << " +- "
              << scale * number(r, std::string(wall) + ".pressure_stderr")
              << " (paper 1.137 +- 0.005, ideal 1.1)\n";
}

// Seed 002 section III.B: T(x) ~ 0.91 + 0.018 x (slope within 5%), kappa within 5% of 150; the
// flux decomposition at x = 2 and 8 is printed.
TEST(ScenesValidation, SlabConductionPeriodic) {
  const auto r = run_case("slab_conduction_periodic", "");
  const double kappa = number(r, "heat_slabs.kappa");
  EXPECT_NEAR(kappa / 150, 1, 0.05) << kappa;
  for (const char* half : {"heat_slabs.hot_to_cold.slope", "heat_slabs.cold_to_hot.slope"})
    EXPECT_NEAR(std::fabs(number(r, half)) / 0.018, 1, 0.05) << half;
  for (const auto& plane : (*twinflow::io::find(r, {"heat_slabs", "flux_decomposition"}))) {
    std::cout << "x = " << twinflow::io::find(plane, {"x"})->get<double>();
    for (const auto& [key, value] : plane.items())
      std::cout << "  " << key << " " << value.get<double>();
    std::cout << "\n";
  }
}

// Issue 27's wall slab (cases/slab_conduction_walls.prm as shipped, seed 1): each wall's jump
// (T_w - the bulk profile carried to the wall) within 3% of dT, allowing two of its stated
// errors; kappa = the heat flow across / the slope at the centre equal to the periodic slab's
// within three combined errors. The periodic slab's 150.1 +- 1.7 is its mean over five runs with
// the error from their scatter (docs/validation.md, "Particle scenes": its own stated errors are
// short).
TEST(ScenesValidation, SlabConductionWalls) {
  const auto r = run_case("slab_conduction_walls", "--threads 2");
  const double dt = 0.4;
  for (const char* side : {"lower", "upper"}) {
    const std::string key = std::string("wall_profile.jump_") + side;
    const double jump = number(r, key), se = number(r, key + "_stderr");
    std::cout << side << " wall: jump " << 100 * jump / dt << " +- " << 100 * se / dt
              << "% of dT\n";
    EXPECT_LE(std::fabs(jump), 0.03 * dt + 2 * se) << side;
  }
  const double q = number(r, "wall_pairs.x.heat_flux"), slope = number(r, "wall_profile.slope");
  const double kappa = -q / slope;
  const double se = std::fabs(kappa) * std::hypot(number(r, "wall_pairs.x.heat_flux_stderr") / q,
                                                  number(r, "wall_profile.slope_stderr") / slope);
  std::cout << "kappa = " << kappa << " +- " << se << " (periodic slab 150.1 +- 1.7)\n";
  EXPECT_NEAR(kappa, 150.1, 3 * std::hypot(se, 1.7));
}

// Seed 004's relaxation method on seed 002's fluid: kappa from the decay agrees with the slab's
// 150 within three standard errors of the mean of four seeds. The error comes from the seeds'
// scatter: one run's fit error was half of it (2026-11-23: 158.3, 149.5, 159.8, 148.6 with
// stated errors 2.6-4.1), and one run against a fixed 5% failed by chance.
TEST(ScenesValidation, ThermalRelaxationKappa) {
  std::vector<twinflow::particle::Estimate> kappa;
  for (const int seed : {1, 2, 3, 4}) {
    const auto r = run_case("thermal_relaxation", "--set Particle/Seed=" + std::to_string(seed));
    kappa.push_back(
        {number(r, "relaxation.kappa_ideal_cp"), number(r, "relaxation.kappa_ideal_cp_stderr")});
    std::cout << "seed " << seed << ": kappa (relaxation) = " << kappa.back().mean << " +- "
              << kappa.back().stderr_
              << "; eta (shear relaxation) = " << number(r, "shear_relaxation.viscosity") << " +- "
              << number(r, "shear_relaxation.viscosity_stderr") << "\n";
  }
  const auto repeated = twinflow::transport::summarise_repeats(kappa);
  const double mean = repeated.value.mean, sem = repeated.spread_stderr;
  std::cout << "kappa (relaxation, " << kappa.size() << " seeds) = " << mean << " +- " << sem
            << "\n";
  EXPECT_NEAR(mean, 150, 3 * sem);
}

namespace {
// A column of wall_layers.csv within the first cutoff of a wall, weighted by its errors. A
// temperature's slices move together (the whole fluid's slow exchange with the walls reaches
// every slice), so its mean's error is the slices' rms error, the bound for fully correlated
// slices: 1 / sqrt(sum of weights) takes them as independent and was ~4x too small
// (2026-11-29). The shapes (the Gamma law's ratio, the kurtosis) do not follow the fluid's
// temperature, and their slices are taken as independent.
struct LayerMean {
  double mean = 0, stderr_ = 0;
};
LayerMean layer_mean(const std::string& csv, const std::string& wall, const std::string& column,
                     bool slices_move_together) {
  const twinflow::io::CsvTable table = twinflow::io::parse_csv(csv);
  const std::size_t h = table.column("h", "wall_layers.csv"),
                    value = table.column(column, "wall_layers.csv"),
                    error = table.column(column + "_se", "wall_layers.csv");
  double sw = 0, swx = 0, sum_se2 = 0;
  int slices = 0;
  for (const auto& row : table.rows) {
    if (row[0] != wall || std::stod(row[h]) >= 1) continue;
    const double se = std::stod(row[error]);
    if (!(se > 0)) continue;
    sw += 1 / (se * se), swx += std::stod(row[value]) / (se * se);
    sum_se2 += se * se, ++slices;
  }
  return {swx / sw, slices_move_together ? std::sqrt(sum_se2 / slices) : 1 / std::sqrt(sw)};
}
} // namespace

// Issue 44: the shipped walls (the default cavity's: half-space, diffuse re-emission, conducting
// 30x and 100x the fluid) hold a fluid started away from their temperature at it, in equilibrium
// (the default fluid at 1.2 between walls at 0.8, no gravity; 2D, c_v = 10, dt 0.01; 600 tau, ~6
// decay times of the slowest mode, to relax, 4800 sampled in 16 blocks of 300 tau: the fluid's
// temperature has an integrated autocorrelation time of ~90 tau, its exchange with the walls, and
// 20 blocks of 30 tau understated its error ~2x, session 16's failure at this seed). It relaxes
// to T_w with T_kinetic = T_internal = T_w, the wall layer's first cutoff included (its internal
// energies the Gamma law's, its velocities Gaussian), and no net heat into either wall; the
// walls' Metropolis acceptance is printed. 24 checks, each error from 16 blocks: at 3 errors one
// of them would fail by chance in ~20% of seeds (Student's t, 15 degrees of freedom), at 4 in
// ~3%.
TEST(ScenesValidation, ShippedWallsHoldAFluidAtTheirTemperature) {
  const double k = 4; // errors allowed per check (above)
  for (const char* factor : {"30", "100"}) {
    std::filesystem::path dir;
    const auto r = run_case(
        "heated_cavity_2d",
        std::string("--threads 2 --set 'Scene/Gravity=0, 0' --set 'Scene/Temperature=1.2' ") +
            "--set 'Scene/x boundaries/Lower wall temperature=0.8' --set 'Scene/x boundaries/Upper "
            "wall temperature=0.8' --set 'Particle/Equilibration steps=60000' --set "
            "'Particle/Steps=480000' --set 'Particle/Diagnostics/Blocks=16' --set "
            "'Particle/Walls/Heat conduction=" +
            factor + "'",
        &dir);
    const double T_w = 0.8;
    const auto near_wall = [&](double value, double se, const char* what) {
      EXPECT_LT(std::fabs(value - T_w), k * se + 1e-3)
          << "f " << factor << ": " << what << " " << value << " +- " << se;
    };
    near_wall(number(r, "T_kinetic"), number(r, "T_kinetic_stderr"), "T_kinetic");
    near_wall(number(r, "T_internal"), number(r, "T_internal_stderr"), "T_internal");
    const std::string layers = twinflow::io::read_file(dir / "particle" / "wall_layers.csv");
    for (const char* wall : {"x_lower", "x_upper"}) {
      const LayerMean tk = layer_mean(layers, wall, "T_kinetic", true);
      const LayerMean ti = layer_mean(layers, wall, "T_internal", true);
      const LayerMean gamma = layer_mean(layers, wall, "u_gamma_ratio", false);
      const LayerMean kurtosis = layer_mean(layers, wall, "kurtosis", false);
      const std::string name = std::string("walls.") + wall;
      const double q = number(r, name + ".heat_flux_in"),
                   q_se = number(r, name + ".heat_flux_in_stderr");
      std::cout << "f " << factor << ", " << wall << " (h < 1): T_kinetic " << tk.mean << " +- "
                << tk.stderr_ << ", T_internal " << ti.mean << " +- " << ti.stderr_
                << ", Var(u)(c_v+1)/<u>^2 " << gamma.mean << " +- " << gamma.stderr_
                << ", kurtosis " << kurtosis.mean << " +- " << kurtosis.stderr_ << "; heat in " << q
                << " +- " << q_se << "; Metropolis acceptance "
                << number(r, name + ".heat_moves_acceptance") << "\n";
      near_wall(tk.mean, tk.stderr_, "layer T_kinetic");
      near_wall(ti.mean, ti.stderr_, "layer T_internal");
      EXPECT_LT(std::fabs(gamma.mean - 1), k * gamma.stderr_ + 0.01) << wall;
      EXPECT_LT(std::fabs(kurtosis.mean - 3), k * kurtosis.stderr_ + 0.02) << wall;
      // No net heat either way: the sign of a wall's flow in equilibrium is noise.
      EXPECT_LT(std::fabs(q), k * q_se) << wall;
      const double acceptance = number(r, name + ".heat_moves_acceptance");
      EXPECT_GT(acceptance, 0.5) << wall;
      EXPECT_LE(acceptance, 1.0) << wall;
    }
  }
}

// A fluid with a conservative force (the column's: a0 = 5) between thermal walls at its own
// start temperature, no gravity: it must stay at T_w. Measured 2026-11-28: T_kinetic 1.0025 +-
// 0.0013, T_internal 1.0017 +- 0.0010 with shardlow's offset pooled; 1.071 / 1.078 when each
// particle's own K + P change went into its u (docs/validation.md, "Particle core").
TEST(ScenesValidation, ConservativeFluidBetweenWallsStaysAtTheirTemperature) {
  const auto r =
      run_case("conduction_column_repulsive_2d",
               "--threads 2 --set Particle/Steps=60000 --set 'Scene/Gravity=0, 0' --set 'Scene/y "
               "boundaries/Lower wall temperature=1' --set 'Scene/y boundaries/Upper "
               "wall temperature=1'");
  for (const char* key : {"T_kinetic", "T_internal"}) {
    const double value = number(r, key), se = number(r, std::string(key) + "_stderr");
    EXPECT_LT(std::fabs(value - 1), 3 * se + 2e-3) << key << " " << value << " +- " << se;
  }
}
