#include "continuum/parameters.hpp"

#include "continuum/compressible_eos.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace twinflow::continuum {

DimensionlessNumbers dimensionless_numbers(const ContinuumParameters& p) {
  DimensionlessNumbers n;
  const double T_ref = p.reference_temperature;
  n.kinematic_viscosity = p.viscosity.at(T_ref, T_ref) / p.mass_density(); // nu = eta/(n m)
  n.thermal_diffusivity = p.conductivity.at(T_ref, T_ref) / p.heat_capacity_per_volume(); // chi
  n.prandtl = n.kinematic_viscosity / n.thermal_diffusivity; // Pr = nu / chi
  for (int d = 0; d < p.dim; ++d) {
    const auto& b = p.boundary[d];
    if (b.periodic || !b.fixed_temperature[0] || !b.fixed_temperature[1]) continue;
    const double dT = b.temperature[0] - b.temperature[1];
    if (dT != 0 && (n.heated_direction < 0 || std::abs(dT) > std::abs(n.temperature_difference))) {
      n.heated_direction = d;
      n.temperature_difference = dT;
    }
  }
  n.height = p.box[std::max(n.heated_direction, 0)];
  double g = 0;
  for (int d = 0; d < p.dim; ++d) g += p.gravity[d] * p.gravity[d];
  g = std::sqrt(g);
  const double H = n.height;
  // Ra = g alpha dT H^3 / (nu chi) (de Vahl Davis 1983, eq. 5); the low-Mach ideal gas has
  // alpha = 1/T_ref (docs/theory.md), which makes this Le Quere et al. 2005's Ra at T0 = T_ref.
  const double alpha = p.model == Model::LowMach || p.model == Model::Compressible
                           ? 1.0 / T_ref
                           : p.thermal_expansion;
  n.rayleigh = g * alpha * std::abs(n.temperature_difference) * H * H * H /
               (n.kinematic_viscosity * n.thermal_diffusivity);
  n.velocity_scale = n.thermal_diffusivity / H; // chi / H (de Vahl Davis 1983)
  if (n.heated_direction >= 0) {
    // Conduction flux (1/H) int_{T_upper}^{T_lower} kappa(T) dT (Kirchhoff transform, Carslaw &
    // Jaeger 1959 sec. 1.7), for kappa = kappa_0 (T/T_ref)^e; H the scene's, between its wall
    // planes (walls moved in leave Nu's scale, and so the particles' Nu, as it was).
    const auto& b = p.boundary[n.heated_direction];
    const double H_scene = p.bin_extent(n.heated_direction);
    const double k0 = p.conductivity.value_at_reference, e = p.conductivity.exponent;
    const double tl = b.temperature[0] / T_ref, tu = b.temperature[1] / T_ref;
    // epsilon = (T_h - T_c) / (T_h + T_c) (Le Quere et al. 2005)
    n.epsilon =
        std::abs(b.temperature[0] - b.temperature[1]) / (b.temperature[0] + b.temperature[1]);
    if (p.conductivity.sutherland_temperature > 0.0) {
      // Sutherland: the same Kirchhoff integral by composite Simpson (smooth integrand).
      const int m = 2000;
      const double h = (b.temperature[0] - b.temperature[1]) / m;
      double sum = 0;
      for (int i = 0; i <= m; ++i)
        sum += (i == 0 || i == m ? 1 : (i % 2 ? 4 : 2)) *
               p.conductivity.at(b.temperature[1] + i * h, T_ref);
      n.conduction_flux = sum * h / 3 / H_scene;
    } else if (e == 0.0)
      n.conduction_flux = k0 * n.temperature_difference / H_scene;
    else if (e == -1.0)
      n.conduction_flux = k0 * T_ref * std::log(tl / tu) / H_scene;
    else
      n.conduction_flux =
          k0 * T_ref * (std::pow(tl, e + 1) - std::pow(tu, e + 1)) / ((e + 1) * H_scene);
  }
  return n;
}

void set_rayleigh_prandtl(ContinuumParameters& p, double rayleigh, double prandtl) {
  p.number_density = p.particle_mass = p.heat_capacity = 1.0;
  p.conductivity = PowerLaw{1.0, 0.0};  // chi = 1
  p.viscosity = PowerLaw{prandtl, 0.0}; // nu = Pr chi
  double g = 0;
  for (int d = 0; d < p.dim; ++d) g += p.gravity[d] * p.gravity[d];
  if (g == 0) {
    p.gravity = {{0, 0, 0}};
    p.gravity[1] = -1.0;
    g = 1.0;
  }
  const DimensionlessNumbers n = dimensionless_numbers(p);
  if (n.heated_direction < 0)
    throw std::invalid_argument("set_rayleigh_prandtl: no two walls at different temperatures");
  const double H = n.height;
  // g alpha dT H^3 / (nu chi) = Ra with nu = Pr, chi = 1
  p.thermal_expansion =
      rayleigh * prandtl / (std::sqrt(g) * std::abs(n.temperature_difference) * H * H * H);
}

double heat_source_density(const ContinuumParameters& p, const std::array<double, 3>& x) {
  double q = 0;
  for (const auto& s : p.heat_slabs) {
    if (x[s.direction] < s.lower || x[s.direction] > s.upper) continue;
    double volume = s.upper - s.lower; // times the cross-section of the box
    for (int d = 0; d < p.dim; ++d)
      if (d != s.direction) volume *= p.box[d];
    q += s.power / volume;
  }
  return q;
}

int take_kinetic_slip(ContinuumParameters& p) {
  if (!has_robin_walls(p.model)) return 0;
  int taken = 0;
  for (int d = 0; d < p.dim; ++d)
    for (int side = 0; side < 2; ++side) {
      auto& b = p.boundary[d];
      if (b.periodic || !b.no_slip || b.slip_length[side] > 0) continue;
      b.kinetic_slip[side] = p.wall_friction.diffuse[d][side];
      taken += b.kinetic_slip[side];
    }
  return taken;
}

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("continuum parameters: " + what);
}

void check_geometry(const ContinuumParameters& p) {
  require(p.dim >= 1 && p.dim <= 3, "dim must be 1, 2 or 3");
  for (const auto& b : p.boundary)
    require(!(b.kinetic_slip[0] || b.kinetic_slip[1]) || has_robin_walls(p.model),
            "kinetic wall slip needs the Boussinesq or compressible model");
  require(p.model == Model::HeatConduction || p.dim >= 2, "Boussinesq needs dim 2 or 3");
  for (int d = 0; d < p.dim; ++d) {
    require(p.box[d] > 0, "box lengths must be > 0");
    require(p.cells[d] >= 1, "cells per direction must be >= 1");
    require(p.bins[d] >= 1, "bins per direction must be >= 1");
    for (int side = 0; side < 2; ++side)
      require(p.boundary[d].periodic || !p.boundary[d].fixed_temperature[side] ||
                  p.boundary[d].temperature[side] > 0,
              "wall temperatures must be > 0");
    for (int side = 0; side < 2; ++side)
      require(std::isfinite(p.boundary[d].kapitza_conductance[side]) &&
                  (has_robin_walls(p.model) || p.boundary[d].kapitza_conductance[side] == 0),
              "Kapitza conductances must be finite, and != 0 only in the Boussinesq and "
              "compressible models");
  }
  for (const auto& s : p.heat_slabs) {
    require(s.direction >= 0 && s.direction < p.dim, "heat slab direction within dim");
    require(s.lower >= 0 && s.lower < s.upper && s.upper <= p.box[s.direction],
            "heat slab 0 <= lower < upper <= box length");
  }
}

// The thermal walls' temperature range (else T_ref's).
std::pair<double, double> wall_temperature_range(const ContinuumParameters& p) {
  double T_min = p.reference_temperature, T_max = T_min;
  bool walls = false;
  for (int d = 0; d < p.dim; ++d)
    for (int side = 0; side < 2; ++side)
      if (!p.boundary[d].periodic && p.boundary[d].fixed_temperature[side]) {
        const double T = p.boundary[d].temperature[side];
        T_min = walls ? std::min(T_min, T) : T, T_max = walls ? std::max(T_max, T) : T;
        walls = true;
      }
  return {T_min, T_max};
}

void check_compressible(const ContinuumParameters& p) {
  require(p.bulk_viscosity >= 0, "bulk viscosity must be >= 0");
  const auto [T_min, T_max] = wall_temperature_range(p);
  // Mechanical stability: dp/dn > 0 for 0 < n <= 3 n0 over the range (linear in T: its ends
  // suffice; quadratic in n: sampled), so p > 0 there too.
  for (const double T : {T_min, T_max})
    for (int i = 1; i <= 60; ++i) {
      const double n = 3 * p.number_density * i / 60;
      const double p_n = pressure(p.equation_of_state, n, T).p_n;
      require(p_n > 0, "Coefficients/Excess pressure: p = n T + n^2 (b0 + b1 T + b2 (n - n0)) is "
                       "unstable in range: dp/dn = " +
                           std::to_string(p_n) + " <= 0 at T = " + std::to_string(T) +
                           ", n = " + std::to_string(n) +
                           " (checked for 0 < n <= 3 n0 between the walls' temperatures)");
    }
  // The barometric scale height (dp/dn) / (m g_d) at T_min (k T_min / (m g_d) for the ideal
  // fluid; the smaller of that and the value at n0) must span 4 cells of the finest mesh: Q1
  // then interpolates exp(-z / H_s) to < 1%.
  const double p_n_min =
      std::min(T_min, pressure(p.equation_of_state, p.number_density, T_min).p_n);
  for (int d = 0; d < p.dim; ++d) {
    if (p.gravity[d] == 0 || p.uniform_along(d)) continue;
    const double h = p.box[d] / (p.cells[d] * std::pow(2.0, p.refinements));
    const double scale_height = p_n_min / (p.particle_mass * std::abs(p.gravity[d]));
    require(h <= 0.25 * scale_height,
            "mesh too coarse for the stratification: the finest cell along gravity (" +
                std::to_string(h) + ") must be <= 1/4 of the scale height (dp/dn) / (m g) = " +
                std::to_string(scale_height) + " (more Mesh/Cells or Refinements)");
  }
}

void check_fluid(const ContinuumParameters& p) {
  const EquationOfState& eos = p.equation_of_state;
  require(std::isfinite(eos.b0) && std::isfinite(eos.b1) && std::isfinite(eos.b2) && eos.n_ref > 0,
          "Coefficients/Excess pressure: b0, b1, b2 must be finite (a failed fit gives NaN)");
  require(p.model == Model::Compressible || p.equation_of_state.ideal(),
          "Coefficients/Excess pressure: b0, b1, b2 != 0 need the compressible model (the "
          "low-Mach model takes the ideal fluid only); allowed here: 0, 0, 0");
  require(p.number_density > 0 && p.particle_mass > 0 && p.heat_capacity > 0,
          "n, m and c_p must be > 0");
  require(p.viscosity.value_at_reference > 0 && p.conductivity.value_at_reference > 0,
          "eta and kappa must be > 0");
  require(p.viscosity.sutherland_temperature >= 0 && p.conductivity.sutherland_temperature >= 0,
          "Sutherland temperatures must be >= 0");
  for (const PowerLaw* law : {&p.viscosity, &p.conductivity})
    require(law->pair_fraction >= 0 && law->pair_fraction <= 1 && std::isfinite(law->pair_exponent),
            "pair fractions in [0, 1] (the compressible twin's; the others leave them out)");
  require(p.reference_temperature > 0, "reference temperature must be > 0");
}

void check_solver(const ContinuumParameters& p) {
  require(p.refinements >= 0 && p.refinements <= 12, "refinements in [0, 12]");
  require(p.newton_tolerance > 0 && p.max_newton_iterations >= 1, "Newton tolerance > 0");
  require(p.continuation_start_rayleigh > 0, "continuation start Ra > 0");
  require(!p.transient() || p.end_time > 0, "end time > 0 in transient mode");
  require(!p.transient() || p.time_step > 0, "time step > 0");
  require(p.series_every >= 1 && p.snapshot_every >= 0, "series every >= 1, snapshot every >= 0");
  for (const double t : p.snapshot_times)
    require(t >= 0 && t <= p.end_time, "snapshot times in [0, end time]");
  require(p.theta >= 0.5 && p.theta <= 1.0, "theta in [0.5, 1]");
  require(p.profile_samples >= 3, "profile samples >= 3");
  require(!p.uses_iterative_solver() || p.dim == 3, "the iterative Boussinesq solver is 3D only");
}

} // namespace

void check(const ContinuumParameters& p) {
  check_geometry(p);
  check_fluid(p);
  if (p.model == Model::Compressible) check_compressible(p);
  check_solver(p);
}

} // namespace twinflow::continuum
