#pragma once
// Binned fields on the scene's bins (fields.csv, blocks.csv, and cumulative snapshots for
// fields.h5), and the fit a reverse Poiseuille scene takes from them.

#include "io/field_file.hpp"
#include "particle/diagnostics/diagnostic.hpp"
#include "particle/fields.hpp"

namespace twinflow::particle {

template <int D> class Fields : public Archived<D, Fields<D>> {
public:
  Fields(const ParticleParameters& p, const RunFacts& m);
  std::string name() const override { return "fields"; }
  PairNeeds pair_needs() const override { return {false, true}; }
  void sample(const Sample<D>& s) override;
  void finish(RunOutput& out) override;
  // The final fields, reduced over the blocks once (by finish) for the fits that use them.
  const BinnedFields& result() const { return result_; }
  template <class A> void archive(A& a) {
    auto f = a.nested("sampler");
    sampler_.archive(f);
    a("taken", taken_);
    auto s = a.nested("snapshots");
    archive_snapshots(s);
  }

private:
  // Cumulative averages at a sequence of times, saved with the run (they cannot be recomputed).
  template <class A> void archive_snapshots(A& a);
  ParticleParameters p_;
  std::size_t n_;
  FieldSampler<D> sampler_;
  long taken_ = 0;
  std::vector<io::Snapshot> snapshots_;
  BinnedFields result_;
};

// Reverse Poiseuille flow: in each half the steady v_x(y) is a parabola with v'' = -n F / eta
// (n F the force density). A weighted quadratic fit per half over the bins away from the two
// planes where the force flips (the central 80% of each half); eta combined over both halves.
template <int D> class PoiseuilleFit : public Diagnostic<D> {
public:
  PoiseuilleFit(const ParticleParameters& p, const Fields<D>& fields) : p_(p), fields_(fields) {}
  std::string name() const override { return "poiseuille_fit"; }
  void finish(RunOutput& out) override;

private:
  ParticleParameters p_;
  const Fields<D>& fields_;
};

template <int D> template <class A> void Fields<D>::archive_snapshots(A& a) {
  long count = static_cast<long>(snapshots_.size());
  a("count", count);
  if constexpr (A::loading) snapshots_.assign(static_cast<std::size_t>(count), io::Snapshot{});
  for (long k = 0; k < count; ++k) {
    auto s = a.nested(std::to_string(k));
    io::Snapshot& snap = snapshots_[k];
    long steps = snap.particle_steps, fields = static_cast<long>(snap.fields.size());
    s("time", snap.time), s("wall_seconds", snap.wall_seconds), s("particle_steps", steps);
    s("fields", fields);
    if constexpr (A::loading) snap.particle_steps = steps, snap.fields.resize(fields);
    for (long i = 0; i < fields; ++i) {
      io::Field& f = snap.fields[i];
      long components = f.components;
      auto fs = s.nested("field" + std::to_string(i));
      fs("name", f.name), fs("components", components);
      fs("values", f.values), fs("standard_error", f.standard_error);
      f.components = static_cast<int>(components);
    }
  }
}

} // namespace twinflow::particle
