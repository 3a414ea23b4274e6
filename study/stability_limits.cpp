#include "study/stability_limits.hpp"

#include <optional>
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

namespace {

// ec-verlet, and euler with the offset, take each particle's own K + P change from its u (002
// Appendix A): with a pair force that is the force's energy flow (docs/theory.md, "The particle
// model").
std::optional<std::string> per_particle_offset_warning(const particle::ParticleParameters& p,
                                                       bool thermal_walls) {
  using particle::Integrator;
  const bool per_particle = p.integrator == Integrator::EcVerlet ||
                            (p.integrator == Integrator::Euler && p.energy_offset);
  if (!per_particle || !thermal_walls || p.energy != particle::EnergyModel::Dpde ||
      p.conservative == particle::ConservativeForce::None)
    return std::nullopt;
  return std::string("warning: ") + particle::to_string(p.integrator) +
         " takes each particle's own kinetic and potential change from its internal energy; with "
         "a pair force that carries the force's energy flow in u, and a fluid between thermal "
         "walls settles above their temperature (the column's fluid, walls at 1: 7% above when "
         "shardlow took it per particle; ec-verlet at dt 0.002 and euler at 0.005 stopped with "
         "u < 0); shardlow pools the change "
         "(Particle/Integrator = shardlow, Particle/Energy offset = true)";
}

} // namespace

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
  if (const auto w = per_particle_offset_warning(p, thermal_walls)) out.push_back(*w);
  return out;
}

} // namespace twinflow::study
