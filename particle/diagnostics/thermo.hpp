#pragma once
// The thermodynamic state over time: thermo.csv (every sample) and the block-averaged
// temperatures and pressure of the summary (sampled steps).

#include "particle/diagnostics/diagnostic.hpp"

namespace twinflow::particle {

template <int D> class Thermo : public Archived<D, Thermo<D>> {
public:
  Thermo(const ParticleParameters& p, const RunFacts& m);
  std::string name() const override { return "thermo"; }
  void sample(const Sample<D>& s) override;
  void finish(RunOutput& out) override;
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

} // namespace twinflow::particle
