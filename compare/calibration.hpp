#pragma once
// The calibrated twin's walls, from the particle run's own wall measurements: a Kapitza (Robin)
// conductance per thermal wall h_K = q / (T_wall - T_fluid at the wall), or the fluid's wall
// temperature where no jump is usable; Navier slip at no-slip walls from the walls' measured
// friction; optionally the walls at their effective (Gibbs) positions. What remains between the
// particle fluid and this twin is not wall physics.

#include <array>
#include <string>
#include <vector>

#include "compare/parameters.hpp"
#include "compare/twin_distance.hpp"
#include "io/json.hpp"
#include "scene/scene.hpp"

namespace twinflow::compare {

struct CalibratedWall {
  double conductance = 0, conductance_stderr = 0; // Kapitza h_K; 0: none
  double fluid_temperature;                       // finite: the twin's wall temperature instead
  double slip_length = 0;                         // Navier b; 0: none
  double position = 0;                            // distance in from the scene's wall plane
};

struct CalibratedWalls {
  std::array<std::array<CalibratedWall, 2>, 3> wall; // [direction][side]
  bool kapitza = false;                              // conductances set (Boussinesq twins only)
  bool slip = false;                                 // slip lengths set at every no-slip wall
  bool effective_positions = false;                  // walls moved to their effective positions
  std::vector<std::string> notes;                    // what could not be calibrated, and why
};

// What the calibration needs of the twin it calibrates.
struct TwinFacts {
  bool robin_walls = true; // the twin has Kapitza walls and Navier slip (Boussinesq, compressible)
  bool kapitza_inverse = false; // the twin's Kapitza law: h_K T_w^2 (1/T_f - 1/T_w)
  double viscosity = 0;         // the nominal twin's eta at its reference temperature (slip)
};

// How the calibrated twin's walls are made, in words (metrics.json, the report).
std::string calibration_description(const CompareParameters& compare, const TwinFacts& twin);

// `results`: the particle summary's "results"; `final_state`: its final binned averages (with
// the per-block temperatures). Throws io::InputError when a needed measurement is missing (a
// run from before it), with what to do.
CalibratedWalls calibrate_walls(const io::Json& results, const BinnedState& final_state,
                                const scene::SceneParameters& scene,
                                const CompareParameters& compare, const TwinFacts& twin);

} // namespace twinflow::compare
