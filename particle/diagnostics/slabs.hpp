#pragma once
// Heat-slab scenes (seed 002 section III.B): the profile along the slab direction in 0.5 rc bins
// (slab_profile.csv), and kappa from its slopes between the slabs with the energy flux split
// into its parts at two planes (SlabKappaFit).

#include "particle/diagnostics/diagnostic.hpp"
#include "particle/fields.hpp"

namespace twinflow::particle {

template <int D> class SlabProfile : public Archived<D, SlabProfile<D>> {
public:
  SlabProfile(const ParticleParameters& p, const RunFacts& m);
  std::string name() const override { return "slab_profile"; }
  PairNeeds pair_needs() const override { return {false, true}; }
  void sample(const Sample<D>& s) override;
  void finish(RunOutput& out) override;
  const BinnedFields& result() const { return result_; } // after finish
  template <class A> void archive(A& a) { sampler_.archive(a); }

private:
  FieldSampler<D> sampler_;
  BinnedFields result_;
};

// A hot and a cold slab: linear fits of T_internal in the central 60% of both halves between the
// slabs, kappa = J0 / |dT/dx| with J0 = power / (2 A), and the flux parts at x = 2 and 8.
template <int D> class SlabKappaFit : public Diagnostic<D> {
public:
  SlabKappaFit(const ParticleParameters& p, const SlabProfile<D>& profile)
      : p_(p), profile_(profile) {}
  std::string name() const override { return "slab_kappa_fit"; }
  void finish(RunOutput& out) override;

private:
  ParticleParameters p_;
  const SlabProfile<D>& profile_;
};

} // namespace twinflow::particle
