// Heat conduction model (no flow) against exact solutions, in 1D, 2D and 3D.
#include <gtest/gtest.h>

#include <deal.II/base/function.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "continuum/heat_conduction.hpp"
#include "continuum/run.hpp"

using namespace twinflow::continuum;

namespace {

// A slab 0 <= x <= L between two walls; all other directions periodic.
ContinuumParameters slab(int dim, double length, unsigned cells_x) {
  ContinuumParameters p;
  p.dim = dim;
  p.model = Model::HeatConduction;
  p.box = {{length, 0.5, 0.5}};
  p.cells = {{cells_x, 2, 2}};
  p.refinements = 0;
  p.boundary[0] = {false, {{true, true}}, {{2.0, 1.0}}, {{0, 0}}, true};
  p.boundary[1].periodic = p.boundary[2].periodic = true;
  p.bins = {{4, 1, 1}};
  p.write_fields = false;
  p.newton_tolerance = 1e-13;
  return p;
}

template <int dim> class Exact : public dealii::Function<dim> {
public:
  explicit Exact(std::function<double(double)> f) : f_(std::move(f)) {}
  double value(const dealii::Point<dim>& x, unsigned = 0) const override { return f_(x[0]); }

private:
  std::function<double(double)> f_;
};

template <int dim> double power_law_slab_error(unsigned cells) {
  // kappa = kappa_0 (T_0/T)^2 between T(0) = 2 and T(1) = 1: int kappa dT = -kappa_0 T_0^2 / T is
  // linear in x (Kirchhoff transform), so 1/T = 1/2 + x/2 exactly.
  ContinuumParameters p = slab(dim, 1.0, cells);
  p.conductivity = {0.7, -2.0};
  HeatConductionProblem<dim> problem(p);
  problem.run("");
  return problem.max_relative_error(Exact<dim>([](double x) { return 1.0 / (0.5 + 0.5 * x); }));
}

template <int dim> void check_power_law_slab(unsigned coarse) {
  // Q2: max error O(h^3); each halving of h must gain at least a factor 6 (8 asymptotically) and
  // the finest mesh (8 coarse cells x 2^3 in 1D) reaches 1e-6 relative.
  double previous = 0, error = 0;
  for (unsigned cells = coarse; cells <= 8 * coarse; cells *= 2) {
    error = power_law_slab_error<dim>(cells);
    std::printf("%dD power-law slab, %u cells: max relative error %.3e\n", dim, cells, error);
    if (previous > 0) {
      EXPECT_GT(previous / error, 6.0);
    }
    previous = error;
  }
  EXPECT_LT(error, 1e-6);
}

} // namespace

TEST(HeatConduction, PowerLawSlab1D) {
  check_power_law_slab<1>(8);
}
TEST(HeatConduction, PowerLawSlab2D) {
  check_power_law_slab<2>(8);
}
TEST(HeatConduction, PowerLawSlab3D) {
  check_power_law_slab<3>(8);
}

TEST(HeatConduction, HeatSlabsBetweenWalls1D) {
  // -kappa T'' = q with a hot slab [2,3] (+P) and a cold slab [7,8] (-P), T(0) = T(10) = 1:
  // T = 1 - F(x)/kappa + F(10) x / (10 kappa), F the double integral of q. Piecewise quadratic
  // with kinks at mesh nodes: exact in Q2 up to round-off (bound 1e-10).
  ContinuumParameters p = slab(1, 10.0, 20);
  p.boundary[0].temperature = {{1.0, 1.0}};
  p.conductivity = {2.0, 0.0};
  const double power = 0.3;
  p.heat_slabs = {{0, 2.0, 3.0, power}, {0, 7.0, 8.0, -power}};
  auto F = [](double x, double a, double b, double q) { // int_0^x int_0^s q 1_[a,b]
    if (x <= a) return 0.0;
    if (x <= b) return q * (x - a) * (x - a) / 2;
    return q * ((b - a) * (b - a) / 2 + (b - a) * (x - b));
  };
  auto exact = [&](double x) {
    auto total = [&](double y) { return F(y, 2, 3, power) + F(y, 7, 8, -power); };
    return 1.0 - total(x) / 2.0 + total(10.0) * x / (10.0 * 2.0);
  };
  HeatConductionProblem<1> problem(p);
  const ContinuumResult r = problem.run("");
  EXPECT_LT(problem.max_relative_error(Exact<1>(exact)), 1e-10);
  // Energy balance: what the slabs put in leaves through the walls (net 0 here).
  EXPECT_NEAR(r.heat_flux_lower + r.heat_flux_upper, 0.0, 1e-10);

  // The same slabs in a periodic box without walls: by the symmetry of the slabs T(0) = T(5) =
  // mean, so the solution is the walled one (mean fixed at the initial 1).
  p.boundary[0].periodic = true;
  HeatConductionProblem<1> periodic(p);
  const ContinuumResult rp = periodic.run("");
  EXPECT_NEAR(rp.temperature_mean, 1.0, 1e-12);
  EXPECT_LT(periodic.max_relative_error(Exact<1>(exact)), 1e-10);
}

TEST(HeatConduction, NeumannWall2D) {
  // T(0) = 2, heat flux h into the domain at x = L: T = 2 + h x / kappa (linear: exact in Q2).
  ContinuumParameters p = slab(2, 3.0, 6);
  p.boundary[0].fixed_temperature = {{true, false}};
  p.boundary[0].heat_flux = {{0.0, 0.4}};
  p.conductivity = {0.8, 0.0};
  HeatConductionProblem<2> problem(p);
  const ContinuumResult r = problem.run("");
  EXPECT_LT(problem.max_relative_error(Exact<2>([](double x) { return 2.0 + 0.4 * x / 0.8; })),
            1e-12);
  EXPECT_NEAR(r.heat_flux_upper, 0.4 * 0.5, 1e-12); // h times the wall length 0.5
}

template <int dim> double sine_mode_error(unsigned cells, double dt) {
  // T = 1 + A exp(-chi k^2 t) sin(k x) in a periodic box, chi = kappa/(n c_p) (Fourier).
  ContinuumParameters p;
  p.dim = dim;
  p.model = Model::HeatConduction;
  p.box = {{2.0, 0.5, 0.5}};
  p.cells = {{cells, 2, 2}};
  p.refinements = 0;
  p.number_density = 2.0, p.heat_capacity = 1.5, p.conductivity = {0.6, 0.0};
  const double chi = 0.6 / 3.0, k = 2 * M_PI / 2.0, amplitude = 0.1;
  p.mode = Mode::Transient;
  p.end_time = 1.0 / (chi * k * k); // one e-folding
  p.time_step = dt * p.end_time;
  p.initial_temperature = "1 + 0.1 * sin(2 * pi * x / Lx)";
  p.write_fields = false;
  HeatConductionProblem<dim> problem(p);
  const ContinuumResult r = problem.run("");
  EXPECT_NEAR(r.temperature_mean, 1.0, 1e-12); // energy conserved
  // Amplitude = (2/|Omega|) int T sin(kx).
  double volume = 1;
  for (int d = 0; d < dim; ++d) volume *= p.box[d];
  Exact<dim> sine([k](double x) { return std::sin(k * x); });
  const double measured = 2.0 / volume * problem.integrate(sine);
  const double expected = amplitude * std::exp(-chi * k * k * problem.time());
  return std::abs(measured / expected - 1);
}

TEST(HeatConduction, PeriodicSineModeDecays) {
  // Crank-Nicolson over one e-folding in 200 steps: amplitude error ~ (lambda dt)^3/12 per step
  // = 200 * (1/200)^3 / 12 = 2e-7; Q2 eigenvalue error O((kh)^4) (Strang & Fix 1973, sec. 6.3):
  // measured 6e-5 at 16 cells per wavelength, so ~4e-6 at 32. Bound 1e-4.
  const double e1 = sine_mode_error<1>(32, 1.0 / 200);
  const double e2 = sine_mode_error<2>(32, 1.0 / 200);
  const double e3 = sine_mode_error<3>(32, 1.0 / 200);
  std::printf("sine mode decay, relative amplitude error: 1D %.2e, 2D %.2e, 3D %.2e\n", e1, e2, e3);
  EXPECT_LT(e1, 1e-4);
  EXPECT_LT(e2, 1e-4);
  EXPECT_LT(e3, 1e-4);
}

TEST(HeatConduction, BinAveragesProbesAndFields) {
  // T = 2 - x/L between the walls (linear: exact in Q2). Bin averages are exact integrals over
  // each bin: 2 - x_centre/L when bin faces are cell faces (4 bins on 8 cells); with 3 bins on 8
  // cells the sub-cell quadrature assigns points to bins (error O(h_sub/bin), bound 1e-2 here,
  // exact for the linear field by symmetry of the QIterated points within each piece).
  for (const unsigned bins : {4u, 3u}) {
    ContinuumParameters p = slab(2, 1.0, 8);
    p.boundary[0].temperature = {{2.0, 1.0}};
    p.bins = {{bins, 2, 1}};
    p.probe_points = {{{0.25, 0.1, 0}}, {{0.8, 0.4, 0}}};
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / "twinflow_continuum_heat_fields";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    p.write_fields = true;
    const ContinuumResult r = run(p, dir);
    ASSERT_EQ(r.bins.values.size(), 1u);
    ASSERT_EQ(r.bins.values[0].size(), 2 * bins);
    for (unsigned iy = 0; iy < 2; ++iy)
      for (unsigned ix = 0; ix < bins; ++ix)
        EXPECT_NEAR(r.bins.values[0][ix + bins * iy], 2.0 - (ix + 0.5) / bins,
                    bins == 4 ? 1e-12 : 1e-2)
            << ix << "," << iy;
    ASSERT_EQ(r.probe_values.size(), 2u);
    EXPECT_NEAR(r.probe_values[0][0], 1.75, 1e-12);
    EXPECT_NEAR(r.probe_values[1][0], 1.2, 1e-12);
    for (const char* f : {"fields.h5", "fields.xdmf"})
      EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  }
}

// A twin whose wall stands inside the scene's (moved in over a pinned layer, twin_walls.hpp): the
// scene's bins beside it count the layer's strip at the wall's temperature, as the particles'
// bins count the layer's particles; own_values keep the twin's domain alone. T = 2 - x on the
// twin's [0, 1] (10 cells: the bin faces are cell faces), the scene's walls 0.2 beyond one end.
TEST(HeatConduction, BinsBesideAMovedWallCountItsPinnedStrip) {
  for (const int side : {0, 1}) {
    ContinuumParameters p = slab(2, 1.0, 10);
    p.bins = {{4, 1, 1}};
    p.bin_lower = {{side == 0 ? -0.2 : 0.0, 0, 0}};
    p.bin_box = {{1.2, 0.5, 0}};
    const ContinuumResult r = run(p, "");
    const auto& T = r.bins.values[0];
    const auto& own = r.bins.own_values()[0];
    ASSERT_EQ(T.size(), 4u);
    const unsigned strip_bin = side == 0 ? 0 : 3, inner = side == 0 ? 3 : 0;
    // the bin's 0.1 of domain (mean T 1.95 or 1.05) and the 0.2 strip at the wall's 2 or 1
    const double domain_mean = side == 0 ? 1.95 : 1.05, wall = side == 0 ? 2.0 : 1.0;
    EXPECT_NEAR(T[strip_bin], (0.1 * domain_mean + 0.2 * wall) / 0.3, 1e-12);
    EXPECT_NEAR(own[strip_bin], domain_mean, 1e-12);
    const double centre = side == 0 ? 0.85 : 0.15; // the bin away from the strip
    EXPECT_NEAR(T[inner], 2.0 - centre, 1e-12);
    EXPECT_NEAR(own[inner], 2.0 - centre, 1e-12);
  }
  ContinuumParameters p = slab(2, 1.0, 10); // no wall moved: no separate domain values
  EXPECT_TRUE(run(p, "").bins.domain_values.empty());
}

TEST(HeatConduction, FieldsIn1D) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "twinflow_continuum_heat_fields_1d";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  ContinuumParameters p = slab(1, 1.0, 8);
  p.write_fields = true;
  const ContinuumResult r = run(p, dir);
  // deal.II writes no 1D HDF5/XDMF: the nodal profile goes to fields.csv.
  ASSERT_EQ(r.files.size(), 1u);
  EXPECT_TRUE(std::filesystem::exists(dir / "fields.csv"));
}
