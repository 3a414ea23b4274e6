#include "particle/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <unistd.h>

#include "io/isa.hpp"
#include "particle/run_models.hpp"

namespace twinflow::particle {

namespace detail {
// The compiled sets (families.cpp): the library's own (its flags: baseline, or -march=native), and
// with dispatch one per x86-64 level above the baseline.
extern "C" const Families twinflow_families_default;
#ifndef TWINFLOW_NATIVE
extern "C" const Families twinflow_families_avx2;
extern "C" const Families twinflow_families_avx512;
#endif
} // namespace detail

namespace {
// ---- resolving the case into a compiled combination (the only place that branches on physics:
// here the dimension and the conservative force, in run_models.tpp the friction and heat laws)
const detail::FamilyEntry& family(const ParticleParameters& p) {
  const detail::Families* set = &detail::twinflow_families_default;
#ifndef TWINFLOW_NATIVE
  if (io::kernel_isa() == io::Isa::avx512) set = &detail::twinflow_families_avx512;
  if (io::kernel_isa() == io::Isa::avx2) set = &detail::twinflow_families_avx2;
#endif
  const int force = p.conservative == ConservativeForce::Constant               ? 1
                    : p.conservative == ConservativeForce::TemperatureDependent ? 2
                                                                                : 0;
  return set->family[p.dim == 2 ? 0 : 1][force];
}
} // namespace

RunControl::Progress RunControl::progress_for_stderr() {
  return isatty(STDERR_FILENO) ? Progress::terminal : Progress::log;
}

RunOutput run_particles(const ParticleParameters& p, const RunControl& control) {
  return family(p).run(p, control);
}

BenchResult bench_particles(const ParticleParameters& p, long steps) {
  return family(p).bench(p, steps);
}

} // namespace twinflow::particle
