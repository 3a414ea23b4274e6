#pragma once
// Relaxation scenes (seed 004's method): the Fourier amplitudes of an initial sine perturbation
// along x, sampled from the start, and the diffusivities of their exponential decay: the heat
// mode (chi, kappa) and the transverse momentum mode (nu, eta). relaxation.csv holds both.

#include "particle/diagnostics/diagnostic.hpp"

namespace twinflow::particle {

template <int D> class RelaxationModes : public Archived<D, RelaxationModes<D>> {
public:
  RelaxationModes(const ParticleParameters& p, const RunFacts& m, bool heat, bool shear);
  std::string name() const override { return "relaxation_modes"; }
  void sample(const Sample<D>& s) override;
  void finish(RunOutput& out) override;
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

} // namespace twinflow::particle
