#include "app/case/case.hpp"

#include <algorithm>
#include <filesystem>

namespace twinflow::app {

using dealii::Patterns::Anything;

CaseFile::CaseFile() {
  registry_.declare("Case name", "", Anything(),
                    "Name of the case (used in reports); empty: the case file's name.");
  declare_scene(registry_);
  declare_particle(registry_);
  declare_transport_and_compare(registry_);
  declare_continuum(registry_);
}

study::Case CaseFile::load(const std::string& filename, const std::vector<std::string>& settings) {
  read(filename, settings);
  study::Case c = resolve(filename);
  c.settings = settings;
  return c;
}

void CaseFile::read(const std::string& filename, const std::vector<std::string>& settings) {
  registry_.parse_file(filename);
  for (const auto& o : settings) registry_.set_override(o);
}

study::Case CaseFile::load_recorded(const io::Json& resolved, const std::string& name,
                                    const std::vector<std::string>& overrides) {
  if (!resolved.is_object()) throw io::InputError("recorded case parameters: not an object");
  for (const auto& [path, value] : resolved.items())
    registry_.set_override(path + "=" +
                           (value.is_string() ? value.get<std::string>() : value.dump()));
  for (const auto& o : overrides)
    for (const char* later : {"Transport/", "Continuum/", "Compare/"})
      if (o.rfind(later, 0) == 0) registry_.set_override(o);
  if (!name.empty() && io::text(resolved, {"Case name"}).empty())
    registry_.set_override("Case name=" + name);
  study::Case c = resolve("");
  c.settings = overrides;
  return c;
}

study::Case CaseFile::resolve(const std::string& filename) const {
  study::Case out;
  out.file = filename;
  study::CaseParameters& c = out.parameters;
  c.name = registry_.get("Case name");
  if (c.name.empty()) c.name = std::filesystem::path(filename).stem().string();
  c.scene = resolve_scene(registry_);
  c.particle = resolve_particle(registry_, c.scene);
  c.checkpoint_interval_minutes = registry_.get_double("Particle/Checkpoint interval");
  resolve_transport_and_compare(registry_, c);
  c.continuum = resolve_continuum(registry_, c.scene, c.particle);
  c.twin.coefficients_from_transport =
      registry_.get("Continuum/Coefficients/Source") == "transport";
  c.twin.model_chosen_automatically = registry_.get("Continuum/Model") == "auto";
  const std::vector<double> slips = registry_.get_doubles("Continuum/Slip lengths");
  c.twin.kinetic_slip_automatically =
      registry_.get("Continuum/Wall slip") == "auto" &&
      std::none_of(slips.begin(), slips.end(), [](double b) { return b > 0; });
  const std::vector<double> kapitza = registry_.get_doubles("Continuum/Kapitza conductances");
  const bool kapitza_given =
      std::any_of(kapitza.begin(), kapitza.end(), [](double h) { return h > 0; });
  const std::string jump = registry_.get("Continuum/Wall jump");
  c.twin.wall_jumps_automatically = jump == "auto" && !kapitza_given;
  c.twin.wall_jumps_from_theory =
      jump == "theory" || (c.twin.wall_jumps_automatically && c.twin.coefficients_from_transport);
  c.twin.low_mach_threshold = registry_.get_double("Continuum/Low-Mach threshold");
  c.twin.compressible_threshold = registry_.get_double("Continuum/Compressible threshold");
  out.record = registry_.resolved_json();
  for (const auto& [path, value] : out.record.items())
    out.defaults[path] = registry_.default_value(path);
  return out;
}

void resolve_transport_and_compare(const Registry& r, study::CaseParameters& c) {
  c.transport.source = r.get("Transport/Source");
  c.transport.measure_flows = r.get_bool("Transport/Measure kappa and eta");
  c.transport.temperature = r.get_double("Transport/Temperature");
  c.transport.flow_particles = r.get_double("Transport/Flow particles");
  c.transport.flow_repeats = static_cast<int>(r.get_integer("Transport/Flow repeats"));
  c.transport.diffusion_repeats = static_cast<int>(r.get_integer("Transport/Diffusion repeats"));
  c.transport.temperature_spread = r.get_double("Transport/Temperature spread");
  c.transport.kappa_from_walls = r.get_bool("Transport/Kappa from walls");
  c.transport.kappa_from_slabs = r.get_bool("Transport/Kappa from slabs");
  c.transport.wall_steps = r.get_integer("Transport/Wall steps");
  c.compare.wall_layer = r.get_double("Compare/Wall layer");
  c.compare.calibration = r.get("Compare/Calibration");
  c.compare.effective_walls = r.get_bool("Compare/Effective walls");
  c.compare.wall_slip = r.get_bool("Compare/Wall slip");
  c.compare.rayleigh_control = r.get("Compare/Rayleigh control");
  c.stability.energy_drift = r.get_double("Compare/Stability/Energy drift bound");
  c.stability.temperature_tolerance = r.get_double("Compare/Stability/Temperature tolerance");
  c.stability.fluctuation_number = r.get_double("Compare/Stability/Fluctuation bound");
}

void declare_transport_and_compare(Registry& r) {
  using namespace dealii::Patterns;
  r.declare("Transport/Source", "estimated", Selection("estimated|measured"),
            "Which coefficients feed the continuum twin: theory estimates or measured by short "
            "particle runs.");
  r.declare("Transport/Temperature", "0", Double(0),
            "State-point temperature of the transport stage (units of T0); 0: the mean of the "
            "thermal walls, or Scene/Temperature without walls. `twinflow run` sets it to the "
            "particle fluid's measured mean temperature unless the case or --set gives one.");
  r.declare("Transport/Flow particles", "4000", Double(100),
            "Particles in the square (cubic) base box of the kappa and eta runs, >= 100; the "
            "relaxation runs double it along x. Their length grows as the box edge squared: 1000 "
            "is ~16x faster than 4000 in 2D.");
  r.declare("Transport/Flow repeats", "4", Integer(1, 100),
            "Independent relaxation runs (different seeds) for kappa and eta, 1-100; the error "
            "stated is the larger of their spread and their fits' errors, over sqrt(repeats).");
  r.declare("Transport/Diffusion repeats", "4", Integer(1, 100),
            "Independent bulk runs (different seeds) at the state point for the self-diffusion "
            "D, 1-100: the error stated is their spread's, sd / sqrt(repeats), with repeats - 1 "
            "degrees of freedom (self_diffusion_stderr_dof). One run's MSD window is one sample "
            "of the box's collective flows, so one run cannot state D's error: with 1, its "
            "particle groups' error, ~1.3x too small (measured in 2D).");
  r.declare("Transport/Temperature spread", "0", Double(0, 0.9),
            "0: kappa and eta at the state point only, constant in the continuum twin. s > 0: "
            "also measured at T (1 - s) and T (1 + s) (three times the cost) and handed to the "
            "twin as power laws c (T / T_ref)^n fitted through the three (the walls' range: "
            "seed 000's cavity spans 0.8-2.8). 0 <= s <= 0.9.");
  r.declare("Transport/Measure kappa and eta", "false", Bool(),
            "Also measure kappa and eta from a heat mode and a transverse momentum mode decaying "
            "in a periodic box (seed 004's relaxation method; Transport/Flow repeats runs of "
            "three decay times each: minutes at seed 002's state point).");
  r.declare("Transport/Kappa from walls", "false", Bool(),
            "Also measure kappa by conduction between the scene's two thermal walls of its "
            "heated direction (their temperatures, slip and Particle/Walls), periodic across, no "
            "gravity, ~4000 particles: kappa = the walls' mean heat flux / |dT/dx| in the central "
            "60% (a line through the binned T_internal), over the scene's own temperature span "
            "(so kappa(T) is averaged as the scene averages it). ~4x more precise than the "
            "relaxation runs in the same time for the default cavity. A check of the heat slabs' "
            "kappa (Kappa from slabs), which the twin takes when both are on; eta comes from the "
            "relaxation runs (Measure kappa and eta).");
  r.declare("Transport/Kappa from slabs", "true", Bool(),
            "With Measure kappa and eta, in a scene with two thermal walls at different "
            "temperatures: kappa and its law kappa(n, T) from periodic heat slabs (seed 002 "
            "III.B) at the scene's own scale, no walls: a box twice the heated length (the walls' "
            "mirror image) and the scene's other lengths, a power that spans the walls' "
            "temperatures, 3 + 10 decay times of the slowest profile mode; kappa = J0 / |dT/dx| "
            "in windows along the profile, fitted by K (T/T0)^a + P (n/n0)^2 (T/T0)^b with the "
            "pair part P, b from theory (docs/theory.md). false: kappa from the relaxation runs "
            "(or the walls), with D's power of T.");
  r.declare("Transport/Wall steps", "100000", Integer(1000),
            "Sampled steps of the wall run of Kappa from walls (a fifth as many settle first).");
  r.declare("Compare/Calibration", "kapitza", Selection("kapitza|wall temperatures"),
            "The calibrated twin's thermal walls: kapitza: the nominal wall temperatures with a "
            "Kapitza (Robin) conductance h_K = q / jump per wall, from the particle wall's heat "
            "flux q and the fluid's temperature jump there; wall temperatures: Dirichlet at the "
            "fluid's temperature extrapolated to each wall.");
  r.declare("Compare/Effective walls", "false", Bool(),
            "The calibrated twin's walls at the particle walls' effective positions: each wall "
            "moved in by the depth of its depleted layer (the Gibbs dividing surface of the "
            "measured density profile, particle/wall_layers.csv), its fluid temperature (and so "
            "its jump) extrapolated to that plane, its heat flow compared over the scene's wall "
            "area. false: the twin fills the scene's box.");
  r.declare("Compare/Wall slip", "true", Bool(),
            "The calibrated twin's no-slip walls with Navier slip (Boussinesq twin): b = eta / "
            "zeta - (h_f - wall), zeta the particle wall's measured friction per area (integral "
            "of n(h) gamma(T(h)) w_D(h) over its layer, particle/summary.json), h_f the mean "
            "depth where it acts, wall the twin's wall position (the particle wall's friction lets "
            "the fluid slip by ~1 rc on the default cavity's hot side). false: no slip.");
  r.declare("Compare/Wall layer", "1", Double(0),
            "Thickness (length units) of the layer next to each wall left out of field errors.");
  r.declare("Compare/Rayleigh control", "gravity", Selection("gravity"),
            "How `twinflow sweep --rayleigh` reaches a target Ra = g alpha dT H^3 / (nu chi): "
            "gravity scales |g| along the case's gravity direction at fixed coefficients. (Scaling "
            "the box size H instead is not implemented.)");
  r.declare("Compare/Stability/Energy drift bound", "1e-3", Double(0),
            "twinflow stability: a run whose max |E(t) - E(0) - wall heat| / E(0) exceeds this "
            "is classified energy_drift.");
  r.declare("Compare/Stability/Temperature tolerance", "0.05", Double(0),
            "twinflow stability: a run whose T_kinetic or T_internal differs from the target "
            "(Scene/Temperature; with thermal walls the mean of their temperatures) by more than "
            "this fraction is classified temperature_off.");
  r.declare("Compare/Stability/Fluctuation bound", "1", Double(0),
            "twinflow stability: predicted_stable needs 000:(3.34)'s sqrt(B C dt*) (4 pi/3) "
            "r*^3 rho* below this. Seed 000 only asks for it to be << 1 (else the heat noise "
            "drives internal energies negative) and gives no number; 1 is where that order-of-"
            "magnitude estimate has certainly failed.");
}

} // namespace twinflow::app
