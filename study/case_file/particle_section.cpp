#include "study/case_file/case_file.hpp"

#include <cmath>

namespace twinflow::study {

namespace {
const char* const kPositive = "a number > 0";
}

using namespace twinflow::particle;

namespace {
// The integrator, its step and the run's length and start.
void declare_integration(Registry& r) {
  using namespace dealii::Patterns;
  const std::string p = "Particle/";
  r.declare(p + "Integrator", "shardlow", Selection("euler|ec-verlet|shardlow"),
            "euler: explicit first-order update (001 eqs. 1-2; 000:(2.23)-(2.25)). ec-verlet: "
            "velocity-Verlet with each particle's kinetic and potential changes offset against its "
            "internal energy (002 Appendix A). shardlow: pairwise splitting of the stochastic "
            "terms around velocity-Verlet (Lisal et al. 2011).");
  r.declare(
      p + "Energy offset", "false", Bool(),
      "euler/shardlow: take the kinetic and potential changes of the conservative kicks from "
      "the internal energies (002 Appendix A), which makes them conserve energy exactly with "
      "conservative forces too. euler: each particle's own. shardlow: each particle's own for "
      "gravity and walls; with a pair force the step's total, shared evenly (a particle's own "
      "would carry the pair force's energy flow in u: a walled fluid settles ~7% hot). "
      "ec-verlet always takes each particle's own.");
  r.declare(p + "Time step", "0.005", Double(), "Time step dt (units of tau), > 0.", kPositive);
  r.declare(p + "Neighbour skin", "0.2", Double(),
            "ec-verlet and shardlow list the pairs closer than the cutoff + skin and keep the "
            "list while no pair closer than the cutoff can be missing (every particle within "
            "skin/2 of where it was listed, or, past that, a check of the few that are not: "
            "a performance setting, the physics is the same for any skin). 0: a new list every "
            "step. In [0, 1).");
  r.declare(
      p + "Noise", "gaussian", Selection("gaussian|uniform"),
      "Distribution of the pair noises xi_ij (friction) and zeta_ij (heat): standard "
      "Gaussians, or unit-variance uniforms on (-sqrt 3, sqrt 3) (Groot & Warren 1997), which "
      "are cheaper and leave the equilibrium unchanged (tested: Maxwell velocities, Gamma law "
      "of u, T_K = T_I). Wall noise stays Gaussian.");
  r.declare(p + "Equilibration steps", "0", Integer(0),
            "Steps run before averages start (not sampled).");
  r.declare(p + "Steps", "1000", Integer(0), "Sampled steps after equilibration.");
  r.declare(p + "Seed", "1", Integer(0), "Seed of the counter-based random numbers.");
  r.declare(p + "Ensemble", "1", Integer(1, 1000),
            "Independent realisations of the particle run (seeds Seed, Seed + 1, ...), one after "
            "another into particle/realisations/NN/, merged into particle/: each field, flux and "
            "wall number the realisations' mean, its error the larger of their spread's, sd / "
            "sqrt(K), and their blocks', sqrt(sum e^2) / K. 1-1000.");
  r.declare(p + "Checkpoint interval", "10", Double(0),
            "Wall-clock minutes between the checkpoints a particle run writes as it goes "
            "(particle/checkpoint.twfc; a crash or kill -9 loses at most this much; --restart "
            "continues). 0: only when interrupted. Changes no result: not part of the inputs "
            "hash.");
  r.declare(p + "Mass", "1", Double(), "Particle mass m, > 0.", kPositive);
  r.declare(p + "Initial velocities", "maxwell", Selection("maxwell|rest"),
            "maxwell: Gaussian velocities at the scene temperature (zero total momentum); rest: "
            "all particles at rest (seed 000's closed-system start).");
  r.declare(p + "Initial internal energy", "equilibrium", Selection("equilibrium|theta"),
            "equilibrium: u_i = (c_v + k) T, the equilibrium mean energy (000:(3.21)), so an "
            "isolated fluid stays at the scene temperature; theta: theta_i = T (u_i = c_v T, "
            "seed 002's start), after which an isolated ideal fluid settles at "
            "T (c_v + d/2) / (c_v + k + d/2) (8% low at c_v = 10 in 2D).");
}

// The fluid: internal energy and the pair terms.
void declare_fluid(Registry& r) {
  using namespace dealii::Patterns;
  const std::string p = "Particle/";
  r.declare(p + "Internal energy/Model", "dpde", Selection("dpde|isothermal"),
            "dpde: every particle carries an internal energy u = c_v theta. isothermal: classical "
            "DPD with the fixed scene temperature in the fluctuation-dissipation relation.");
  r.declare(p + "Internal energy/Heat capacity", "200", Double(),
            "Particle heat capacity c_v in units of k; seed 000 needs c_v > k.",
            "a number > 1 (c_v > k, 000 footnote 23)");

  r.declare(p + "Conservative force/Type", "none", Selection("none|constant|temperature-dependent"),
            "none: ideal gas; constant: a_ij = a0; temperature-dependent: a_ij = a0 (theta_i + "
            "theta_j)/(2 T_ref) (002 section II.C).");
  r.declare(p + "Conservative force/a0", "15", Double(), "Repulsion amplitude a0 (k T0 / rc).");
  r.declare(p + "Conservative force/Cutoff", "1", Double(), "Cutoff rc_C, > 0.", kPositive);
  r.declare(p + "Conservative force/Reference temperature", "1", Double(),
            "T_ref of the temperature-dependent a_ij, > 0.", kPositive);

  r.declare(p + "Dissipation/Parametrisation", "constant-sigma",
            Selection("constant-sigma|constant-gamma"),
            "constant-sigma: gamma_ij = sigma^2/(2 k Theta_ij) (002, LAMMPS); constant-gamma: "
            "sigma_ij = sqrt(2 k Theta_ij gamma) with 003:(18)'s drift correction.");
  r.declare(p + "Dissipation/sigma", "3", Double(0), "Noise amplitude sigma (constant-sigma).");
  r.declare(p + "Dissipation/gamma", "4.5", Double(0),
            "Friction gamma (constant-gamma and isothermal).");
  r.declare(p + "Dissipation/Cutoff", "1", Double(), "Cutoff rc_D of w_D, > 0.", kPositive);
  r.declare(p + "Dissipation/Exponent", "0.5", Double(0),
            "w_D = (1 - r/rc_D)^n_D; w_R = sqrt(w_D). 002: 0.5; LAMMPS: 2.");

  r.declare(p + "Heat conduction/Law", "inverse", Selection("none|inverse|linear"),
            "none; inverse: q = kappa_ij w_H (1/theta_i - 1/theta_j) (000, 003, LAMMPS); "
            "linear: q = kappa_ij w_H (theta_j - theta_i) (002 eq. 8).");
  r.declare(p + "Heat conduction/Coefficient", "seed-002", Selection("constant|seed-002"),
            "inverse law only. constant: kappa_ij = kappa0; seed-002: kappa_ij = kappa0 c_v^2 "
            "(theta_i + theta_j)^2/(4k). The linear law always uses kappa_ij = c_v kappa0.");
  r.declare(p + "Heat conduction/kappa0", "0.001", Double(0), "Heat-conduction strength kappa0.");
  r.declare(p + "Heat conduction/Linear noise", "fdt", Selection("fdt|seed-002-printed"),
            "linear law only: fdt: Lambda^2 = 2 k kappa_ij w_H theta_i theta_j (000:(2.38)); "
            "seed-002-printed: (alpha^B)^2 = kappa_ij theta_i theta_j as printed in 002 (no 2k).");
  r.declare(p + "Heat conduction/Cutoff", "1", Double(), "Cutoff rc_H of w_H, > 0.", kPositive);
  r.declare(p + "Heat conduction/Exponent", "0.5", Double(0), "w_H = (1 - r/rc_H)^n_H.");
}

// The walls' model.
void declare_walls(Registry& r) {
  using namespace dealii::Patterns;
  const std::string p = "Particle/";
  r.declare(p + "Walls/Model", "half-space", List(Selection("half-space|seed000"), 1, 6),
            "How a wall acts on the fluid: half-space: as the half-space of wall material beyond "
            "its plane (density Walls/Density, at rest, at the wall's temperature), every pair "
            "term (the fluid's repulsion, friction, noise, heat conduction) integrated over it: "
            "a particle by the wall has the coupling of the fluid's own neighbours; seed000: as "
            "one particle of infinite mass and heat capacity at the nearest point (seed 000 "
            "section 3.1), with Repulsion and Range below. One value for every wall, or one per "
            "wall in the order x lower, x upper, y lower, ...");
  r.declare(p + "Walls/Density", "0", Double(0),
            "half-space walls: the wall material's number density rho_w; 0: the fluid's "
            "(Scene/Density). The walls' thermal coupling grows with it.");
  r.declare(p + "Walls/Heat conduction", "1", List(Double(0), 1, 6),
            "half-space walls: the wall material's heat-conduction strength for its pairs with "
            "the fluid, in units of the fluid's own (kappa0 x this). A wall passes heat by "
            "re-emitting the particles that reach it and by this conduction; beside a dilute hot "
            "fluid the re-emission alone leaves a jump of several % of the walls' difference "
            "(docs/case-files.md, Walls). One value for every wall, or one per wall in the order "
            "x lower, x upper, y lower, ...");
  r.declare(p + "Walls/Diffuse reflection", "true", Bool(),
            "half-space thermal walls: a particle that reaches the plane comes back as one "
            "emitted by wall material at T_w (velocity from the flux-weighted Maxwell law, "
            "tangential part only on no-slip walls; internal energy from u^c_v exp(-u/T_w)), "
            "as a fluid particle beyond the plane would; false: bounced back (no-slip) or "
            "mirrored (free-slip) with its own energies.");
  r.declare(p + "Walls/Repulsion", "25", Double(0),
            "seed000 walls: repulsion a_w: force a_w (1 - h/range) along the wall normal at "
            "distance h.");
  r.declare(p + "Walls/Range", "1", Double(),
            "seed000 walls: interaction range (repulsion, friction, heat exchange), > 0.",
            kPositive);
}

// What the run samples.
void declare_diagnostics(Registry& r) {
  using namespace dealii::Patterns;
  const std::string p = "Particle/";
  r.declare(p + "Diagnostics/Sample interval", "10", Integer(1), "Steps between samples.");
  r.declare(p + "Diagnostics/Blocks", "20", Integer(2, 10000),
            "Number of blocks for block-averaged standard errors.");
  r.declare(p + "Diagnostics/Histogram bins", "60", Integer(4, 100000),
            "Bins of the velocity and internal-energy histograms.");
  r.declare(p + "Diagnostics/RDF bins", "100", Integer(4, 100000),
            "Bins of g(r) up to the largest cutoff x 2.5.");
  r.declare(p + "Diagnostics/Correlation samples", "100", Integer(2, 100000),
            "Length of the VACF / MSD window, in samples.");
}

} // namespace

void declare_particle(Registry& r) {
  declare_integration(r);
  declare_fluid(r);
  declare_walls(r);
  declare_diagnostics(r);
}

namespace {
WeightParameters weight(const Registry& r, const std::string& s) {
  WeightParameters w{r.get_double(s + "/Cutoff"), r.get_double(s + "/Exponent")};
  r.require(w.cutoff > 0, s + "/Cutoff", kPositive);
  return w;
}
} // namespace

namespace {
const std::string s = "Particle/";

void resolve_integration(const Registry& r, ParticleParameters& p) {
  const std::string integrator = r.get(s + "Integrator");
  p.integrator = integrator == "euler"      ? Integrator::Euler
                 : integrator == "shardlow" ? Integrator::Shardlow
                                            : Integrator::EcVerlet;
  p.energy_offset = r.get_bool(s + "Energy offset");
  p.dt = r.get_double(s + "Time step");
  r.require(p.dt > 0 && std::isfinite(p.dt), s + "Time step", kPositive);
  p.neighbour_skin = r.get_double(s + "Neighbour skin");
  r.require(p.neighbour_skin >= 0 && p.neighbour_skin < 1, s + "Neighbour skin", "in [0, 1)");
  p.uniform_noise = r.get(s + "Noise") == "uniform";
  p.equilibration_steps = r.get_integer(s + "Equilibration steps");
  p.steps = r.get_integer(s + "Steps");
  p.seed = static_cast<std::uint64_t>(r.get_integer(s + "Seed"));
  p.mass = r.get_double(s + "Mass");
  r.require(p.mass > 0, s + "Mass", kPositive);
  p.initial_velocities = r.get(s + "Initial velocities") == "rest" ? InitialVelocities::Rest
                                                                   : InitialVelocities::Maxwell;
  p.initial_internal_energy = r.get(s + "Initial internal energy") == "theta"
                                  ? InitialInternalEnergy::Theta
                                  : InitialInternalEnergy::Equilibrium;
}

void resolve_fluid(const Registry& r, ParticleParameters& p) {
  p.energy = r.get(s + "Internal energy/Model") == "isothermal" ? EnergyModel::Isothermal
                                                                : EnergyModel::Dpde;
  p.cv = r.get_double(s + "Internal energy/Heat capacity");
  r.require(p.cv > 1.0, s + "Internal energy/Heat capacity",
            "a number > 1 (c_v > k, 000 footnote 23)");
  const std::string c = r.get(s + "Conservative force/Type");
  p.conservative = c == "none"       ? ConservativeForce::None
                   : c == "constant" ? ConservativeForce::Constant
                                     : ConservativeForce::TemperatureDependent;
  p.a0 = r.get_double(s + "Conservative force/a0");
  p.conservative_cutoff = r.get_double(s + "Conservative force/Cutoff");
  r.require(p.conservative_cutoff > 0, s + "Conservative force/Cutoff", kPositive);
  p.reference_temperature = r.get_double(s + "Conservative force/Reference temperature");
  r.require(p.reference_temperature > 0, s + "Conservative force/Reference temperature", kPositive);
  p.friction = r.get(s + "Dissipation/Parametrisation") == "constant-gamma"
                   ? Friction::ConstantGamma
                   : Friction::ConstantSigma;
  p.sigma = r.get_double(s + "Dissipation/sigma");
  p.gamma = r.get_double(s + "Dissipation/gamma");
  p.dissipation = weight(r, s + "Dissipation");
  const std::string h = r.get(s + "Heat conduction/Law");
  p.heat = h == "none" ? HeatLaw::None : h == "linear" ? HeatLaw::Linear : HeatLaw::Inverse;
  p.heat_coefficient = r.get(s + "Heat conduction/Coefficient") == "constant"
                           ? HeatCoefficient::Constant
                           : HeatCoefficient::Seed002;
  p.kappa0 = r.get_double(s + "Heat conduction/kappa0");
  p.heat_weight = weight(r, s + "Heat conduction");
  p.linear_noise_factor = r.get(s + "Heat conduction/Linear noise") == "fdt" ? 2.0 : 1.0;
  if (p.energy == EnergyModel::Isothermal) p.heat = HeatLaw::None; // no internal energy at all
}

void resolve_diagnostics(const Registry& r, ParticleParameters& p) {
  p.sample_interval = r.get_integer(s + "Diagnostics/Sample interval");
  p.blocks = static_cast<int>(r.get_integer(s + "Diagnostics/Blocks"));
  p.histogram_bins = static_cast<int>(r.get_integer(s + "Diagnostics/Histogram bins"));
  p.rdf_bins = static_cast<int>(r.get_integer(s + "Diagnostics/RDF bins"));
  p.correlation_samples = static_cast<int>(r.get_integer(s + "Diagnostics/Correlation samples"));
}

// The scene's walls with the case's wall model per wall, and gravity.
void resolve_walls(const Registry& r, const scene::SceneParameters& scene, ParticleParameters& p) {
  p.wall_a0 = r.get_double(s + "Walls/Repulsion");
  p.wall_range = r.get_double(s + "Walls/Range");
  r.require(p.wall_range > 0, s + "Walls/Range", kPositive);
  p.wall_density = r.get_double(s + "Walls/Density");
  p.wall_diffuse = r.get_bool(s + "Walls/Diffuse reflection");
  const std::string models = r.get(s + "Walls/Model");
  std::vector<std::string> model = dealii::Utilities::split_string_list(models);
  r.require(model.size() == 1 || static_cast<int>(model.size()) == 2 * p.dim, s + "Walls/Model",
            "one value, or one per wall (2 x dimension)");
  const std::vector<double> conduction = r.get_doubles(s + "Walls/Heat conduction");
  r.require(conduction.size() == 1 || static_cast<int>(conduction.size()) == 2 * p.dim,
            s + "Walls/Heat conduction", "one value, or one per wall (2 x dimension)");
  for (int d = 0; d < p.dim; ++d) {
    const auto& b = scene.boundary[d];
    p.walls[d] = WallPair{!b.periodic, b.thermal, b.temperature, b.no_slip};
    for (int side = 0; side < 2; ++side) {
      const std::size_t k = 2 * d + side;
      p.walls[d].model[side] =
          model[model.size() == 1 ? 0 : k] == "seed000" ? WallModel::Seed000 : WallModel::HalfSpace;
      p.walls[d].conduction[side] = conduction[conduction.size() == 1 ? 0 : k];
    }
    p.gravity[d] = scene.gravity[d];
    r.require(!(b.periodic && scene.gravity[d] != 0), "Scene/Gravity",
              "no component along a periodic direction (its potential would jump at the wrap)");
  }
}

// What does not fit together: seed 000's wall keys for half-space walls (a value set for walls
// that ignore it is a mistake the user should hear of, not a silent no-op), the scene's forcing
// against its walls, and minimum image (every periodic edge >= 2 cutoffs).
void check_particle(const Registry& r, const ParticleParameters& p) {
  bool walls_present = false, seed000_wall = false;
  for (int d = 0; d < p.dim; ++d)
    for (int side = 0; side < 2; ++side)
      if (p.walls[d].present) {
        walls_present = true;
        seed000_wall |= p.walls[d].model[side] == WallModel::Seed000;
      }
  for (const std::string key : {"Walls/Repulsion", "Walls/Range"})
    r.require(!walls_present || seed000_wall || r.get(s + key) == r.default_value(s + key), s + key,
              "its default unless a wall is seed000 (Particle/Walls/Model); half-space walls take "
              "the fluid's own pair terms");
  r.require(p.poiseuille_force == 0 || (p.dim >= 2 && !p.walls[0].present),
            "Scene/Reverse Poiseuille force", "0 with walls along x (the force is along x)");
  r.require(p.shear_perturbation == 0 || (p.dim >= 2 && !p.walls[0].present && !p.walls[1].present),
            "Scene/Shear perturbation", "0 unless the scene is 2D or 3D with periodic x and y");
  const double rc = p.largest_cutoff();
  for (int d = 0; d < p.dim; ++d)
    r.require(p.box[d] >= 2 * rc, "Scene/Box size",
              "every edge >= 2 x the largest cutoff (" + std::to_string(2 * rc) + ")");
}
} // namespace

ParticleParameters resolve_particle(const Registry& r, const scene::SceneParameters& scene) {
  ParticleParameters p;
  p.dim = scene.dim;
  p.box = scene.box;
  p.density = scene.density;
  p.temperature = scene.temperature;
  p.temperature_perturbation = scene.temperature_perturbation;
  p.shear_perturbation = scene.shear_perturbation;
  p.poiseuille_force = scene.poiseuille_force;
  resolve_integration(r, p);
  resolve_fluid(r, p);
  resolve_diagnostics(r, p);
  for (const auto& slab : scene.heat_slabs)
    p.heat_slabs.push_back({slab.direction, slab.lower, slab.upper, slab.power});
  p.bins = scene.bins;
  resolve_walls(r, scene, p);
  check_particle(r, p);
  return p;
}

} // namespace twinflow::study
