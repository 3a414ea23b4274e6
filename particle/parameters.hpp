#pragma once
// Plain parameters of a particle run: filled once from the case file (study/case_file), read
// everywhere. Units: m, k (Boltzmann), rc and T0 are the DPD units; k = 1 throughout.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace twinflow::particle {

enum class Integrator { Euler, EcVerlet, Shardlow };
enum class EnergyModel { Dpde, Isothermal };
enum class ConservativeForce { None, Constant, TemperatureDependent };
enum class Friction { ConstantSigma, ConstantGamma };
enum class HeatLaw { None, Inverse, Linear };
enum class HeatCoefficient { Constant, Seed002 };
enum class InitialVelocities { Maxwell, Rest };
// Equilibrium: u_i = (c_v + k) T, the equilibrium mean (000:(3.21)), so an isolated fluid stays
// at T. Theta: theta_i = T (u_i = c_v T), seed 002's start; an isolated ideal fluid then settles
// at T (c_v + d/2) / (c_v + k + d/2).
enum class InitialInternalEnergy { Equilibrium, Theta };

// w(r) = (1 - r/cutoff)^exponent for r < cutoff.
struct WeightParameters {
  double cutoff = 1.0;
  double exponent = 1.0;
};

// Seed 002's heat slabs: `power` (energy per time; < 0 removes it) shared equally by the
// particles inside lower <= x_direction < upper.
struct HeatSlab {
  int direction;
  double lower, upper, power;
};

// How a wall acts on a particle at distance h. Seed000: like one particle of infinite mass and
// heat capacity at rest at the nearest point, within Particle/Walls/Range (docs/theory.md, "Walls";
// seed 000 section 3.1). HalfSpace: like the half-space of wall material at density rho_w beyond
// the plane, every pair term integrated over it (wall_weights.hpp): the coupling of the fluid's own
// neighbours.
enum class WallModel { HalfSpace, Seed000 };

// Walls at x_d = 0 and x_d = L_d of a non-periodic direction; nothing crosses them.
struct WallPair {
  bool present = false;
  std::array<bool, 2> thermal{{true, true}}; // lower, upper; false: adiabatic
  std::array<double, 2> temperature{{1, 1}};
  bool no_slip = false;
  std::array<WallModel, 2> model{{WallModel::HalfSpace, WallModel::HalfSpace}};
  // half-space walls: the wall material's heat-conduction strength for its pairs with the fluid,
  // in units of the fluid's kappa0
  std::array<double, 2> conduction{{1, 1}};
};

struct ParticleParameters {
  int dim = 3;
  std::array<double, 3> box{{20.0, 10.0, 10.0}}; // box[2] unused in 2D
  double density = 3.0;
  double mass = 1.0;
  std::uint64_t seed = 1;

  Integrator integrator = Integrator::Shardlow;
  bool energy_offset = false; // seed 002's K+P offset (shardlow: pooled with a pair force)
  double dt = 0.005;
  // Pairs within largest_cutoff() + skin are listed; the list is kept while no pair closer than
  // the cutoff can be missing (Simulation::update_neighbours; ec-verlet, shardlow). 0: a new list
  // every step.
  double neighbour_skin = 0.2;
  bool uniform_noise = false; // pair noises uniform with unit variance instead of Gaussian
  long equilibration_steps = 0;
  long steps = 1000;

  double temperature = 1.0;            // initial temperature; the fixed T of isothermal DPD
  double temperature_perturbation = 0; // initial theta = T (1 + A sin(2 pi x / Lx))
  double shear_perturbation = 0;       // initial v_y += U sqrt(k T / m) sin(2 pi x / Lx)
  double poiseuille_force = 0;         // +F along x where y < Ly/2, -F above (reverse Poiseuille)
  InitialVelocities initial_velocities = InitialVelocities::Maxwell;
  InitialInternalEnergy initial_internal_energy = InitialInternalEnergy::Equilibrium;

  EnergyModel energy = EnergyModel::Dpde;
  double cv = 200.0; // particle heat capacity, in units of k

  ConservativeForce conservative = ConservativeForce::None;
  double a0 = 15.0;
  double conservative_cutoff = 1.0;
  double reference_temperature = 1.0; // T-bar of 002's a_T

  Friction friction = Friction::ConstantSigma;
  double sigma = 3.0;
  double gamma = 4.5;
  WeightParameters dissipation{1.0, 0.5};

  HeatLaw heat = HeatLaw::Inverse;
  HeatCoefficient heat_coefficient = HeatCoefficient::Seed002;
  double kappa0 = 0.001;
  WeightParameters heat_weight{1.0, 0.5};
  double linear_noise_factor =
      2.0; // linear law: Lambda^2 = factor k kappa theta_i theta_j (2: FDT)

  std::vector<HeatSlab> heat_slabs;    // hot then cold: equal and opposite powers
  std::array<WallPair, 3> walls;       // per direction
  double wall_a0 = 25, wall_range = 1; // seed 000's walls: repulsion and range
  double wall_density = 0;             // half-space walls: rho_w; 0: the fluid's density
  bool wall_diffuse = true;            // half-space thermal walls re-emit what hits them at T_w
  std::array<double, 3> gravity{{0, 0, 0}};
  bool has_walls() const;
  bool has_wall_model(WallModel m) const; // some wall of the scene acts this way
  double wall_material_density() const;   // rho_w, the fluid's density where none is given

  // Diagnostics
  std::array<int, 3> bins{{1, 1, 1}}; // field bins per direction (1: averaged over it)
  long sample_interval = 10;
  int blocks = 20; // block averages for standard errors
  int histogram_bins = 60;
  int rdf_bins = 100;
  int correlation_samples = 100; // VACF / MSD window, in sample intervals

  double largest_cutoff() const;
  long particle_count() const;
};

const char* to_string(Integrator);

} // namespace twinflow::particle
