#include "transport/measure.hpp"

#include <cmath>
#include <sstream>
#include <vector>

namespace twinflow::transport {

using particle::Estimate;

particle::Estimate diffusion_from_msd(const std::string& csv, int dim) {
  std::vector<double> t, msd;
  std::istringstream in(csv);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || !std::isdigit(static_cast<unsigned char>(line[0]))) continue;
    std::istringstream row(line);
    std::string a, b, c;
    std::getline(row, a, ','), std::getline(row, b, ','), std::getline(row, c, ',');
    t.push_back(std::stod(a)), msd.push_back(std::stod(c));
  }
  Estimate e;
  const std::size_t n = t.size(), first = n / 2;
  if (n - first < 6) return e;
  // Least-squares slope of msd(t) over [from, to)
  auto fit = [&](std::size_t from, std::size_t to) {
    double st = 0, sm = 0, stt = 0, stm = 0;
    const double k = static_cast<double>(to - from);
    for (std::size_t i = from; i < to; ++i)
      st += t[i], sm += msd[i], stt += t[i] * t[i], stm += t[i] * msd[i];
    return (k * stm - st * sm) / (k * stt - st * st);
  };
  const std::size_t mid = (first + n) / 2;
  e.mean = fit(first, n) / (2 * dim); // Einstein relation: MSD = 2 d D t
  // MSD points are strongly correlated, so a fit residual would understate the error: take the
  // difference between the slopes of the two halves of the window instead.
  e.stderr_ = std::fabs(fit(first, mid) - fit(mid, n)) / (2 * dim) / 2;
  return e;
}

namespace {
struct Point {
  Estimate p, t;
  std::string rdf, corr;
};
Point run_at(particle::ParticleParameters p, double density, double temperature, long steps) {
  p.density = density;
  p.temperature = temperature;
  p.steps = steps;
  p.equilibration_steps = steps / 2;
  const auto out = particle::run_particles(p);
  const auto& r = out.summary;
  Point pt;
  pt.p = {r.find("pressure")->number(), r.find("pressure_stderr")->number()};
  pt.t = {r.find("T_kinetic")->number(), r.find("T_kinetic_stderr")->number()};
  pt.rdf = out.rdf_csv;
  pt.corr = out.correlations_csv;
  return pt;
}
} // namespace

Measured measure(const particle::ParticleParameters& p, long steps, double h) {
  Measured m;
  const double rho = p.density, T = p.temperature;
  const Point c = run_at(p, rho, T, steps);
  m.pressure = c.p;
  m.temperature = c.t;
  m.rdf_csv = c.rdf;
  m.diffusion = diffusion_from_msd(c.corr, p.dim);
  const Point tp = run_at(p, rho, T * (1 + h), steps), tm = run_at(p, rho, T * (1 - h), steps);
  const Point rp = run_at(p, rho * (1 + h), T, steps), rm = run_at(p, rho * (1 - h), T, steps);
  // Central differences against the measured temperatures (an NVE run's T is an outcome).
  const double dtemp = tp.t.mean - tm.t.mean;
  m.dp_dt = {(tp.p.mean - tm.p.mean) / dtemp,
             std::hypot(tp.p.stderr_, tm.p.stderr_) / std::fabs(dtemp)};
  m.dp_drho = {(rp.p.mean - rm.p.mean) / (2 * h * rho),
               std::hypot(rp.p.stderr_, rm.p.stderr_) / (2 * h * rho)};
  const double alpha = m.dp_dt.mean / (rho * m.dp_drho.mean); // physics.md
  m.expansion = {alpha, std::fabs(alpha) * std::hypot(m.dp_dt.stderr_ / m.dp_dt.mean,
                                                      m.dp_drho.stderr_ / m.dp_drho.mean)};
  return m;
}

io::Json Measured::json() const {
  io::Json j = io::Json::object();
  auto put = [&](const char* k, const Estimate& e) {
    j[k] = e.mean;
    j[std::string(k) + "_stderr"] = e.stderr_;
  };
  put("pressure", pressure);
  put("temperature_kinetic", temperature);
  put("self_diffusion", diffusion);
  put("thermal_expansion", expansion);
  put("dp_dT", dp_dt);
  put("dp_drho", dp_drho);
  return j;
}

particle::Estimate measure_conductivity_relaxation(particle::ParticleParameters p,
                                                   const Estimates& estimate, double cp) {
  p.box[0] *= 2;
  p.temperature_perturbation = 0.2;
  p.heat_slabs.clear();
  const double k = 2 * M_PI / p.box[0];
  const double chi = estimate.conductivity / (p.density * estimate.heat_capacity_p);
  p.equilibration_steps = 0;
  p.steps = static_cast<long>(std::ceil(3 / (chi * k * k) / p.dt)); // three decay times
  p.sample_interval = std::max(1L, p.steps / 1000);
  p.bins = {{1, 1, 1}};
  const auto out = particle::run_particles(p);
  const io::Json* r = out.summary.find("relaxation");
  if (!r || !r->find("chi")) return {std::nan(""), std::nan("")};
  const double scale = p.density * cp; // kappa = rho c_p chi
  return {scale * r->find("chi")->number(), scale * r->find("chi_stderr")->number()};
}

particle::Estimate measure_viscosity_poiseuille(particle::ParticleParameters p,
                                                const Estimates& estimate) {
  p.box[1] *= 2;
  const double half = 0.5 * p.box[1], nu = estimate.kinematic_viscosity;
  // Peak speed n F half^2 / (8 eta) = 0.1 sqrt(k T / m).
  p.poiseuille_force =
      0.8 * estimate.viscosity * std::sqrt(p.temperature / p.mass) / (p.density * half * half);
  // The slowest start-up mode decays in half^2 / (pi^2 nu): five of those to steady state.
  const double settle = 5 * half * half / (M_PI * M_PI * nu);
  p.equilibration_steps = static_cast<long>(std::ceil(settle / p.dt));
  p.steps = p.equilibration_steps;
  p.sample_interval = std::max(1L, p.steps / 2000);
  p.bins = {{1, 40, 1}};
  const auto out = particle::run_particles(p);
  const io::Json* r = out.summary.find("poiseuille");
  if (!r || !r->find("viscosity")) return {std::nan(""), std::nan("")};
  return {r->find("viscosity")->number(), r->find("viscosity_stderr")->number()};
}

} // namespace twinflow::transport
