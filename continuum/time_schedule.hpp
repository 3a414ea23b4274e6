#pragma once
// The schedule of a flow run in time (every model and backend of FlowProblem): fixed step
// dt = end / round(end / time_step), BDF2 with a BDF1 first step (or BDF1 throughout, for a
// first-order model), which steps record a time-series row and which write a field snapshot.
// Plain C++, no deal.II.

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

#include "continuum/parameters.hpp"

namespace twinflow::continuum::detail {

class TimeSchedule {
public:
  // order: 2 for BDF2 (first step BDF1), 1 for implicit Euler throughout.
  TimeSchedule(const ContinuumParameters& prm, int order)
      : steps_(std::max(1, static_cast<int>(std::lround(prm.end_time / prm.time_step)))),
        dt_(prm.end_time / steps_), series_every_(prm.series_every), order_(order) {
    // Snapshots: every `snapshot_every` steps (and the initial state), at the steps nearest the
    // listed times, at the end.
    snapshot_steps_.insert(steps_);
    for (const double t : prm.snapshot_times)
      snapshot_steps_.insert(static_cast<int>(std::lround(t / dt_)));
    if (prm.snapshot_every > 0)
      for (int k = 0; k < steps_; k += prm.snapshot_every) snapshot_steps_.insert(k);
  }

  int steps() const { return steps_; }
  double dt() const { return dt_; }
  double time(int step) const { return step * dt_; }
  bool is_snapshot(int step) const { return snapshot_steps_.count(step) > 0; }
  bool is_sample(int step) const { return step % series_every_ == 0 || step == steps_; }
  // About ten progress lines per run.
  bool is_report(int step) const { return step == steps_ || step % std::max(1, steps_ / 10) == 0; }

  // Step n -> n+1 (n + 1 = `step` >= 1): dx/dt ~ c[0] x^{n+1} + c[1] x^n + c[2] x^{n-1}.
  //   BDF1 (first step, or every step of order 1): (x^{n+1} - x^n) / dt
  //   BDF2: (3 x^{n+1} - 4 x^n + x^{n-1}) / (2 dt) (Hairer, Norsett & Wanner I, sec. III.1)
  std::array<double, 3> coefficients(int step) const {
    if (step == 1 || order_ == 1) return {{1.0 / dt_, -1.0 / dt_, 0.0}};
    return {{1.5 / dt_, -2.0 / dt_, 0.5 / dt_}};
  }

private:
  int steps_;
  double dt_;
  int series_every_;
  int order_;
  std::set<int> snapshot_steps_;
};

} // namespace twinflow::continuum::detail
