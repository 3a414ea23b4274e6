#pragma once
// Plain parameters of the continuum twin, filled from the case file by study/case_file (or directly
// by tests). Units are the particle solver's: lengths in rc, temperature in T0 (k = 1), mass in m,
// time in tau. Number density n, so mass density n m and heat capacity per volume n c_p.

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace twinflow::continuum {

enum class Model { Boussinesq, HeatConduction, LowMach, Compressible };
// The models whose walls take Kapitza conductances and Navier slip (Robin conditions).
inline bool has_robin_walls(Model m) {
  return m == Model::Boussinesq || m == Model::Compressible;
}
// Steady: the stationary equations (Newton). Transient: march in time from the initial state to
// end_time (Boussinesq: BDF2, low-Mach: implicit Euler, heat conduction: theta scheme).
enum class Mode { Steady, Transient };
// Equation of state p = n k T + n^2 B, B = b0 + b1 k T + b2 (n - n_ref)
// (continuum/compressible_eos.hpp): the ideal DPDE fluid at B = 0 (000:(3.20)); with a
// conservative force, the transport stage's fit to its bulk runs around n_ref (Groot & Warren
// 1997's p = n k T + alpha a n^2 is B = alpha a). The low-Mach model takes the ideal fluid only.
struct EquationOfState {
  double b0 = 0, b1 = 0, b2 = 0, n_ref = 1;
  bool ideal() const { return b0 == 0 && b1 == 0 && b2 == 0; }
};
// Boussinesq linear solver: direct (serial UMFPACK) or iterative (p4est + Trilinos FGMRES, 3D);
// automatic: direct in 2D, iterative in 3D.
enum class LinearSolver { Automatic, Direct, Iterative };

// coefficient(T) = value_at_reference * (T / reference_temperature)^exponent; exponent 0: constant.
// (seed 000 uses kappa = kappa_0 (T/T_0)^-2.) With sutherland_temperature S > 0 Sutherland's law
// instead: value_at_reference * (T/T_ref)^(3/2) (T_ref + S) / (T + S) (Sutherland 1893; the form
// of Le Quere et al. 2005, anchored at T_ref instead of T* = 273 K: the same law).
// The compressible twin also gives it a density dependence: a part f = pair_fraction (at n_ref,
// T_ref) is carried by pair terms and goes as n^2 (DPD friction for eta, pair heat conduction
// for kappa: both n^2 integrals, 000:(3.25), Marsh, Backx & Ernst 1997), with its own power of T;
// the rest rides on moving particles, whose mean free path goes as 1/n, and does not depend on
// n: coefficient(n, T) = (1 - f) at(T) + f value_at_reference (n/n_ref)^2 (T/T_ref)^pair_exponent.
// n_ref is the box's mean density (the transport stage's).
struct PowerLaw {
  double value_at_reference = 1.0;
  double exponent = 0.0;
  double sutherland_temperature = 0.0; // S in units of T0; 0: the power law above
  double pair_fraction = 0.0;          // f in [0, 1] at (n_ref, T_ref); 0: none
  double pair_exponent = 0.0;          // the pair part's power of T

  // The coefficient at the reference density n_ref (Boussinesq, low-Mach, heat conduction, and
  // the compressible twin's Nu scale): its particles' part and its pair part.
  double at(double T, double T_ref) const {
    if (pair_fraction == 0.0) return particles_part(T, T_ref);
    return (1.0 - pair_fraction) * particles_part(T, T_ref) + pair_part(T, T_ref);
  }
  // d coefficient / dT at n_ref, for the exact Newton Jacobian.
  double derivative(double T, double T_ref) const {
    const double particles = particles_derivative(T, T_ref);
    if (pair_fraction == 0.0) return particles;
    return (1.0 - pair_fraction) * particles + pair_exponent * pair_part(T, T_ref) / T;
  }
  bool is_constant() const {
    return exponent == 0.0 && sutherland_temperature <= 0.0 &&
           (pair_fraction == 0.0 || pair_exponent == 0.0);
  }
  // The value at (n, T) and its derivatives in T and n (the exact Newton Jacobian).
  struct AtState {
    double value, d_T, d_n;
  };
  AtState at(double n, double T, double n_ref, double T_ref) const {
    const double rest = 1.0 - pair_fraction;
    AtState s{rest * particles_part(T, T_ref), rest * particles_derivative(T, T_ref), 0.0};
    if (pair_fraction == 0.0) return s;
    const double r = n / n_ref;
    const double pair = r * r * pair_part(T, T_ref);
    s.value += pair, s.d_T += pair_exponent * pair / T, s.d_n = 2.0 * pair / n;
    return s;
  }

private:
  // value_at_reference (T/T_ref)^exponent, or Sutherland's law.
  double particles_part(double T, double T_ref) const {
    if (sutherland_temperature > 0.0) {
      const double S = sutherland_temperature;
      return value_at_reference * std::pow(T / T_ref, 1.5) * (T_ref + S) / (T + S);
    }
    return exponent == 0.0 ? value_at_reference
                           : value_at_reference * std::pow(T / T_ref, exponent);
  }
  double particles_derivative(double T, double T_ref) const {
    if (sutherland_temperature > 0.0)
      return particles_part(T, T_ref) * (1.5 / T - 1.0 / (T + sutherland_temperature));
    return exponent == 0.0 ? 0.0 : exponent * particles_part(T, T_ref) / T;
  }
  // f value_at_reference (T/T_ref)^pair_exponent: the pair part at n_ref.
  double pair_part(double T, double T_ref) const {
    return pair_fraction * value_at_reference * std::pow(T / T_ref, pair_exponent);
  }
};

// Boundaries of one box direction: walls at x_d = 0 (side 0) and x_d = L_d (side 1), or periodic.
struct DirectionBoundary {
  bool periodic = true;
  std::array<bool, 2> fixed_temperature{{true, true}}; // Dirichlet (thermal wall) or flux wall
  std::array<double, 2> temperature{{1.0, 1.0}};       // of a fixed-temperature wall
  std::array<double, 2> heat_flux{{0.0, 0.0}};         // into the domain, of a flux wall
  bool no_slip = true;                                 // else free slip (no normal flux)
  // Kapitza (Robin) condition of a fixed-temperature wall: with h != 0 the heat flux into the
  // domain is h (T_wall - T) instead of T = T_wall (the particle walls' temperature jump).
  // Boussinesq and compressible. h < 0 (the nominal twin's walls from theory, wall_layer.hpp):
  // a wall that holds the fluid of its layer at T_wall, so that the bulk's profile reaches T_wall
  // kappa / |h| inside the domain (docs/theory.md, "The wall layer"). (Last: aggregate
  // initialisers of the fields above stay valid.)
  std::array<double, 2> kapitza_conductance{{0.0, 0.0}};
  bool robin(int side) const { return fixed_temperature[side] && kapitza_conductance[side] != 0; }
  // Inverse law (the particle wall's own, docs/theory.md): q = h T_wall^2 (1/T - 1/T_wall), the
  // same h at T = T_wall, larger where the fluid is colder. Else linear: q = h (T_wall - T).
  bool kapitza_inverse = false;
  // The conductances' standard errors (not used by the solver: the continuum stage moves each
  // h_K by its error in an extra solve, for the twin's heat-flux error).
  std::array<double, 2> kapitza_conductance_stderr{{0.0, 0.0}};
  // Navier slip of a no-slip wall: with b > 0 no normal flow and the tangential traction
  // eta(T) u_t / b (Navier 1823; the particle wall's friction over its layer). Boussinesq and
  // compressible.
  std::array<double, 2> slip_length{{0.0, 0.0}};
  // Kinetic slip of a no-slip thermal wall (ContinuumParameters::wall_friction): the traction
  // beta(n, T) u_t of the particle wall the twin stands for, instead of eta / b.
  std::array<bool, 2> kinetic_slip{{false, false}};
  // A layer the particle wall holds at T_wall, this deep (rc; its theory's b < 0): the twin's
  // wall stands that far inside the scene's plane, T = T_wall there (docs/theory.md, "The wall
  // layer"); set with move_walls_in by study::take_wall_jumps.
  std::array<double, 2> pinned_depth{{0.0, 0.0}};
  bool navier(int side) const { return no_slip && (slip_length[side] > 0 || kinetic_slip[side]); }
  double kapitza_flux(int side, double T) const { // heat flux into the domain at fluid T
    const double h = kapitza_conductance[side], Tw = temperature[side];
    return kapitza_inverse ? h * Tw * Tw * (1 / T - 1 / Tw) : h * (Tw - T);
  }
  double kapitza_flux_derivative(int side, double T) const { // d(kapitza_flux)/dT
    const double h = kapitza_conductance[side], Tw = temperature[side];
    return kapitza_inverse ? -h * Tw * Tw / (T * T) : -h;
  }
};

// The friction per area of a particle wall that re-emits what reaches it diffusely (Maxwell's
// wall) and pulls on the fluid beside it with the DPD friction of its half-space (references.md,
// "Kinetic slip at a particle wall"): with the slip velocity u_s and the shear rate S at the wall,
// eta S = beta u_s, beta(n, T) = 2 n [sqrt(m k T / 2 pi) + rho_w I_d gamma(T, T_w)].
struct WallFriction {
  double wall_density = 0;   // rho_w
  double tangent_moment = 0; // I_d = int_{r.n > 0} (r.n) w_D(r) (e.t)^2 d^d r
  // gamma(T, T_w) = gamma_constant + gamma_inverse (1/T + 1/T_w) (000:(2.37) at the pair's
  // harmonic-mean temperature: gamma_inverse = sigma^2 / 4)
  double gamma_constant = 0, gamma_inverse = 0;
  // The particle walls this holds for: no-slip thermal half-space walls with diffuse reflection
  // (per direction, lower and upper); take_kinetic_slip turns them on.
  std::array<std::array<bool, 2>, 3> diffuse{};
  struct AtState {
    double value, d_T, d_n;
  };
  AtState at(double n, double T, double T_wall, double mass) const {
    // Maxwell (1879): the momentum flux onto the wall per drift velocity, m n <v_n+>, over n
    const double kinetic = std::sqrt(mass * T / (2 * M_PI));
    const double pair =
        wall_density * tangent_moment * (gamma_constant + gamma_inverse * (1 / T + 1 / T_wall));
    const double d_pair = -wall_density * tangent_moment * gamma_inverse / (T * T);
    return {2 * n * (kinetic + pair), 2 * n * (0.5 * kinetic / T + d_pair), 2 * (kinetic + pair)};
  }
};

// A slab x_d in [lower, upper] that injects `power` (energy per time; < 0: a sink) uniformly:
// the particle twin's hot and cold heat-exchange slabs.
struct HeatSlab {
  int direction = 0;
  double lower = 0.0, upper = 0.0;
  double power = 0.0;
};

struct ContinuumParameters {
  // Scene
  int dim = 2;
  std::array<double, 3> box{{1, 1, 1}};
  Model model = Model::Boussinesq;
  std::array<DirectionBoundary, 3> boundary;
  std::array<double, 3> gravity{{0, 0, 0}};

  // Material, particle units
  double number_density = 1.0; // n; low-Mach: the mean N/V of the closed box (its mass)
  // Compressible and low-Mach: the particles N of the twin's box; 0: number_density x its volume
  // (walls moved in over pinned layers leave those layers' particles out).
  double particle_count = 0;
  double particle_mass = 1.0;         // m
  double heat_capacity = 1.0;         // c_p per particle (units of k)
  double thermal_expansion = 0.0;     // alpha (1/T0); low-Mach: 1/T_ref (ideal gas)
  double reference_temperature = 1.0; // T_ref of Boussinesq and of the power laws
  PowerLaw viscosity{1.0, 0.0};       // eta(T)
  PowerLaw conductivity{1.0, 0.0};    // kappa(T)
  WallFriction wall_friction;         // of the walls with kinetic slip
  std::vector<HeatSlab> heat_slabs;
  // Low-Mach and compressible models: n(P, T) or p(n, T) (continuum/low_mach_eos.hpp,
  // compressible_eos.hpp). Non-ideal: compressible only; c_p above stays the ideal fluid's (the
  // excess pressure adds no heat capacity at constant volume, see compressible_eos.hpp).
  EquationOfState equation_of_state;
  // Compressible model: bulk viscosity zeta (units of eta), constant; the stress is
  // 2 eta S + (zeta - (2/d) eta) div u I. 0: the ideal gas's kinetic part (none for particles
  // without internal degrees of freedom in their kinetic stress); the DPD friction adds
  // zeta_D = (1 + 2/d) eta_D (Marsh, Backx & Ernst 1997) where eta_D is eta's dissipative part.
  double bulk_viscosity = 0.0;

  // Mesh: `cells` coarse cells per direction, then `refinements` global refinements.
  std::array<unsigned, 3> cells{{8, 8, 8}};
  int refinements = 2; // the problem is solved on every level (nested iteration: mesh study)
  // A periodic direction given one coarse cell is taken as uniform (a thin periodic slice: the
  // flow does not vary along it); refinement leaves it one cell thick.
  bool uniform_along(int d) const { return boundary[d].periodic && cells[d] == 1; }
  bool thin_slice() const {
    for (int d = 0; d < dim; ++d)
      if (uniform_along(d)) return true;
    return false;
  }

  // Nonlinear solver
  double newton_tolerance = 1e-9; // on the relative update |dx| / |x|
  int max_newton_iterations = 25;
  double continuation_start_rayleigh = 1e4; // larger Ra is reached by steps of 10 from here
  LinearSolver linear_solver = LinearSolver::Automatic;
  // Automatic: the direct solver in 2D and for a thin 3D slice (2D-sized), else iterative.
  bool uses_iterative_solver() const {
    return model == Model::Boussinesq &&
           (linear_solver == LinearSolver::Iterative ||
            (linear_solver == LinearSolver::Automatic && dim == 3 && !thin_slice()));
  }

  // In time (mode Transient): the step is adjusted to end_time / round(end_time / time_step).
  Mode mode = Mode::Steady;
  double end_time = 0.0;
  double time_step = 0.01;
  double theta = 0.5; // heat conduction: 0.5 Crank-Nicolson, 1 implicit Euler (Boussinesq: BDF2)
  // muparser expression in x, y, z; "": T_ref (heat conduction), the conduction profile between
  // the walls of the heated direction (Boussinesq, which starts at rest).
  std::string initial_temperature = "";
  // Boussinesq in time: field snapshots at these times (the nearest step) and every
  // `snapshot_every` steps (0: none), always at the end; a time-series row (Nu, kinetic energy,
  // max speed) every `series_every` steps and at the end.
  std::vector<double> snapshot_times;
  int snapshot_every = 0;
  int series_every = 1;
  bool transient() const { return mode == Mode::Transient; }

  // Output
  std::array<unsigned, 3> bins{{10, 10, 10}};
  // The bins cover [bin_lower, bin_lower + bin_box] of this twin's coordinates (bin_box 0: the
  // domain [0, box]). A twin whose walls sit inside the scene's, at the particle walls' effective
  // positions delta, bins over the scene's box: bin_lower = -delta_lower, bin_box = scene box.
  std::array<double, 3> bin_lower{{0, 0, 0}}, bin_box{{0, 0, 0}};
  double bin_extent(int d) const { return bin_box[d] > 0 ? bin_box[d] : box[d]; }
  std::vector<std::array<double, 3>> probe_points;
  int profile_samples = 401; // samples per mid-line before zooming in on the maximum
  bool write_fields = true;  // HDF5 + XDMF

  // Derived material numbers
  double mass_density() const { return number_density * particle_mass; }
  double heat_capacity_per_volume() const { return number_density * heat_capacity; }
};

// Kinetic slip at the twin's no-slip walls that stand for diffuse particle walls
// (WallFriction::diffuse), where the model has Navier walls and no slip length is given;
// returns how many walls took it.
int take_kinetic_slip(ContinuumParameters& p);

// Dimensionless groups of the scene, at the reference temperature.
struct DimensionlessNumbers {
  double kinematic_viscosity = 0;    // nu = eta / (n m)
  double thermal_diffusivity = 0;    // chi = kappa / (n c_p)
  double rayleigh = 0;               // Ra = g alpha dT H^3 / (nu chi)
  double prandtl = 0;                // Pr = nu / chi
  int heated_direction = -1;         // direction whose two walls hold different temperatures
  double height = 0;                 // H: box length of the heated direction (else box[0])
  double temperature_difference = 0; // dT = T_lower_wall - T_upper_wall of that direction
  double velocity_scale = 0;         // chi / H (de Vahl Davis 1983 scaling)
  double conduction_flux = 0;        // pure-conduction heat flux per area across H
  double epsilon = 0; // (T_hot - T_cold) / (T_hot + T_cold) of the heated direction (Le Quere 2005)
};

DimensionlessNumbers dimensionless_numbers(const ContinuumParameters&);

// Heat source per volume at x: the sum of the slabs containing x, power / slab volume.
double heat_source_density(const ContinuumParameters&, const std::array<double, 3>& x);

// Coefficients that give a cavity of height H = box[heated direction] the target Ra and Pr at
// n = m = c_p = 1 and chi = 1 (for tests): nu = Pr, g alpha dT = Ra Pr chi^2 / H^3.
void set_rayleigh_prandtl(ContinuumParameters&, double rayleigh, double prandtl);

// Throws std::invalid_argument naming the first inconsistent value.
void check(const ContinuumParameters&);

} // namespace twinflow::continuum
