#include "transport/estimates.hpp"

#include <cmath>
#include <sstream>

#include "particle/theory.hpp"

namespace twinflow::transport {

PairDistribution PairDistribution::from_csv(const std::string& csv) {
  PairDistribution g;
  std::istringstream in(csv);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || !(std::isdigit(static_cast<unsigned char>(line[0])) || line[0] == '.'))
      continue;
    const auto comma = line.find(',');
    g.r_.push_back(std::stod(line.substr(0, comma)));
    g.g_.push_back(std::stod(line.substr(comma + 1)));
  }
  return g;
}

double PairDistribution::operator()(double r) const {
  if (r_.empty()) return 1.0;
  if (r <= r_.front()) return g_.front();
  if (r >= r_.back()) return g_.back();
  std::size_t k = 1;
  while (r_[k] < r) ++k;
  const double t = (r - r_[k - 1]) / (r_[k] - r_[k - 1]);
  return (1 - t) * g_[k - 1] + t * g_[k];
}

namespace {
// Composite Simpson on [0, 1] with an even number of panels.
template <class F> double integrate01(F&& f, int panels = 2000) {
  const double h = 1.0 / panels;
  double s = f(0.0) + f(1.0);
  for (int k = 1; k < panels; ++k) s += (k % 2 ? 4 : 2) * f(k * h);
  return s * h / 3;
}
double weight(double l, double n) {
  return l < 1 ? std::pow(1 - l, n) : 0.0;
}
} // namespace

double pair_conductance(const particle::ParticleParameters& p, double T) {
  using namespace particle;
  if (p.energy == EnergyModel::Dpde && p.heat == HeatLaw::Inverse)
    return (p.heat_coefficient == HeatCoefficient::Constant ? p.kappa0
                                                            : p.kappa0 * p.cv * p.cv * T * T) /
           (T * T); // kappa_ij w_H / T^2
  if (p.energy == EnergyModel::Dpde && p.heat == HeatLaw::Linear)
    return p.cv * p.kappa0 * (1 + p.linear_noise_factor / (2 * p.cv)); // with the Ito drift
  return 0;
}

Estimates estimate(const particle::ParticleParameters& p, double T, const PairDistribution& g) {
  using namespace particle;
  Estimates e;
  e.temperature = T;
  e.density = p.density;
  const int d = p.dim;
  const double rho = p.density, m = p.mass;
  const double surface = d == 3 ? 4 * M_PI : 2 * M_PI; // integral over directions
  const double rd = p.dissipation.cutoff, nd = p.dissipation.exponent;
  const double rh = p.heat_weight.cutoff, nh = p.heat_weight.exponent;
  const double gamma = particle::pair_friction(p, T); // at equal temperatures, 002:(4)
  // int d^d r r^k g(r) w(r) over r < rc, with l = r/rc
  auto moment = [&](int k, double rc, double n) {
    return surface * std::pow(rc, d + k) *
           integrate01([&](double l) { return std::pow(l, d - 1 + k) * g(l * rc) * weight(l, n); });
  };
  e.collision_time = 1 / (gamma * rho / (d * m) * moment(0, rd, nd)); // 002:(17), general d
  e.diffusion = T * e.collision_time / m;                             // 002:(25)
  e.viscosity_kinetic = rho * m * e.diffusion / 2;
  e.viscosity_dissipative = gamma * rho * rho / (2 * d * (d + 2)) * moment(2, rd, nd); // 002:(26)
  e.viscosity = e.viscosity_kinetic + e.viscosity_dissipative;

  const double lambda = pair_conductance(p, T);
  const double cv = p.energy == EnergyModel::Dpde ? p.cv : 0.0;
  e.conductivity_diffusion = rho * cv * e.diffusion;                            // 002:(21)
  e.conductivity_conduction = rho * rho / (2 * d) * lambda * moment(2, rh, nh); // 000:(3.25)
  e.conductivity = e.conductivity_diffusion + e.conductivity_conduction;

  if (d == 3) {
    // 002's coefficients with l = r/rc: I1 = int_0^1 ds (1 - s^2) int_s^1 dl l^3 g w_H
    //   = int_0^1 dl l^3 g w_H (l - l^3/3) after swapping the order (002:(14))
    e.i1_002 = integrate01(
        [&](double l) { return l * l * l * g(l * rh) * weight(l, nh) * (l - l * l * l / 3); });
    e.i2 = integrate01([&](double l) { return l * l * g(l * rd) * weight(l, nd); }); // 002:(17)
    e.i3 = integrate01([&](double l) { return std::pow(l, 4) * g(l * rd) * weight(l, nd); });
    // 002:(22): pi rho^2 (lambda T^2) rh^5 I1 / k + rho c_v D  (lambda T^2 = kappa_ij at T)
    e.conductivity_002_eq22 =
        M_PI * rho * rho * lambda * std::pow(rh, 5) * e.i1_002 + e.conductivity_diffusion;
  }
  e.expansion = 1 / T;                       // ideal gas, 000:(4.2)
  e.heat_capacity_v = cv + 1 + 0.5 * d;      // docs/theory.md: c_v + k + (d/2) k
  e.heat_capacity_p = e.heat_capacity_v + 1; // + k
  e.kinematic_viscosity = e.viscosity / (rho * m);
  e.diffusivity = e.conductivity / (rho * e.heat_capacity_p);
  e.prandtl = e.kinematic_viscosity / e.diffusivity;
  // 002:(23) as the paper evaluates it: C_P ~ c_v and kappa from its eq. (22)
  if (d == 3) e.prandtl_002 = e.viscosity * cv / e.conductivity_002_eq22;
  e.schmidt = e.kinematic_viscosity / e.diffusion; // 002:(24)
  return e;
}

double rayleigh(const Estimates& e, double gravity, double delta_t, double height) {
  return gravity * e.expansion * delta_t * std::pow(height, 3) /
         (e.kinematic_viscosity * e.diffusivity); // docs/theory.md
}

io::Json convection_numbers(const particle::ParticleParameters& p, double max_speed) {
  double g = 0;
  int up = -1;
  for (int d = 0; d < p.dim; ++d)
    if (std::fabs(p.gravity[d]) > g) g = std::fabs(p.gravity[d]), up = d;
  int across = -1;
  for (int d = 0; d < p.dim; ++d) {
    const auto& w = p.walls[d];
    if (w.present && w.thermal[0] && w.thermal[1] && w.temperature[0] != w.temperature[1])
      across = d;
  }
  if (up < 0 || across < 0) return io::Json();
  const auto& w = p.walls[across];
  const double t_mean = 0.5 * (w.temperature[0] + w.temperature[1]);
  const double dt = std::fabs(w.temperature[0] - w.temperature[1]);
  const Estimates e = estimate(p, t_mean, PairDistribution::ideal());
  // Isothermal sound speed dp/drho: ideal gas k T / m, plus Groot-Warren's 2 * 0.101 a0 rho for
  // a constant a0 repulsion (3D; an estimate elsewhere).
  double c2 = t_mean / p.mass;
  if (p.conservative != particle::ConservativeForce::None)
    c2 += 2 * 0.101 * p.a0 * p.density / p.mass;
  const double length = p.box[across], height = p.box[up];
  io::Json j = io::Json::object();
  j["mean_wall_temperature"] = t_mean;
  j["delta_T"] = dt;
  j["delta_T_over_T"] = dt / t_mean;
  j["alpha_delta_T"] = e.expansion * dt;
  j["stratification_g_H_over_c2"] = g * height / c2; // docs/theory.md
  j["sound_speed"] = std::sqrt(c2);
  j["rayleigh"] = rayleigh(e, g, dt, length); // on the distance between the thermal walls
  j["prandtl"] = e.prandtl;
  const double free_fall = std::sqrt(g * e.expansion * dt * length);
  j["mach_free_fall"] = free_fall / std::sqrt(c2);
  if (max_speed > 0) j["mach_measured"] = max_speed / std::sqrt(c2);
  j["note"] = "estimates at the mean wall temperature with g(r) = 1; alpha = 1/T (ideal gas)";
  return j;
}

io::Json Estimates::json() const {
  return io::Json{{"temperature", temperature},
                  {"density", density},
                  {"collision_time", collision_time},
                  {"self_diffusion", diffusion},
                  {"viscosity_kinetic", viscosity_kinetic},
                  {"viscosity_dissipative", viscosity_dissipative},
                  {"viscosity", viscosity},
                  {"conductivity_particle_diffusion", conductivity_diffusion},
                  {"conductivity_pair_conduction", conductivity_conduction},
                  {"conductivity", conductivity},
                  {"conductivity_002_eq22", conductivity_002_eq22},
                  {"I1_002", i1_002},
                  {"I2", i2},
                  {"I3", i3},
                  {"thermal_expansion", expansion},
                  {"heat_capacity_v_per_particle", heat_capacity_v},
                  {"heat_capacity_p_per_particle", heat_capacity_p},
                  {"kinematic_viscosity", kinematic_viscosity},
                  {"thermal_diffusivity", diffusivity},
                  {"prandtl", prandtl},
                  {"prandtl_002_convention", prandtl_002},
                  {"schmidt", schmidt}};
}

} // namespace twinflow::transport
