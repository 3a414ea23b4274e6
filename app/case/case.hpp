#pragma once
// One case file describes a whole paired case. This folder is the one place that maps it to
// the plain parameter structs of each stage.

#include <array>
#include <string>
#include <vector>

#include "app/case/registry.hpp"
#include "continuum/parameters.hpp"
#include "particle/parameters.hpp"

namespace twinflow::app {

// Boundaries of one box direction, shared by both twins.
struct DirectionBoundary {
  bool periodic = true;
  std::array<bool, 2> thermal{{true, true}}; // lower, upper: thermal (true) or adiabatic
  std::array<double, 2> temperature{{1.0, 1.0}};
  bool no_slip = false;
};

// A slab x_d in [lower, upper] into which `power` (energy per time; < 0: out of) is put.
struct HeatSlab {
  int direction;
  double lower, upper, power;
};

struct SceneParameters {
  int dim = 3;
  std::array<double, 3> box{{20, 10, 10}};
  double density = 3.0;
  double temperature = 1.0;
  double temperature_perturbation = 0; // relative amplitude of sin(2 pi x / Lx) at the start
  double shear_perturbation = 0;       // v_y amplitude of sin(2 pi x / Lx), in sqrt(k T / m)
  double poiseuille_force = 0;         // reverse Poiseuille: +F x-hat for y < Ly/2, -F above
  std::array<double, 3> gravity{{0, 0, 0}};
  std::array<DirectionBoundary, 3> boundary;
  std::vector<HeatSlab> heat_slabs;   // hot then cold
  std::array<int, 3> bins{{1, 1, 1}}; // field bins shared by both twins
  bool has_walls() const;
};

struct TransportParameters {
  std::string source = "estimated"; // estimated | measured
  bool measure_flows = false;       // also kappa and eta by the relaxation of sine modes
  double temperature = 0;           // state point; 0: the walls' mean, else Scene/Temperature
  double flow_particles = 4000;     // particles of the square/cubic base box of the flow runs
  int flow_repeats = 4;             // independent relaxation runs (their spread is the error)
  double temperature_spread = 0;    // > 0: also at T (1 -+ spread), power laws kappa(T), eta(T)
  bool kappa_from_walls = false;    // kappa by conduction between the scene's thermal walls
  long wall_steps = 100000;         // its sampled steps (after as many / 5 to settle)
};

// Bounds of the stability map (twinflow stability).
struct StabilityBounds {
  double energy_drift = 1e-3;          // largest acceptable max |dE/E|
  double temperature_tolerance = 0.05; // |T / T_target - 1|
  double fluctuation_number = 1.0;     // 000:(3.34)'s number must stay below this
};

struct CompareParameters {
  double wall_layer = 1.0;             // thickness excluded from field errors
  std::string calibration = "kapitza"; // kapitza | wall temperatures
  bool effective_walls = false; // calibrated twin's walls at the particle walls' Gibbs depths
  bool wall_slip = true;        // calibrated twin's no-slip walls with the measured Navier slip
  std::string rayleigh_control = "gravity"; // how a sweep reaches a target Ra
  StabilityBounds stability;
};

struct CaseParameters {
  std::string name;
  SceneParameters scene;
  particle::ParticleParameters particle;
  TransportParameters transport;
  continuum::ContinuumParameters continuum;
  CompareParameters compare;
};

// Declares every parameter of every section (so print-parameters documents them all).
class Case {
public:
  Case();
  // Reads the file, applies --set overrides, checks every value: throws io::InputError.
  CaseParameters load(const std::string& filename, const std::vector<std::string>& overrides);
  // The parameters a stage recorded in its summary.json ("parameters": path -> value), with the
  // later stages' --set options (Transport/, Continuum/, Compare/) over them: those sections
  // may change without rerunning the particles.
  CaseParameters load_resolved(const io::Json& resolved, const std::string& name,
                               const std::vector<std::string>& overrides = {});
  // The two halves of load(): read() rejects unknown keys and values outside a key's pattern;
  // resolve() the values that do not fit together or the sections' ranges.
  void read(const std::string& filename, const std::vector<std::string>& overrides);
  CaseParameters resolve(const std::string& filename) const;
  const Registry& registry() const { return registry_; }

private:
  Registry registry_;
};

// Per-section declaration and mapping (app/case/*_section.cpp).
void declare_scene(Registry&);
SceneParameters resolve_scene(const Registry&);
void declare_particle(Registry&);
particle::ParticleParameters resolve_particle(const Registry&, const SceneParameters&);
void declare_continuum(Registry&);
continuum::ContinuumParameters resolve_continuum(const Registry&, const SceneParameters&);
// (T_max - T_min) / (T_max + T_min) over the scene's thermal walls; 0 without any.
double thermal_wall_epsilon(const SceneParameters&);
void declare_transport_and_compare(Registry&);

} // namespace twinflow::app
