#include "compare/twin_distance.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "io/csv.hpp"
#include "io/files.hpp"
#include "statistics/blocking.hpp"

namespace twinflow::compare {

namespace {

std::array<long, 3> bin_index(const io::Grid& g, long b) {
  return {{b % g.counts[0], (b / g.counts[0]) % g.counts[1], b / (g.counts[0] * g.counts[1])}};
}

long flat_index(const io::Grid& g, const std::array<long, 3>& i) {
  return i[0] + g.counts[0] * (i[1] + g.counts[1] * i[2]);
}

double centre(const io::Grid& g, int d, long i) {
  return g.origin[d] + (i + 0.5) * g.spacing[d];
}

const io::Field& require_field(const io::Snapshot& s, const std::string& name) {
  const io::Field* f = s.find(name);
  if (!f) throw io::InputError("particle fields: no field '" + name + "' in the snapshot");
  return *f;
}

// Central layer(s) of an axis with n bins: one when n is odd, two when it is even.
std::vector<long> central_layers(long n) {
  if (n % 2) return {n / 2};
  return {n / 2 - 1, n / 2};
}

} // namespace

io::Json Distance::to_json() const {
  io::Json j{{"l2", l2},         {"l2_stderr", l2_stderr},
             {"noise", noise},   {"excess_over_noise", excess},
             {"max", max},       {"max_stderr", max_stderr},
             {"max_at", max_at}, {"bins", static_cast<double>(bins)}};
  if (noise_twin > 0) j["noise_twin"] = noise_twin;
  return j;
}

BinnedState particle_state(const io::Grid& grid, const io::Snapshot& snapshot) {
  BinnedState s;
  s.grid = grid;
  const io::Field& T = require_field(snapshot, "temperature_kinetic");
  s.temperature = T.values;
  s.temperature_se = T.standard_error;
  const io::Field& n = require_field(snapshot, "density");
  s.density = n.values;
  s.density_se = n.standard_error;
  if (const io::Field* v = snapshot.find("velocity")) {
    s.velocity = v->values;
    s.velocity_se = v->standard_error;
  }
  return s;
}

namespace {
// The twin's bins from the rows of a table laid out as bins.csv (those of one `input` where the
// table has that column, else all); `file` names it in errors.
BinnedState state_from_table(const io::Grid& grid, const io::CsvTable& table,
                             const std::string& file, const std::string& input = "") {
  const auto& header = table.header;
  const auto column = [&](const std::string& name) { return table.find(name); };
  const char* index_names[3] = {"ix", "iy", "iz"};
  const char* velocity_names[3] = {"u_x", "u_y", "u_z"};
  std::array<int, 3> index_column{{-1, -1, -1}}, velocity_column{{-1, -1, -1}};
  for (int d = 0; d < grid.dim; ++d) {
    index_column[d] = column(index_names[d]);
    velocity_column[d] = column(velocity_names[d]);
    if (index_column[d] < 0)
      throw io::InputError(file + ": no column '" + index_names[d] +
                           "'; the continuum's bins do not match the particle grid");
  }
  const int t_column = column("T");
  if (t_column < 0) throw io::InputError(file + ": no temperature column 'T'");
  const bool has_velocity = velocity_column[0] >= 0;
  const int n_column = column("n"); // the low-Mach twin's number density
  const int input_column = column("input");

  BinnedState s;
  s.grid = grid;
  const long cells = grid.cell_count();
  s.temperature.assign(cells, std::nan(""));
  if (has_velocity) s.velocity.assign(cells * grid.dim, std::nan(""));
  if (n_column >= 0) s.density.assign(cells, std::nan(""));
  long rows = 0;
  for (const auto& v : table.rows) {
    if (v.size() != header.size())
      throw io::InputError(file + ": a row has " + std::to_string(v.size()) +
                           " values, the header " + std::to_string(header.size()));
    if (input_column >= 0 && v[input_column] != input) continue;
    std::array<long, 3> i{{0, 0, 0}};
    for (int d = 0; d < grid.dim; ++d) {
      i[d] = std::stol(v[index_column[d]]);
      if (i[d] < 0 || i[d] >= grid.counts[d])
        throw io::InputError(file + ": bin index " + std::to_string(i[d]) +
                             " outside the particle grid's " + std::to_string(grid.counts[d]));
    }
    const long b = flat_index(grid, i);
    s.temperature[b] = std::stod(v[t_column]);
    if (has_velocity)
      for (int d = 0; d < grid.dim; ++d)
        s.velocity[b * grid.dim + d] = std::stod(v[velocity_column[d]]);
    if (n_column >= 0) s.density[b] = std::stod(v[n_column]);
    ++rows;
  }
  if (rows != cells)
    throw io::InputError(file + ": " + std::to_string(rows) + " bins" +
                         (input.empty() ? "" : " for '" + input + "'") +
                         ", the particle grid has " + std::to_string(cells));
  return s;
}
} // namespace

BinnedState continuum_state(const io::Grid& grid, const std::filesystem::path& bins_csv) {
  return state_from_table(grid, io::parse_csv(io::read_file(bins_csv)), bins_csv.string());
}

void read_coefficient_responses(const std::filesystem::path& csv, BinnedState& twin) {
  twin.responses.clear();
  if (!std::filesystem::exists(csv)) return;
  const io::CsvTable table = io::parse_csv(io::read_file(csv));
  const int input_column = table.find("input");
  if (table.rows.empty()) return;
  if (input_column < 0) throw io::InputError(csv.string() + ": no column 'input'");
  std::vector<std::string> inputs; // in the file's order
  for (const auto& v : table.rows)
    if (std::find(inputs.begin(), inputs.end(), v.at(input_column)) == inputs.end())
      inputs.push_back(v.at(input_column));
  for (const std::string& input : inputs) {
    BinnedState r = state_from_table(twin.grid, table, csv.string(), input);
    twin.responses.push_back(
        {input, std::move(r.temperature), std::move(r.velocity), std::move(r.density)});
  }
}

std::vector<char> interior_bins(const io::Grid& grid, const std::array<bool, 3>& walled,
                                double wall_layer) {
  std::vector<char> interior(grid.cell_count(), 1);
  for (long b = 0; b < grid.cell_count(); ++b) {
    const auto i = bin_index(grid, b);
    for (int d = 0; d < grid.dim; ++d) {
      if (!walled[d]) continue;
      const double lower = i[d] * grid.spacing[d], upper = (i[d] + 1) * grid.spacing[d];
      const double length = grid.counts[d] * grid.spacing[d];
      // A small tolerance: a layer equal to a bin width excludes exactly that bin.
      const double tol = 1e-9 * grid.spacing[d];
      if (lower < wall_layer - tol || upper > length - wall_layer + tol) interior[b] = 0;
    }
  }
  return interior;
}

namespace {
// One field's sums over the interior bins: the squared differences, the particle's variances,
// their products, and per twin response its dot product with the difference and its square.
struct Sums {
  double d2 = 0, sigma2 = 0, d2_sigma2 = 0, twin2 = 0;
  std::vector<double> dot; // per response: sum of d . response
};

// l2, its error and the noises from the sums. d(mean d^2) = (2/n) sqrt(sum d^2 sigma^2 + sum over
// responses (d . response)^2) (the particle's errors bin by bin, the twin's linearised in its
// inputs' errors); d l2 = d(mean d^2) / (2 l2). docs/theory.md, "The distance between the twins
// and its errors".
Distance finish(const Sums& s, long n, double max, double max_se, std::array<double, 3> max_at) {
  Distance r;
  r.bins = n;
  if (n == 0) return r;
  const double mean_d2 = s.d2 / n;
  r.l2 = std::sqrt(mean_d2);
  r.noise = std::sqrt(s.sigma2 / n);
  r.noise_twin = std::sqrt(s.twin2 / n);
  r.excess = std::sqrt(std::max(0.0, mean_d2 - s.sigma2 / n));
  double var = s.d2_sigma2;
  for (const double dot : s.dot) var += dot * dot;
  r.l2_stderr = r.l2 > 0 ? std::sqrt(var) / (n * r.l2) : r.noise;
  r.max = max;
  r.max_stderr = max_se;
  r.max_at = max_at;
  return r;
}

// The distance of fields with `components` values per bin (1: scalar, dim: vector, compared by
// the norm of the difference); `a_se` may be empty; `responses` the twin's, one field each.
Distance field_distance(const io::Grid& grid, const std::vector<double>& a,
                        const std::vector<double>& a_se, const std::vector<double>& c,
                        int components, const std::vector<char>& interior, double scale,
                        const std::vector<const std::vector<double>*>& responses) {
  Sums sums;
  sums.dot.assign(responses.size(), 0.0);
  double max = -1, max_se = 0;
  std::array<double, 3> at{{0, 0, 0}};
  long n = 0;
  for (long b = 0; b < grid.cell_count(); ++b) {
    if (!interior[b]) continue;
    double d2 = 0, sig2 = 0, d2sig2 = 0;
    for (int k = 0; k < components; ++k) {
      const long i = b * components + k;
      const double d = (a[i] - c[i]) / scale;
      const double sig = a_se.empty() ? 0 : a_se[i] / scale;
      d2 += d * d;
      sig2 += sig * sig;
      d2sig2 += d * d * sig * sig;
      for (std::size_t r = 0; r < responses.size(); ++r) {
        const double g = (*responses[r])[i] / scale;
        sums.dot[r] += d * g;
        sums.twin2 += g * g;
      }
    }
    sums.d2 += d2;
    sums.sigma2 += sig2;
    sums.d2_sigma2 += d2sig2;
    if (std::sqrt(d2) > max) {
      max = std::sqrt(d2);
      // error of |a - c| along its own direction
      max_se = d2 > 0 ? std::sqrt(d2sig2 / d2) : std::sqrt(sig2);
      const auto i = bin_index(grid, b);
      for (int k = 0; k < 3; ++k) at[k] = centre(grid, k, i[k]);
    }
    ++n;
  }
  return finish(sums, n, std::max(max, 0.0), max_se, at);
}

// The twin's responses of one field (those that have it).
template <class Member>
std::vector<const std::vector<double>*> responses_of(const BinnedState& twin, Member field) {
  std::vector<const std::vector<double>*> out;
  for (const auto& r : twin.responses)
    if (!(r.*field).empty()) out.push_back(&(r.*field));
  return out;
}
} // namespace

Distance temperature_distance(const BinnedState& p, const BinnedState& c,
                              const std::vector<char>& interior, double scale) {
  return field_distance(p.grid, p.temperature, p.temperature_se, c.temperature, 1, interior, scale,
                        responses_of(c, &BinnedState::Response::temperature));
}

Distance velocity_distance(const BinnedState& p, const BinnedState& c,
                           const std::vector<char>& interior, double scale) {
  if (!p.has_velocity() || !c.has_velocity()) return {};
  return field_distance(p.grid, p.velocity, p.velocity_se, c.velocity, p.grid.dim, interior, scale,
                        responses_of(c, &BinnedState::Response::velocity));
}

Distance density_distance(const BinnedState& p, const BinnedState& c,
                          const std::vector<char>& interior, double scale) {
  if (c.density.empty()) return {};
  return field_distance(p.grid, p.density, p.density_se, c.density, 1, interior, scale,
                        responses_of(c, &BinnedState::Response::density));
}

WallFluidTemperature wall_fluid_temperature(const BinnedState& p, const std::vector<char>& interior,
                                            int direction, int side, double plane) {
  const io::Grid& g = p.grid;
  const long n = g.counts[direction];
  // Layer index counted from the wall, and back to the grid index.
  auto grid_index = [&](long k) { return side == 0 ? k : n - 1 - k; };
  long first = -1;
  for (long k = 0; k + 1 < n && first < 0; ++k)
    for (long b = 0; b < g.cell_count(); ++b)
      if (interior[b] && bin_index(g, b)[direction] == grid_index(k)) {
        first = k;
        break;
      }
  WallFluidTemperature w;
  if (first < 0) return {std::nan(""), std::nan(""), 0, {}};
  const double h = g.spacing[direction];
  w.extrapolated_from = (first + 0.5) * h;
  const double r = (w.extrapolated_from - plane) / h; // T(plane) = T1 + (T1 - T2) r
  // The bins of the first layer beyond the wall layer and their neighbours one layer further in.
  std::vector<std::pair<long, long>> columns;
  for (long b = 0; b < g.cell_count(); ++b) {
    auto i = bin_index(g, b);
    if (!interior[b] || i[direction] != grid_index(first)) continue;
    i[direction] = grid_index(first + 1);
    columns.emplace_back(b, flat_index(g, i));
  }
  const double count = static_cast<double>(columns.size());
  auto extrapolated = [&](const std::vector<double>& t) { // mean over the columns
    double sum = 0;
    for (const auto& [b1, b2] : columns) sum += (1 + r) * t[b1] - r * t[b2];
    return sum / count;
  };
  w.value = extrapolated(p.temperature);
  double var = 0;
  if (!p.temperature_se.empty())
    for (const auto& [b1, b2] : columns)
      var += (1 + r) * (1 + r) * p.temperature_se[b1] * p.temperature_se[b1] +
             r * r * p.temperature_se[b2] * p.temperature_se[b2];
  w.stderr_ = std::sqrt(var) / count;
  if (p.temperature_blocks.size() < 2) return w;
  std::vector<double> per_block; // the same extrapolation, block by block
  for (const auto& t : p.temperature_blocks) per_block.push_back(extrapolated(t));
  w.blocking = statistics::merged_blocking_errors(per_block);
  // The estimate grows with the block length until blocks outlast the correlation time
  // (Flyvbjerg & Petersen 1989); with a few levels only, the largest is the honest figure.
  w.stderr_ = *std::max_element(w.blocking.begin(), w.blocking.end());
  return w;
}

std::vector<std::vector<double>> read_temperature_blocks(const io::Grid& grid,
                                                         const std::filesystem::path& blocks_csv) {
  const io::CsvTable table = io::parse_csv(io::read_file(blocks_csv)); // block,bin,T_kinetic
  std::vector<std::vector<double>> blocks;
  for (const auto& f : table.rows) {
    std::string line;
    for (std::size_t k = 0; k < f.size(); ++k) line += (k ? "," : "") + f[k];
    std::size_t block = 0, bin = 0;
    double t = 0;
    try {
      if (f.size() != 3) throw std::invalid_argument("columns");
      block = std::stoul(f[0]), bin = std::stoul(f[1]), t = std::stod(f[2]);
    } catch (const std::exception&) {
      throw io::InputError(blocks_csv.string() + ": bad row '" + line + "' (block,bin,T_kinetic)");
    }
    if (bin >= static_cast<std::size_t>(grid.cell_count()) || block > blocks.size())
      throw io::InputError(blocks_csv.string() + ": row '" + line +
                           "' does not fit the particle grid");
    if (block == blocks.size()) blocks.emplace_back(grid.cell_count(), std::nan(""));
    blocks[block][bin] = t;
  }
  return blocks;
}

namespace {
struct ProfilePoint {
  double T = 0, T_se = 0;
  std::array<double, 3> v{{0, 0, 0}}, v_se{{0, 0, 0}};
};

// Mean over the central layers of the other directions at index i along `direction`.
ProfilePoint profile_point(const BinnedState& s, int direction, long i) {
  const io::Grid& g = s.grid;
  const int dim = g.dim;
  std::vector<long> layers[3];
  for (int d = 0; d < 3; ++d)
    layers[d] = d == direction ? std::vector<long>{i} : central_layers(g.counts[d]);
  ProfilePoint p;
  std::array<double, 3> v_var{{0, 0, 0}};
  double T_var = 0;
  long m = 0;
  for (long a : layers[0])
    for (long b : layers[1])
      for (long c : layers[2]) {
        const long k = flat_index(g, {{a, b, c}});
        p.T += s.temperature[k];
        if (!s.temperature_se.empty()) T_var += s.temperature_se[k] * s.temperature_se[k];
        if (s.has_velocity())
          for (int d = 0; d < dim; ++d) {
            p.v[d] += s.velocity[k * dim + d];
            if (!s.velocity_se.empty())
              v_var[d] += s.velocity_se[k * dim + d] * s.velocity_se[k * dim + d];
          }
        ++m;
      }
  p.T /= m;
  p.T_se = std::sqrt(T_var) / m;
  for (int d = 0; d < dim; ++d) {
    p.v[d] /= m;
    p.v_se[d] = std::sqrt(v_var[d]) / m;
  }
  return p;
}

const char* kAxis = "xyz";

void write_state_header(std::ostream& out, const std::string& name, const BinnedState& s,
                        bool errors) {
  out << ",T_" << name;
  if (errors) out << ",T_" << name << "_se";
  if (s.has_velocity())
    for (int d = 0; d < s.grid.dim; ++d) {
      out << ",v" << kAxis[d] << "_" << name;
      if (errors) out << ",v" << kAxis[d] << "_" << name << "_se";
    }
}
} // namespace

std::string
midline_profiles_csv(const BinnedState& particle,
                     const std::vector<std::pair<std::string, const BinnedState*>>& continua) {
  std::ostringstream out;
  out << std::setprecision(10);
  out << "# mid-line profiles: bins along each direction through the box centre, averaged over "
         "the central layer(s) of the other directions; _se: block standard errors\n";
  out << "direction,coordinate";
  write_state_header(out, "particle", particle, true);
  for (const auto& [name, s] : continua) write_state_header(out, name, *s, false);
  out << "\n";
  const io::Grid& g = particle.grid;
  const int dim = g.dim;
  for (int d = 0; d < dim; ++d)
    for (long i = 0; i < g.counts[d]; ++i) {
      out << kAxis[d] << "," << centre(g, d, i);
      const ProfilePoint p = profile_point(particle, d, i);
      out << "," << p.T << "," << p.T_se;
      if (particle.has_velocity())
        for (int k = 0; k < dim; ++k) out << "," << p.v[k] << "," << p.v_se[k];
      for (const auto& entry : continua) {
        const BinnedState& s = *entry.second;
        const ProfilePoint q = profile_point(s, d, i);
        out << "," << q.T;
        if (s.has_velocity())
          for (int k = 0; k < dim; ++k) out << "," << q.v[k];
      }
      out << "\n";
    }
  return out.str();
}

std::string bins_csv(const BinnedState& particle, const std::vector<char>& interior,
                     const std::vector<std::pair<std::string, const BinnedState*>>& continua) {
  std::ostringstream out;
  out << std::setprecision(10);
  out << "# every bin: centre, interior (1: counted in the field errors), the particle's "
         "averages with block standard errors (_se), each continuum twin's bin averages\n";
  const io::Grid& g = particle.grid;
  const int dim = g.dim;
  for (int d = 0; d < dim; ++d) out << (d ? "," : "") << kAxis[d];
  out << ",interior,density_particle,density_particle_se";
  write_state_header(out, "particle", particle, true);
  for (const auto& [name, s] : continua) {
    write_state_header(out, name, *s, false);
    if (!s->density.empty()) out << ",density_" << name;
  }
  out << "\n";
  for (long b = 0; b < g.cell_count(); ++b) {
    const auto i = bin_index(g, b);
    for (int d = 0; d < dim; ++d) out << (d ? "," : "") << centre(g, d, i[d]);
    out << "," << int(interior[b]) << "," << particle.density[b] << ","
        << (particle.density_se.empty() ? 0.0 : particle.density_se[b]);
    out << "," << particle.temperature[b] << ","
        << (particle.temperature_se.empty() ? 0.0 : particle.temperature_se[b]);
    if (particle.has_velocity())
      for (int k = 0; k < dim; ++k)
        out << "," << particle.velocity[b * dim + k] << ","
            << (particle.velocity_se.empty() ? 0.0 : particle.velocity_se[b * dim + k]);
    for (const auto& entry : continua) {
      const BinnedState& s = *entry.second;
      out << "," << s.temperature[b];
      if (s.has_velocity())
        for (int k = 0; k < dim; ++k) out << "," << s.velocity[b * dim + k];
      if (!s.density.empty()) out << "," << s.density[b];
    }
    out << "\n";
  }
  return out.str();
}

} // namespace twinflow::compare
