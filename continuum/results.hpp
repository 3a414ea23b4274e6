#pragma once
// What a continuum run measured: plain structs (no deal.II), written to summary.json by to_json.

#include <array>
#include <string>
#include <vector>

#include "continuum/parameters.hpp"
#include "io/json.hpp"

namespace twinflow::continuum {

// Wall time of each phase, seconds (summed over Newton iterations and levels).
struct PhaseTimes {
  double setup = 0, assembly = 0, solve = 0, postprocess = 0, output = 0;
  double total() const { return setup + assembly + solve + postprocess + output; }
};

// A signed maximum along a mid-line: value in units of chi/H, position as a fraction of the box.
struct LineMaximum {
  double value = 0;
  double position = 0;
};

// Local Nusselt number at the face quadrature points of one fixed-temperature wall.
struct WallNusselt {
  int direction = 0, side = 0;
  double average = 0; // face integral / face area
  std::vector<std::array<double, 3>> points;
  std::vector<double> local;
};

struct BinAverages {
  std::array<unsigned, 3> bins{{1, 1, 1}};
  std::vector<std::string> names;          // field names
  std::vector<std::vector<double>> values; // [field][bin], bin index x fastest
  // Beside a wall moved in over a pinned layer the scene's bins reach beyond the twin's domain:
  // `values` count the layer's strip at the wall's values, as the particles' bins count the
  // layer's particles; `domain_values` are the twin's own fields over its domain alone (empty
  // when no wall was moved: then the same as `values`).
  std::vector<std::vector<double>> domain_values;
  const std::vector<std::vector<double>>& own_values() const {
    return domain_values.empty() ? values : domain_values;
  }
};

struct MeshLevel {
  int level = 0;
  std::array<unsigned, 3> cells{{0, 0, 0}};
  unsigned long dofs = 0;
  double nusselt = 0;
  double change_in_nusselt = 0; // to the previous level
  double pressure_ratio =
      0; // P / p0 at this level (low-Mach; compressible: mean p / p0; 0: Boussinesq)
  int newton_iterations = 0;
  double wall_time = 0;
};

// One row of a Boussinesq run in time.
struct TimeSample {
  int step = 0;
  double time = 0;
  double nusselt = 0;        // volume form, as ContinuumResult::nusselt
  double kinetic_energy = 0; // int (1/2) n m |u|^2 dV, particle units
  double max_speed = 0;      // max |u| at the quadrature points, units chi/H
  int newton_iterations = 0; // of this step
};

struct ContinuumResult {
  std::string model;
  int dim = 2;
  DimensionlessNumbers numbers;
  unsigned long dofs = 0;
  std::array<unsigned, 3> cells{{0, 0, 0}};
  int newton_iterations = 0;
  std::vector<double> continuation_rayleigh; // the Ra of every converged continuation step
  PhaseTimes times;

  // Boussinesq
  double nusselt = 0;             // volume form, (1/|Omega|) int (n c_p u_d T - kappa dT/dx_d)
  std::vector<WallNusselt> walls; // local and average Nu of each fixed-temperature wall
  bool has_midline_maxima = false;
  LineMaximum u_max_vertical_midline;          // max u_x on x = Lx/2 (position: y / Ly)
  LineMaximum v_max_horizontal_midline;        // max u_y on y = Ly/2 (position: x / Lx)
  double stream_function_max = 0;              // max |psi| / chi (2D walled cavities)
  std::array<double, 2> vortex_centre{{0, 0}}; // where |psi| is largest, fractions of the box
  double max_speed = 0;                        // max |u| at the quadrature points, chi/H
  double kinetic_energy = 0;                   // int (1/2) n m |u|^2 dV, particle units
  std::vector<MeshLevel> mesh_study;
  std::vector<TimeSample> time_series; // Boussinesq in time: BDF2 (first step BDF1)
  double time_step = 0;                // in time: the step used

  // Low-Mach (continuum/low_mach.hpp); its Nu is normalised by kappa(T_ref) dT / H (Le Quere 2005)
  double thermodynamic_pressure = 0; // P of the closed box, from its mass
  double pressure_ratio = 0;         // P / p0, p0 = n k T_ref (the box at rest at T_ref)
  double mass_error = 0;             // int n dV / N - 1 at the end
  double density_min = 0;            // number density n = P / (k T) at the nodes
  double density_max = 0;
  // Per wall as `walls`: Nu from the consistent (residual) flux, converges faster than the
  // wall gradient.
  std::vector<double> consistent_wall_nusselt;

  // In time (all models)
  double time = 0;
  int time_steps = 0;
  double heat_flux_lower = 0, heat_flux_upper = 0; // into the domain through the walls of the
                                                   // heated (or first walled) direction

  double temperature_min = 0, temperature_max = 0, temperature_mean = 0;
  BinAverages bins;
  std::vector<std::array<double, 3>> probe_points;
  std::vector<std::vector<double>> probe_values; // [point][component], as the first bins.names
  std::vector<std::string> files;                // written into the output folder
};

io::Json to_json(const ContinuumParameters&);
io::Json to_json(const ContinuumResult&);
// One line per bin: indices, centre, every field.
std::string bins_csv(const ContinuumResult&, const ContinuumParameters&);
// The twin's bins with one input moved by +1 standard error, minus its own: the part of a
// particle-twin difference that input's error can explain, bin by bin.
struct BinResponse {
  std::string input; // "conductivity", "kapitza_x_lower", ...
  BinAverages change;
};
// One line per bin of each response: the input's name, then as bins_csv.
std::string bin_responses_csv(const std::vector<BinResponse>&, const ContinuumParameters&, int dim);
// One line per face quadrature point of each fixed-temperature wall.
std::string wall_nusselt_csv(const ContinuumResult&);
// One line per TimeSample, units in the header.
std::string time_series_csv(const ContinuumResult&);

} // namespace twinflow::continuum
