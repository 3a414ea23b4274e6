#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "continuum/twin_walls.hpp"
#include "particle/wall_weights.hpp"
#include "study/case_file/case_file.hpp"
#include "study/twin_model.hpp"

namespace twinflow::study {

namespace {
const char* const kAxes = "xyz";
const std::string s = "Continuum/";

// "8" -> 8 cells along the shortest box edge, the others in proportion; "16, 8" -> per direction.
std::array<unsigned, 3> cells_per_direction(const Registry& r, const std::string& path,
                                            const scene::SceneParameters& scene) {
  const auto values = r.get_doubles(path);
  std::array<unsigned, 3> cells{{1, 1, 1}};
  if (values.size() == 1) {
    double shortest = scene.box[0];
    for (int d = 1; d < scene.dim; ++d) shortest = std::min(shortest, scene.box[d]);
    for (int d = 0; d < scene.dim; ++d)
      cells[d] =
          std::max(1u, static_cast<unsigned>(std::lround(values[0] * scene.box[d] / shortest)));
  } else {
    r.require(static_cast<int>(values.size()) == scene.dim, path,
              "one value, or one per dimension (" + std::to_string(scene.dim) + ")");
    for (int d = 0; d < scene.dim; ++d) cells[d] = static_cast<unsigned>(values[d]);
  }
  return cells;
}

std::vector<std::array<double, 3>> points(const Registry& r, const std::string& path, int dim,
                                          const std::array<double, 3>& box) {
  std::vector<std::array<double, 3>> out;
  std::istringstream list(r.get(path));
  std::string item;
  while (std::getline(list, item, ';')) {
    if (dealii::Utilities::trim(item).empty()) continue;
    std::vector<double> x;
    try {
      x = dealii::Utilities::string_to_double(dealii::Utilities::split_string_list(item));
    } catch (const std::exception&) {
      r.fail(path, "points 'x, y[, z]' separated by ';'");
    }
    r.require(static_cast<int>(x.size()) == dim, path,
              "points of " + std::to_string(dim) + " coordinates separated by ';'");
    std::array<double, 3> p{{0, 0, 0}};
    for (int d = 0; d < dim; ++d) {
      r.require(x[d] >= 0 && x[d] <= box[d], path, "points inside the box");
      p[d] = x[d];
    }
    out.push_back(p);
  }
  return out;
}

// Continuum/Wall slip. The wall friction of the particle walls is always worked out (`run`
// turns auto's kinetic slip on once its twin takes the transport stage's coefficients).
void resolve_wall_slip(const Registry& r, const particle::ParticleParameters& particle,
                       bool slip_lengths_given, continuum::ContinuumParameters& c) {
  auto& f = c.wall_friction;
  for (int d = 0; d < c.dim; ++d)
    for (int side = 0; side < 2; ++side) {
      const auto& wall = particle.walls[d];
      f.diffuse[d][side] = wall.present && wall.no_slip && wall.thermal[side] &&
                           wall.model[side] == particle::WallModel::HalfSpace &&
                           particle.wall_diffuse;
    }
  f.wall_density = particle.wall_material_density();
  f.tangent_moment = particle::tangent_friction_moment(c.dim, particle.dissipation.cutoff,
                                                       particle.dissipation.exponent);
  // constant gamma: its Ito part against a wall, O(1/c_v) (pair_terms.hpp), left out
  if (particle.friction == particle::Friction::ConstantSigma)
    f.gamma_inverse = 0.25 * particle.sigma * particle.sigma; // 000:(2.37)
  else
    f.gamma_constant = particle.gamma;

  const std::string choice = r.get(s + "Wall slip");
  if (choice == "no-slip") return;
  r.require(!slip_lengths_given || choice == "auto", s + "Wall slip",
            "no-slip or auto when Slip lengths are given (they take the walls)");
  if (choice == "auto") {
    // a twin that stands for the particle fluid: it takes the transport stage's coefficients
    if (r.get(s + "Coefficients/Source") == "transport" && !slip_lengths_given)
      continuum::take_kinetic_slip(c);
    return;
  }
  r.require(continuum::has_robin_walls(c.model), s + "Wall slip",
            "no-slip or auto unless Continuum/Model = boussinesq or compressible");
  const int kinetic_walls = continuum::take_kinetic_slip(c);
  r.require(kinetic_walls > 0, s + "Wall slip",
            "auto or no-slip when no wall is a no-slip thermal half-space wall with diffuse "
            "reflection");
}
} // namespace

namespace {
// The model, and how `auto` chooses it.
void declare_model(Registry& r) {
  using namespace dealii::Patterns;
  r.declare(s + "Model", "auto", Selection("auto|boussinesq|low-mach|compressible|heat-conduction"),
            "Equations of the continuum twin: Boussinesq natural convection (Taylor-Hood Q2/Q1 + "
            "Q2 temperature, Newton); low-Mach-number convection of a variable-density ideal gas "
            "in the closed box (n = P/(k T), P from the box's mass N = Scene density x volume, "
            "for large temperature differences; Thermal expansion is then 1/T_ref and the key is "
            "ignored); compressible Navier-Stokes of the ideal DPDE fluid (unknowns n, u, T; "
            "p = n k T, c_V = c_p - k; the particle count N fixed; stratified by gravity; "
            "Thermal expansion ignored as for low-mach); or heat conduction without flow. auto: "
            "compressible when the scene's stratification g H / c^2 (c^2 = k T / m at the "
            "thermal walls' mean temperature) exceeds Compressible threshold, else low-mach "
            "when the thermal walls' epsilon = (T_max - T_min) / (T_max + T_min) exceeds "
            "Low-Mach threshold (the Boussinesq approximation is wrong to first order in "
            "epsilon), else boussinesq.");
  r.declare(s + "Low-Mach threshold", "0.2", Double(0, 1),
            "Model = auto: the thermal walls' epsilon above which the twin is low-Mach (0.2: "
            "walls at T0 (1 -+ 0.2), a temperature ratio of 1.5); compressible instead for a "
            "fluid with a conservative force (the low-Mach twin takes the ideal gas's p).");
  r.declare(s + "Compressible threshold", "0.1", Double(0),
            "Model = auto: the stratification g H / c^2 above which the twin is compressible "
            "(0.1: the density falls by ~10% from bottom to top, which the low-Mach and "
            "Boussinesq twins do not have).");
}

// The twin's walls: Kapitza jumps, positions, slip.
void declare_walls(Registry& r) {
  using namespace dealii::Patterns;
  r.declare(s + "Kapitza conductances", "", List(Double(0), 0, 6),
            "Kapitza (Robin) walls of the Boussinesq and compressible twins: h_K per wall in the "
            "order x lower, "
            "x upper, y lower, y upper, z lower, z upper (k T0 / (rc^(d-1) tau T0)); a thermal "
            "wall with h_K > 0 takes the heat flux h_K (T_wall - T) instead of T = T_wall; 0 or "
            "absent: T = T_wall. `run`'s calibrated twin sets them from the particle walls' "
            "measured heat flux and temperature jump.");
  r.declare(s + "Kapitza conductance errors", "", List(Double(0), 0, 6),
            "Standard errors of the Kapitza conductances, in the same order. The twin's heat-flux "
            "error then includes each h_K moved by its error (one more solve per wall). `run`'s "
            "calibrated twin sets them from the particle walls' heat-flux and fluid-temperature "
            "errors.");
  r.declare(
      s + "Wall positions", "", List(Double(0), 0, 6),
      "Distance of each wall of the twin inside the scene's wall plane (rc), in the order x "
      "lower, x upper, y lower, ...: the twin's domain is the scene's box less these, its "
      "output bins still the scene's. `run`'s calibrated twin sets them to the particle "
      "walls' effective positions (Compare/Effective walls); 0 or absent: the scene's walls.");
  r.declare(s + "Slip lengths", "", List(Double(0), 0, 6),
            "Navier slip b (rc) per wall, in the order x lower, x upper, y lower, ...: a no-slip "
            "wall with b > 0 lets the fluid slip with the tangential traction eta u_t / b "
            "(Boussinesq and compressible; all of the twin's no-slip walls or none). `run`'s "
            "calibrated twin "
            "sets them from the particle walls' measured friction (Compare/Wall slip); 0 or "
            "absent: no slip.");
  r.declare(s + "Wall slip", "auto", Selection("auto|no-slip|kinetic"),
            "Velocity at the twin's no-slip walls where no Slip lengths are given. kinetic: at "
            "each no-slip thermal wall of half-space particle walls with diffuse reflection, the "
            "particle wall's own friction per area beta(n, T) = 2 n [sqrt(m k T / 2 pi) + rho_w "
            "I_d gamma(T, T_w)] (Maxwell's diffuse wall and the wall material's DPD friction, "
            "docs/references.md \"Kinetic slip at a particle wall\"; slip length eta / beta, about "
            "0.1-0.3 rc), no slip at the others (bounce-back: no kinetic slip); Boussinesq and "
            "compressible. auto: where the twin stands for the particle fluid (it takes the "
            "transport stage's coefficients: `run`, `sweep`, Coefficients/Source = transport) "
            "and Model is Boussinesq or compressible, the slip length of the wall model's own "
            "slip layer at every no-slip half-space wall, diffuse or bounce-back (docs/theory.md, "
            "\"The slip layer\"), else no-slip (a continuum case of its own). `run`'s calibrated "
            "twin takes the measured slip lengths instead.");
  r.declare(
      s + "Wall jump", "auto", Selection("auto|none|theory"),
      "Temperature at the twin's thermal walls where no Kapitza conductances are given. theory: "
      "at each thermal wall of half-space particle walls, the Robin condition of the wall "
      "model's own layer (docs/theory.md, \"The wall layer\"): the extrapolation length b of "
      "the wall's pair conduction, friction and re-emission over the fluid's first cutoffs, "
      "computed from the case's wall parameters and the transport stage's fluid alone (nothing "
      "measured beside a wall); the conductance kappa / b, negative where the wall holds its "
      "layer at T_wall. auto: theory where the twin stands for the particle fluid (Coefficients/"
      "Source = transport: `run`, `sweep`), else none. none: T = T_wall. `run`'s calibrated "
      "twin takes the measured jumps instead.");
  r.declare(s + "Kapitza law", "linear", Selection("linear|inverse"),
            "The heat flux into the fluid at a Kapitza wall: linear, h_K (T_wall - T); inverse, "
            "h_K T_wall^2 (1/T - 1/T_wall), the particle wall's own law (docs/theory.md: the "
            "inverse heat law against a wall particle at T_wall), whose conductance grows where "
            "the fluid is colder; the same h_K at T = T_wall. `run`'s calibrated twin sets h_K "
            "for the law chosen here.");
}

void declare_mode(Registry& r) {
  using namespace dealii::Patterns;
  r.declare(s + "Mode", "steady", Selection("steady|transient"),
            "steady: the stationary state (Newton, with continuation in Ra and the mesh study "
            "over the refinement levels); transient: march in time from the initial state to "
            "Time/End time on the finest mesh (Boussinesq: BDF2 with a BDF1 first step, inertia "
            "included, one Newton solve per step; low-Mach: implicit Euler from rest at the "
            "reference temperature; compressible: BDF2 from rest, the conduction profile and the "
            "isothermal column at the reference temperature; heat conduction: the theta "
            "scheme). Boussinesq in time "
            "writes time_series.csv (Nu, kinetic energy, max speed) and field snapshots "
            "(fields.xdmf, a ParaView time series).");
}

// eta and kappa: the value at T_ref, a power law in T or Sutherland's law, a pair part.
void declare_temperature_laws(Registry& r, const std::string& c) {
  using namespace dealii::Patterns;
  struct TemperatureLaw {
    const char* name;
    const char* value_doc;
    const char* exponent_doc;
    const char* sutherland_doc;
  };
  for (const TemperatureLaw& law :
       {TemperatureLaw{
            "Viscosity",
            "Shear viscosity eta at the reference temperature (particle units m/(rc tau)), > 0.",
            "eta = eta_0 (T/T_ref)^exponent; 0: constant.",
            "S > 0: Sutherland's law eta = eta_0 (T/T_ref)^(3/2) (T_ref + S)/(T + S) instead of "
            "the power law (units of T0; Le Quere et al. 2005: S = 110.5 K / T0); 0: off."},
        TemperatureLaw{
            "Conductivity",
            "Thermal conductivity kappa at the reference temperature (k/(rc tau)), > 0.",
            "kappa = kappa_0 (T/T_ref)^exponent (seed 000: -2); 0: constant.",
            "S > 0: Sutherland's law for kappa as for the viscosity (constant Pr); 0: off."}}) {
    const std::string name = c + law.name;
    r.declare_positive(name, "1", law.value_doc);
    r.declare(name + " exponent", "0", Double(), law.exponent_doc);
    r.declare(name + " Sutherland temperature", "0", Double(0), law.sutherland_doc,
              "a number >= 0 (0: off)");
    r.declare(name + " pair fraction", "0", Double(0, 1),
              "Compressible model: the part f of the value at the scene's density n0 carried by "
              "pair terms, which go as n^2 (DPD friction, pair heat conduction); the value at n "
              "is (1 - f) times the above + f value (n/n0)^2 (T/T_ref)^(pair exponent). 0: no "
              "density dependence (the transport stage does not measure one yet).");
    r.declare(name + " pair exponent", "0", Double(),
              "Compressible model: the pair part's power of T (the exponent above is then the "
              "rest's).");
  }
}

// eta, kappa, c_p, alpha and the equation of state, or where they come from.
void declare_coefficients(Registry& r) {
  using namespace dealii::Patterns;
  const std::string c = s + "Coefficients/";
  r.declare(c + "Source", "case", Selection("case|transport"),
            "case: the values below; transport: eta, kappa, c_p and alpha at the reference "
            "temperature from RUNDIR/transport/summary.json (run `twinflow transport` first): "
            "measured where Transport/Source = measured and available, else the estimate with "
            "the measured g(r). The exponents below still apply.");
  declare_temperature_laws(r, c);
  r.declare_positive(
      c + "Heat capacity", "1",
      "Heat capacity at constant pressure per particle c_p (units of k); n c_p per volume, "
      "> 0.");
  r.declare(c + "Thermal expansion", "0", Double(0),
            "Thermal expansion coefficient alpha (1/T0) of the Boussinesq buoyancy.");
  r.declare(c + "Bulk viscosity", "0", Double(0),
            "Compressible model: bulk viscosity zeta (units of eta), constant; the stress is "
            "2 eta S + (zeta - (2/d) eta) div u I. 0: none, the ideal gas's kinetic part; the "
            "DPD friction adds zeta_D = (1 + 2/d) eta_D where eta_D is the dissipative part of "
            "eta (central pair friction; Marsh, Backx & Ernst 1997), which the twin takes from "
            "the transport stage's estimate with Source = transport.");
  r.declare(c + "Excess pressure", "0, 0, 0", List(Double(), 3, 3),
            "Compressible model: b0, b1, b2 of the equation of state p = n k T + n^2 (b0 + b1 k T "
            "+ b2 (n - n0)), n0 the scene's density; 0, 0, 0: the ideal DPDE fluid. With Source = "
            "transport, a fluid with a conservative force takes the transport stage's fit to its "
            "bulk runs instead.");
  r.declare_positive(c + "Reference temperature", "1",
                     "T_ref of the buoyancy and of the power laws (units of T0), > 0.");
}

// The mesh and the nonlinear and linear solvers.
void declare_mesh_and_solver(Registry& r) {
  using namespace dealii::Patterns;
  const std::string m = s + "Mesh/";
  r.declare(m + "Cells", "8", List(Integer(1, 4096), 1, 3),
            "Coarse cells: one value for the shortest box edge (others in proportion), or one per "
            "direction. A periodic direction given 1 stays one cell thick through the "
            "refinements: a thin periodic slice whose flow is uniform along it (e.g. 8, 1, 8).");
  r.declare(m + "Refinements", "2", Integer(0, 10),
            "Global refinements of the coarse mesh. Boussinesq solves on every level (nested "
            "iteration) and records the mesh study.");

  const std::string n = s + "Solver/";
  r.declare(n + "Newton tolerance", "1e-9", Double(0),
            "Newton stops when the relative update of velocity and temperature is below this.");
  r.declare(n + "Max Newton iterations", "25", Integer(1, 1000), "Per continuation step.");
  r.declare_positive(
      n + "Continuation start Rayleigh", "1e4",
      "Larger Ra is reached in factor-10 steps starting here (halved on failure), > 0.");

  r.declare(n + "Linear solver", "auto", Selection("auto|direct|iterative"),
            "Boussinesq: direct (UMFPACK, one process) or iterative (p4est + Trilinos FGMRES with "
            "a block AMG preconditioner, 3D only, runs under mpirun); auto: direct in 2D, "
            "iterative in 3D.");
}

// In time, the initial state and the output.
void declare_time_and_output(Registry& r) {
  using namespace dealii::Patterns;
  const std::string t = s + "Time/";
  r.declare(t + "End time", "0", Double(0),
            "Mode transient: simulated time (tau), > 0 (unused when steady).");
  r.declare_positive(
      t + "Time step", "0.01",
      "Mode transient: time step (tau), > 0; adjusted to End time / round(End time / "
      "Time step).");
  r.declare(t + "Theta", "0.5", Double(0.5, 1),
            "Heat conduction in time: theta scheme, 0.5 Crank-Nicolson, 1 implicit Euler "
            "(Boussinesq uses BDF2).");
  r.declare(t + "Snapshot times", "", List(Double(0)),
            "Boussinesq in time: times (tau) of field snapshots, each at the nearest step, "
            "comma-separated, within [0, End time]; the end time is always written.",
            "times in [0, End time], comma-separated");
  r.declare(t + "Snapshot every", "0", Integer(0),
            "Boussinesq in time: a field snapshot every this many steps, from the initial state "
            "on; 0: none besides Snapshot times and the end.");
  r.declare(t + "Series every", "1", Integer(1),
            "Boussinesq in time: a row of time_series.csv (Nu, kinetic energy, max speed) every "
            "this many steps (and at the end), >= 1.");
  r.declare(s + "Initial temperature", "", Anything(),
            "Mode transient: initial T as a muparser expression in x, y, z (constants pi, Lx, "
            "Ly, Lz); empty: the reference temperature (heat conduction), the conduction profile "
            "between the walls of the heated direction (Boussinesq, which starts at rest).");

  const std::string o = s + "Output/";
  r.declare(o + "Probe points", "", Anything(),
            "Points 'x, y[, z]' separated by ';' where all fields are recorded.");
  r.declare(o + "Write fields", "true", Bool(), "Write fields.h5 + fields.xdmf (ParaView).");
  r.declare(o + "Profile samples", "401", Integer(3, 1000000),
            "Samples per mid-line before the velocity maximum is refined (10x zooms).");
}
} // namespace

void declare_continuum(Registry& r) {
  declare_model(r);
  declare_walls(r);
  declare_mode(r);
  declare_coefficients(r);
  declare_mesh_and_solver(r);
  declare_time_and_output(r);
}

namespace {
// The model: as named, or chosen by the scene (study/twin_model.hpp).
continuum::Model resolve_model(const Registry& r, const scene::SceneParameters& scene,
                               const particle::ParticleParameters& particle) {
  const std::string model = r.get(s + "Model");
  if (model == "auto")
    return automatic_model(
        scene, particle.mass, particle.conservative != particle::ConservativeForce::None,
        r.get_double(s + "Low-Mach threshold"), r.get_double(s + "Compressible threshold"));
  return model == "heat-conduction" ? continuum::Model::HeatConduction
         : model == "low-mach"      ? continuum::Model::LowMach
         : model == "compressible"  ? continuum::Model::Compressible
                                    : continuum::Model::Boussinesq;
}

// The scene's boundaries as the twin's, with the case's Kapitza conductances and their errors.
void resolve_thermal_walls(const Registry& r, const scene::SceneParameters& scene,
                           continuum::ContinuumParameters& c) {
  for (int d = 0; d < 3; ++d) {
    const auto& from = scene.boundary[d];
    auto& to = c.boundary[d];
    to.periodic = from.periodic || d >= scene.dim;
    to.fixed_temperature = from.thermal; // adiabatic: zero-flux wall
    to.temperature = from.temperature;
    to.heat_flux = {{0.0, 0.0}};
    to.no_slip = from.no_slip;
  }
  const std::vector<double> kapitza = r.get_doubles(s + "Kapitza conductances");
  for (std::size_t w = 0; w < kapitza.size(); ++w) {
    const int d = static_cast<int>(w / 2), side = static_cast<int>(w % 2);
    r.require(d < scene.dim, s + "Kapitza conductances", "at most 2 x dimension values");
    if (kapitza[w] == 0) continue;
    r.require(!c.boundary[d].periodic && c.boundary[d].fixed_temperature[side],
              s + "Kapitza conductances",
              "0 for periodic directions and adiabatic walls (h_K > 0 only at thermal walls)");
    r.require(continuum::has_robin_walls(c.model), s + "Kapitza conductances",
              "0 unless Continuum/Model = boussinesq or compressible");
    c.boundary[d].kapitza_conductance[side] = kapitza[w];
  }
  const std::vector<double> kapitza_errors = r.get_doubles(s + "Kapitza conductance errors");
  for (std::size_t w = 0; w < kapitza_errors.size(); ++w) {
    const int d = static_cast<int>(w / 2), side = static_cast<int>(w % 2);
    r.require(d < scene.dim && (kapitza_errors[w] == 0 || c.boundary[d].robin(side)),
              s + "Kapitza conductance errors",
              "at most 2 x dimension values, > 0 only where a Kapitza conductance is");
    c.boundary[d].kapitza_conductance_stderr[side] = kapitza_errors[w];
  }
  for (auto& b : c.boundary) b.kapitza_inverse = r.get(s + "Kapitza law") == "inverse";
}

// Navier slip lengths (all no-slip walls or none), then the kinetic slip's choice.
void resolve_slip(const Registry& r, const scene::SceneParameters& scene,
                  const particle::ParticleParameters& particle, continuum::ContinuumParameters& c) {
  const std::vector<double> slips = r.get_doubles(s + "Slip lengths");
  int navier = 0, sticking = 0; // no-slip walls with and without a slip length
  for (std::size_t w = 0; w < slips.size(); ++w) {
    const int d = static_cast<int>(w / 2), side = static_cast<int>(w % 2);
    r.require(d < scene.dim &&
                  (slips[w] == 0 || (!c.boundary[d].periodic && c.boundary[d].no_slip)),
              s + "Slip lengths", "at most 2 x dimension values, > 0 only at no-slip walls");
    r.require(slips[w] == 0 || c.model == continuum::Model::Boussinesq ||
                  c.model == continuum::Model::Compressible,
              s + "Slip lengths", "0 unless Continuum/Model = boussinesq or compressible");
    c.boundary[d].slip_length[side] = slips[w];
  }
  for (int d = 0; d < scene.dim; ++d)
    for (int side = 0; side < 2; ++side)
      if (!c.boundary[d].periodic && c.boundary[d].no_slip)
        ++(c.boundary[d].navier(side) ? navier : sticking);
  r.require(navier == 0 || sticking == 0, s + "Slip lengths",
            "> 0 at all of the twin's no-slip walls or at none");
  resolve_wall_slip(r, particle, navier > 0, c);
}

// Walls moved in from the scene's planes (a calibrated twin at the effective positions).
std::array<double, 6> wall_distances(const Registry& r, const scene::SceneParameters& scene,
                                     const continuum::ContinuumParameters& c) {
  const std::vector<double> positions = r.get_doubles(s + "Wall positions");
  std::array<double, 6> distance{};
  for (std::size_t w = 0; w < positions.size(); ++w) {
    const int d = static_cast<int>(w / 2);
    r.require(d < scene.dim && (positions[w] == 0 || !c.boundary[d].periodic), s + "Wall positions",
              "at most 2 x dimension values, 0 in periodic directions");
    distance[w] = positions[w];
  }
  for (int d = 0; d < scene.dim; ++d)
    r.require(scene.box[d] - distance[2 * d] - distance[2 * d + 1] > 0.5 * scene.box[d],
              s + "Wall positions", "two walls' distances together below half the box length");
  return distance;
}

// Same units as the particle twin: n from the scene, m from the particle section.
void resolve_coefficients(const Registry& r, const scene::SceneParameters& scene,
                          const particle::ParticleParameters& particle,
                          continuum::ContinuumParameters& c) {
  c.number_density = scene.density;
  c.particle_mass = particle.mass;
  const std::string k = s + "Coefficients/";
  const auto law = [&](const std::string& name) {
    return continuum::PowerLaw{r.get_positive(k + name), r.get_double(k + name + " exponent"),
                               r.get_double(k + name + " Sutherland temperature"),
                               r.get_double(k + name + " pair fraction"),
                               r.get_double(k + name + " pair exponent")};
  };
  c.viscosity = law("Viscosity");
  c.conductivity = law("Conductivity");
  c.heat_capacity = r.get_positive(k + "Heat capacity");
  // The compressible twin's c_p > k is checked by the continuum stage on the c_p it takes (`run`
  // takes the transport stage's whatever the case says).
  c.thermal_expansion = r.get_double(k + "Thermal expansion");
  c.reference_temperature = r.get_positive(k + "Reference temperature");
  c.bulk_viscosity = r.get_double(k + "Bulk viscosity");
  const std::vector<double> excess = r.get_doubles(k + "Excess pressure");
  c.equation_of_state = {excess[0], excess[1], excess[2], scene.density};
}

void resolve_mesh_and_solver(const Registry& r, const scene::SceneParameters& scene,
                             continuum::ContinuumParameters& c) {
  c.cells = cells_per_direction(r, s + "Mesh/Cells", scene);
  c.refinements = static_cast<int>(r.get_integer(s + "Mesh/Refinements"));
  c.newton_tolerance = r.get_positive(s + "Solver/Newton tolerance");
  c.max_newton_iterations = static_cast<int>(r.get_integer(s + "Solver/Max Newton iterations"));
  c.continuation_start_rayleigh = r.get_positive(s + "Solver/Continuation start Rayleigh");
  const std::string solver = r.get(s + "Solver/Linear solver");
  c.linear_solver = solver == "direct"      ? continuum::LinearSolver::Direct
                    : solver == "iterative" ? continuum::LinearSolver::Iterative
                                            : continuum::LinearSolver::Automatic;
  r.require(!c.uses_iterative_solver() || scene.dim == 3, s + "Solver/Linear solver",
            "auto or direct in 2D (the iterative path is 3D only)");
}

void resolve_time(const Registry& r, continuum::ContinuumParameters& c) {
  c.mode = r.get(s + "Mode") == "transient" ? continuum::Mode::Transient : continuum::Mode::Steady;
  c.end_time = r.get_double(s + "Time/End time");
  r.require(c.transient() ? c.end_time > 0 : c.end_time == 0, s + "Time/End time",
            c.transient() ? "> 0 with Mode = transient"
                          : "0 with Mode = steady (set Mode = transient to march in time)");
  c.time_step = r.get_positive(s + "Time/Time step");
  c.theta = r.get_double(s + "Time/Theta");
  c.snapshot_times = r.get_doubles(s + "Time/Snapshot times");
  for (const double time : c.snapshot_times)
    r.require(time <= c.end_time, s + "Time/Snapshot times",
              "times in [0, End time], comma-separated");
  c.snapshot_every = static_cast<int>(r.get_integer(s + "Time/Snapshot every"));
  c.series_every = static_cast<int>(r.get_integer(s + "Time/Series every"));
  c.initial_temperature = r.get(s + "Initial temperature");
  r.require(
      (c.transient() && c.model != continuum::Model::LowMach) || c.initial_temperature.empty(),
      s + "Initial temperature",
      "empty with Mode = steady and for low-Mach (which starts at the reference temperature)");
}

// The heat slabs, bins and probe points in the scene's frame, moved with the twin's walls.
void resolve_output(const Registry& r, const scene::SceneParameters& scene,
                    const std::array<double, 6>& distance, continuum::ContinuumParameters& c) {
  for (const auto& slab : scene.heat_slabs)
    c.heat_slabs.push_back({slab.direction, slab.lower, slab.upper, slab.power});
  for (int d = 0; d < scene.dim; ++d) c.bins[d] = static_cast<unsigned>(scene.bins[d]);
  c.probe_points = points(r, s + "Output/Probe points", scene.dim, scene.box);
  continuum::move_walls_in(c, distance, scene.box); // slabs and points to this twin's frame
  c.write_fields = r.get_bool(s + "Output/Write fields");
  c.profile_samples = static_cast<int>(r.get_integer(s + "Output/Profile samples"));
}
} // namespace

continuum::ContinuumParameters resolve_continuum(const Registry& r,
                                                 const scene::SceneParameters& scene,
                                                 const particle::ParticleParameters& particle) {
  continuum::ContinuumParameters c;
  c.dim = scene.dim;
  c.box = scene.box;
  c.model = resolve_model(r, scene, particle);
  c.gravity = scene.gravity;
  resolve_thermal_walls(r, scene, c);
  resolve_slip(r, scene, particle, c);
  const std::array<double, 6> distance = wall_distances(r, scene, c);
  resolve_coefficients(r, scene, particle, c);
  resolve_mesh_and_solver(r, scene, c);
  resolve_time(r, c);
  resolve_output(r, scene, distance, c);
  // Whatever the per-key checks above did not catch (e.g. a power law with a zero wall
  // temperature) is reported against the section.
  try {
    continuum::check(c);
  } catch (const std::invalid_argument& e) {
    throw io::InputError(std::string("section Continuum: ") + e.what());
  }
  return c;
}

} // namespace twinflow::study
