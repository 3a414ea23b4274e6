// Relaxation scenes (seed 004's method): the Fourier amplitudes of an initial sine perturbation
// along x, sampled from the start, and the diffusivities of their exponential decay: the heat
// mode (chi, kappa) and the transverse momentum mode (nu, eta). relaxation.csv holds both.
#include "particle/diagnostics/plugins.hpp"

#include <cmath>
#include <sstream>

#include "particle/decay_fit.hpp"

namespace twinflow::particle {

namespace {

io::Json heat_relaxation_fit(const ParticleParameters& p, const std::vector<double>& t,
                             const std::vector<double>& a) {
  io::Json j = decay_fit(2 * M_PI / p.box[0], t, a, "chi");
  if (!j.contains("chi")) return j;
  // kappa = rho c_p chi with the ideal DPDE fluid's c_p = c_v + k + (d/2) k + k per particle
  // (docs/theory.md); the transport stage converts chi itself, with the c_p of its estimate.
  const double scale = p.density * (p.cv + 2 + 0.5 * p.dim);
  j["kappa_ideal_cp"] = scale * j["chi"].get<double>();
  j["kappa_ideal_cp_stderr"] = scale * j["chi_stderr"].get<double>();
  return j;
}

io::Json shear_relaxation_fit(const ParticleParameters& p, const std::vector<double>& t,
                              const std::vector<double>& a) {
  io::Json j = decay_fit(2 * M_PI / p.box[0], t, a, "nu");
  if (!j.contains("nu")) return j;
  const double scale = p.density * p.mass; // eta = rho m nu
  j["viscosity"] = scale * j["nu"].get<double>();
  j["viscosity_stderr"] = scale * j["nu_stderr"].get<double>();
  return j;
}

template <int D> class RelaxationModes : public Archived<D, RelaxationModes<D>> {
public:
  RelaxationModes(const ParticleParameters& p, const RunFacts& m, bool heat, bool shear)
      : Archived<D, RelaxationModes<D>>("relaxation_modes"), p_(p), n_(m.particles), heat_(heat),
        shear_(shear) {
    for (int d = 0; d < D; ++d) volume_ *= p.box[d];
  }
  void sample(const Sample<D>& smp) override {
    const auto& s = smp.state;
    if (heat_) {
      // The heat mode: the Fourier amplitude of the heat density e - h n (h = (E + p V)/N, the
      // enthalpy per particle), which decouples from sound and decays as exp(-chi k^2 t) in
      // linear hydrodynamics; the temperature mode alone rides on sound waves.
      const double h = smp.energy / n_ + smp.pressure * volume_ / n_;
      double a = 0;
      for (std::size_t i = 0; i < n_; ++i) {
        double ei = s.u[i] + smp.potential[i];
        for (int d = 0; d < D; ++d) ei += 0.5 * p_.mass * s.v[d][i] * s.v[d][i];
        a += (ei - h) * std::sin(2 * M_PI * s.x[0][i] / p_.box[0]);
      }
      heat_time_.push_back(smp.time), heat_amplitude_.push_back(2 * a / n_);
    }
    if (shear_) {
      // The transverse momentum mode: decoupled from sound and heat, it decays as exp(-nu k^2 t).
      double b = 0;
      for (std::size_t i = 0; i < n_; ++i)
        b += p_.mass * s.v[1][i] * std::sin(2 * M_PI * s.x[0][i] / p_.box[0]);
      shear_time_.push_back(smp.time), shear_amplitude_.push_back(2 * b / n_);
    }
  }
  void finish(RunOutput& out) override {
    if (!heat_time_.empty())
      out.summary["relaxation"] = heat_relaxation_fit(p_, heat_time_, heat_amplitude_);
    if (!shear_time_.empty())
      out.summary["shear_relaxation"] = shear_relaxation_fit(p_, shear_time_, shear_amplitude_);
    if (heat_time_.empty() && shear_time_.empty()) return;
    // Both modes are sampled at the same steps; a column is empty when its mode is absent.
    std::ostringstream r;
    r << "# heat mode: (2/N) sum (e_i - h) sin(2 pi x_i / Lx), e_i = u_i + K_i + phi_i, h = (E + "
         "p V)/N; shear mode: (2/N) sum m v_y,i sin(2 pi x_i / Lx)\n"
         "time,amplitude,shear_amplitude\n";
    const std::vector<double>& time = heat_time_.empty() ? shear_time_ : heat_time_;
    for (std::size_t k = 0; k < time.size(); ++k) {
      r << time[k] << ",";
      if (k < heat_amplitude_.size()) r << heat_amplitude_[k];
      r << ",";
      if (k < shear_amplitude_.size()) r << shear_amplitude_[k];
      r << "\n";
    }
    out.relaxation_csv = r.str();
  }
  template <class A> void archive(A& a) {
    a("heat_time", heat_time_), a("heat_amplitude", heat_amplitude_);
    a("shear_time", shear_time_), a("shear_amplitude", shear_amplitude_);
  }

private:
  ParticleParameters p_;
  std::size_t n_;
  bool heat_, shear_;
  double volume_ = 1;
  std::vector<double> heat_time_, heat_amplitude_, shear_time_, shear_amplitude_;
};

} // namespace

template <int D>
DiagnosticPtr<D> make_relaxation_modes(const ParticleParameters& p, const RunFacts& m, bool heat,
                                       bool shear) {
  return std::make_unique<RelaxationModes<D>>(p, m, heat, shear);
}

template DiagnosticPtr<2> make_relaxation_modes<2>(const ParticleParameters&, const RunFacts&, bool,
                                                   bool);
template DiagnosticPtr<3> make_relaxation_modes<3>(const ParticleParameters&, const RunFacts&, bool,
                                                   bool);

} // namespace twinflow::particle
