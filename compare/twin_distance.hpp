#pragma once
// The distance between the twins on the scene's bins: the particle fluid's bin averages (with
// their block standard errors) against the continuum's averages over the same bins. Plain data
// in, plain numbers out; no solver, no case file.

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "io/field_file.hpp"
#include "io/json.hpp"

namespace twinflow::compare {

// Temperature and velocity per bin (bin index x fastest, as io::Grid). Velocity components of
// bin b sit at b * dim + c. Standard errors are empty for the continuum.
struct BinnedState {
  io::Grid grid;
  std::vector<double> temperature, temperature_se;
  std::vector<double> velocity, velocity_se; // empty if the twin has no flow
  std::vector<double> density, density_se;   // the particle's; the low-Mach twin's (no errors)
  std::vector<std::vector<double>> temperature_blocks; // the particle's per block (blocks.csv)
  // A twin's change with each input moved by +1 standard error (coefficient_responses.csv), laid
  // out as the fields; empty where the twin's inputs carry no errors.
  struct Response {
    std::string input;
    std::vector<double> temperature, velocity, density;
  };
  std::vector<Response> responses;
  bool has_velocity() const { return !velocity.empty(); }
};

// The particle run's binned averages of one snapshot (temperature = T_kinetic).
BinnedState particle_state(const io::Grid& grid, const io::Snapshot& snapshot);
// RUNDIR/particle/blocks.csv: T_kinetic of each block on the grid's bins (throws io::InputError
// if it does not fit).
std::vector<std::vector<double>> read_temperature_blocks(const io::Grid& grid,
                                                         const std::filesystem::path& blocks_csv);
// RUNDIR/<continuum stage>/bins.csv on the same grid (throws io::InputError if it does not fit);
// the density from its column "n" where there is one.
BinnedState continuum_state(const io::Grid& grid, const std::filesystem::path& bins_csv);
// A twin's coefficient_responses.csv (the continuum stage's, where its inputs carry errors) into
// `twin.responses`; nothing where the file is absent.
void read_coefficient_responses(const std::filesystem::path& csv, BinnedState& twin);

// Bins whose whole extent lies at least `wall_layer` from every wall; `walled[d]`: direction d
// has walls (else periodic).
std::vector<char> interior_bins(const io::Grid& grid, const std::array<bool, 3>& walled,
                                double wall_layer);

// Relative L2 and max distance over the interior bins, in units of `scale`:
//   l2 = sqrt(mean_b |a_b - c_b|^2) / scale, with a the particle and c the continuum value;
//   noise = sqrt(mean_b sigma_b^2) / scale: the l2 that two identical twins would show through
//   the particle's statistical error alone; excess = sqrt(max(0, l2^2 - noise^2)): the part
//   that noise does not explain; l2_stderr propagates the block errors to l2;
//   max = max_b |a_b - c_b| / scale with the standard error at that bin.
// noise: the particle's, the L2 that its errors alone give; noise_twin: the L2 that the twin's
// inputs' errors give (its responses); l2_stderr from both, the twin's linearised.
struct Distance {
  double l2 = 0, l2_stderr = 0, noise = 0, excess = 0, noise_twin = 0;
  double max = 0, max_stderr = 0;
  std::array<double, 3> max_at{{0, 0, 0}}; // centre of the bin of the max
  long bins = 0;
  io::Json to_json() const;
};
Distance temperature_distance(const BinnedState& particle, const BinnedState& continuum,
                              const std::vector<char>& interior, double scale);
Distance velocity_distance(const BinnedState& particle, const BinnedState& continuum,
                           const std::vector<char>& interior, double scale);

// The number density's distance in units of `scale` (empty if the twin has no density field).
Distance density_distance(const BinnedState& particle, const BinnedState& continuum,
                          const std::vector<char>& interior, double scale);

// The fluid's temperature at a wall (direction d, side 0: x_d = 0, 1: x_d = L_d), extrapolated
// linearly from the first two bin layers beyond the wall layer and averaged over the interior
// bins along the wall, with its standard error: from the spread of the same extrapolation over
// the particle's blocks where it has them (the bins' correlations included): the largest of the
// errors with 1, 2 and 4 adjacent blocks merged (`blocking`), since a roll that changes more
// slowly than a block makes the short-block error too small; else from the bins' errors as if
// independent.
struct WallFluidTemperature {
  double value = 0, stderr_ = 0;
  double extrapolated_from = 0; // distance from the wall of the nearer bin layer used
  std::vector<double> blocking;
};
// `plane`: the distance from the wall plane to extrapolate to (a wall's effective position).
WallFluidTemperature wall_fluid_temperature(const BinnedState& particle,
                                            const std::vector<char>& interior, int direction,
                                            int side, double plane = 0);

// Mid-line profiles: along each direction a through the box centre, the bins' values averaged
// over the central layer(s) of the other directions (two layers when the count is even).
// Rows: direction, coordinate, then per state T (and T_se for the particle), velocity
// components (and their errors).
std::string
midline_profiles_csv(const BinnedState& particle,
                     const std::vector<std::pair<std::string, const BinnedState*>>& continua);

// Every bin: centre, interior flag, the particle's T and velocity with errors, each continuum's.
std::string bins_csv(const BinnedState& particle, const std::vector<char>& interior,
                     const std::vector<std::pair<std::string, const BinnedState*>>& continua);

} // namespace twinflow::compare
