#include "study/stability_limits.hpp"

#include <sstream>

#include "io/files.hpp"
#include "particle/theory.hpp"

namespace twinflow::study {

std::vector<StabilityLimit> read_stability_limits(const std::filesystem::path& csv) {
  std::vector<StabilityLimit> out;
  std::istringstream in(io::read_file(csv));
  int number = 0;
  bool header = true;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    if (header) { // integrator,scene,largest_stable_dt,smallest_failed_dt,maps
      header = false;
      continue;
    }
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; cells.size() < 4 && std::getline(row, cell, ',');) cells.push_back(cell);
    std::string rest;
    std::getline(row, rest);
    try {
      if (cells.size() < 4) throw std::invalid_argument("too few columns");
      out.push_back({cells[0], cells[1], std::stod(cells[2]),
                     cells[3].empty() ? 0.0 : std::stod(cells[3]), rest});
    } catch (const std::exception& e) {
      throw io::InputError(
          csv.string() + ":" + std::to_string(number) +
          ": not a row integrator,scene,largest_stable_dt,smallest_failed_dt,maps (" + e.what() +
          ")");
    }
  }
  return out;
}

std::filesystem::path shipped_case(const std::string& name) {
  return std::filesystem::path(TWINFLOW_SOURCE_DIR) / "cases" / (name + ".prm");
}

const std::vector<StabilityLimit>& stability_limits() {
  static const std::vector<StabilityLimit> limits = read_stability_limits(
      std::filesystem::path(TWINFLOW_SOURCE_DIR) / "data" / "stability_limits.csv");
  return limits;
}

std::vector<std::string> stiff_choice_warnings(const particle::ParticleParameters& p,
                                               const std::vector<StabilityLimit>& limits) {
  std::vector<std::string> out;
  bool thermal_walls = false;
  for (int d = 0; d < p.dim; ++d)
    thermal_walls |= p.walls[d].present && (p.walls[d].thermal[0] || p.walls[d].thermal[1]);
  const std::string integrator = particle::to_string(p.integrator);
  for (const StabilityLimit& l : limits) {
    if (l.integrator == integrator && l.scene == "thermal walls" && thermal_walls &&
        p.dt > l.largest_stable_dt) {
      std::ostringstream s;
      s << "warning: " << integrator << " beside thermal walls at dt " << p.dt
        << ": the stability maps saw it fail there from dt " << l.smallest_failed_dt;
      if (l.largest_stable_dt > 0) s << " (stable up to " << l.largest_stable_dt << ")";
      s << " [" << l.maps
        << "]; shardlow runs these scenes stably (Particle/Integrator = shardlow)";
      out.push_back(s.str());
    }
    if (l.integrator == "any" && l.scene == "fluctuation number" &&
        p.energy == particle::EnergyModel::Dpde) {
      const double number = particle::fluctuation_stability_number(p);
      if (number > l.largest_stable_dt) {
        std::ostringstream s;
        s << "warning: the fluctuation number 000:(3.34) is " << number << " (bound "
          << l.largest_stable_dt << "; [" << l.maps
          << "]): a lower Particle/Time step, a larger heat capacity or weaker heat conduction "
             "keeps internal energies positive";
        out.push_back(s.str());
      }
    }
  }
  return out;
}

} // namespace twinflow::study
