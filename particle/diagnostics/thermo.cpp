// The thermodynamic state over time: thermo.csv (every sample) and the block-averaged
// temperatures and pressure of the summary (sampled steps).
#include "particle/diagnostics/plugins.hpp"

#include <cstdio>

#include "particle/theory.hpp"
#include "statistics/blocking.hpp"

namespace twinflow::particle {

namespace {
template <int D> class Thermo : public Archived<D, Thermo<D>> {
public:
  Thermo(const ParticleParameters& p, const RunFacts& m)
      : Archived<D, Thermo<D>>("thermo"), p_(p), m_(m),
        csv_("# particle thermo: one row per sample. Units: m = k = rc = T0 = 1 (energies in k "
             "T0, time in tau)\n"
             "step,time,sampled,E_total,E_kinetic,E_internal,E_potential,T_kinetic,"
             "T_internal_harmonic,T_internal_mean,pressure,momentum_x,momentum_y,momentum_z\n") {}
  void sample(const Sample<D>& s) override {
    const auto& state = s.state;
    const double n = static_cast<double>(state.size());
    double inv_theta = 0, mean_theta = 0;
    for (const double ui : state.u) inv_theta += p_.cv / ui, mean_theta += ui / p_.cv;
    const double t_int = state.u.empty() ? p_.temperature : n / inv_theta;
    mean_theta = state.u.empty() ? p_.temperature : mean_theta / n;
    std::array<double, 3> mom{0, 0, 0};
    for (int d = 0; d < D; ++d)
      for (const double v : state.v[d]) mom[d] += p_.mass * v;
    char row[512];
    std::snprintf(row, sizeof row,
                  "%ld,%.6f,%d,%.17g,%.17g,%.17g,%.17g,%.10g,%.10g,%.10g,%.10g,%.3e,%.3e,%.3e\n",
                  s.step, s.time, s.sampled ? 1 : 0, s.energy, s.kinetic, s.internal,
                  s.potential_energy, s.t_kinetic, t_int, mean_theta, s.pressure, mom[0], mom[1],
                  mom[2]);
    csv_ += row;
    if (!s.sampled) return;
    t_kinetic_.push_back(s.t_kinetic), t_internal_.push_back(t_int), t_mean_.push_back(mean_theta);
    pressure_.push_back(s.pressure);
  }
  void finish(RunOutput& out) override {
    io::Json& j = out.summary;
    auto put = [&](const std::string& key, const std::vector<double>& series) {
      const statistics::Estimate e = statistics::block_average(series, p_.blocks);
      j[key] = e.mean;
      j[key + "_stderr"] = e.stderr_;
    };
    put("T_kinetic", t_kinetic_);
    put("T_internal", t_internal_);
    put("T_internal_mean_theta", t_mean_);
    put("pressure", pressure_);
    if (m_.has_energy && !m_.conservative && !p_.has_walls()) // 000:(3.21)
      j["T_energy_equation_of_state"] =
          ideal_dpde_temperature(p_, m_.initial_energy / m_.particles);
    out.thermo_csv = csv_;
  }
  template <class A> void archive(A& a) {
    a("rows", csv_);
    a("T_kinetic", t_kinetic_), a("T_internal", t_internal_), a("T_internal_mean", t_mean_);
    a("pressure", pressure_);
  }

private:
  ParticleParameters p_;
  RunFacts m_;
  std::string csv_;
  std::vector<double> t_kinetic_, t_internal_, t_mean_, pressure_; // sampled steps
};

} // namespace

template <int D> DiagnosticPtr<D> make_thermo(const ParticleParameters& p, const RunFacts& m) {
  return std::make_unique<Thermo<D>>(p, m);
}

template DiagnosticPtr<2> make_thermo<2>(const ParticleParameters&, const RunFacts&);
template DiagnosticPtr<3> make_thermo<3>(const ParticleParameters&, const RunFacts&);

} // namespace twinflow::particle
