#include "particle/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <unistd.h>

#include "particle/run_models.hpp"

namespace twinflow::particle {

namespace {
// ---- resolving the case into a compiled combination (the only place that branches on physics:
// here the dimension and the conservative force, in run_models.tpp the friction and heat laws)
template <int D, class V> auto with_conservative(const ParticleParameters& p, V&& visit) {
  const double rc = p.conservative_cutoff;
  switch (p.conservative) {
  case ConservativeForce::Constant:
    return visit.template operator()<D>(ConstantRepulsion{p.a0, rc, 1 / rc});
  case ConservativeForce::TemperatureDependent:
    return visit.template operator()<D>(
        TemperatureRepulsion{p.a0, rc, 1 / rc, 0.5 / p.reference_temperature});
  default:
    return visit.template operator()<D>(NoConservative{});
  }
}

// Calls visit.operator()<D>(conservative) with the family the parameters describe.
template <class V> auto dispatch(const ParticleParameters& p, V&& visit) {
  return p.dim == 2 ? with_conservative<2>(p, visit) : with_conservative<3>(p, visit);
}

struct Run {
  const ParticleParameters& p;
  const RunControl& control;
  template <int D, class C> RunOutput operator()(const C& c) const {
    return detail::run_family<D>(p, c, control);
  }
};
struct Bench {
  const ParticleParameters& p;
  long steps;
  template <int D, class C> BenchResult operator()(const C& c) const {
    return detail::bench_family<D>(p, c, steps);
  }
};
} // namespace

RunControl::Progress RunControl::progress_for_stderr() {
  return isatty(STDERR_FILENO) ? Progress::terminal : Progress::log;
}

RunOutput run_particles(const ParticleParameters& p, const RunControl& control) {
  return dispatch(p, Run{p, control});
}

BenchResult bench_particles(const ParticleParameters& p, long steps) {
  return dispatch(p, Bench{p, steps});
}

} // namespace twinflow::particle
