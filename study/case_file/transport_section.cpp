#include "study/case_file/case_file.hpp"

namespace twinflow::study {

namespace {
// Where the coefficients come from, at which temperature, and how many runs measure them.
void declare_transport_runs(Registry& r) {
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
}

// kappa and eta: relaxation runs, heat slabs, a wall run, eta along the isobar.
void declare_transport_flows(Registry& r) {
  using namespace dealii::Patterns;
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
            "temperatures, 3 decay times of the slowest profile mode to settle and the time that "
            "gives kappa ~1.5% to sample (10 decay times of a 20 rc slab, at least 3 of its own); "
            "kappa = J0 / |dT/dx| "
            "in windows along the profile, fitted by K (T/T0)^a + P (n/n0)^2 (T/T0)^b with the "
            "pair part P, b from theory (docs/theory.md). false: kappa from the relaxation runs "
            "(or the walls), with D's power of T.");
  r.declare("Transport/Viscosity along the isobar", "true", Bool(),
            "With Measure kappa and eta, in a scene with two thermal walls at different "
            "temperatures: eta also by relaxation runs (half of Flow repeats, at least 2) at each "
            "wall's temperature and the density the box at rest has there (the ideal gas's "
            "isobar), and its law K (T/T0)^a + P (n/n0)^2 (T/T0)^b fitted through them and the "
            "state point with P free (b from theory). false: P from theory, a from D(T).");
  r.declare("Transport/Wall steps", "100000", Integer(1000),
            "Sampled steps of the wall run of Kappa from walls (a fifth as many settle first).");
}
} // namespace

// Section Transport: how the fluid's coefficients are measured (transport/parameters.hpp).
void declare_transport(Registry& r) {
  declare_transport_runs(r);
  declare_transport_flows(r);
}

transport::TransportParameters resolve_transport(const Registry& r) {
  transport::TransportParameters t;
  t.source = r.get("Transport/Source");
  t.measure_flows = r.get_bool("Transport/Measure kappa and eta");
  t.temperature = r.get_double("Transport/Temperature");
  t.flow_particles = r.get_double("Transport/Flow particles");
  t.flow_repeats = static_cast<int>(r.get_integer("Transport/Flow repeats"));
  t.diffusion_repeats = static_cast<int>(r.get_integer("Transport/Diffusion repeats"));
  t.temperature_spread = r.get_double("Transport/Temperature spread");
  t.kappa_from_walls = r.get_bool("Transport/Kappa from walls");
  t.kappa_from_slabs = r.get_bool("Transport/Kappa from slabs");
  t.viscosity_along_isobar = r.get_bool("Transport/Viscosity along the isobar");
  t.wall_steps = r.get_integer("Transport/Wall steps");
  return t;
}

} // namespace twinflow::study
