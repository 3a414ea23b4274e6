#pragma once
// The families of compiled particle models (run_models.tpp): one per dimension and conservative
// force, each instantiated in its own unit (run_2d_none.cpp, ...); the six as one table
// (families.cpp), compiled once per instruction-set level (io/isa.hpp).

#include "particle/pair_terms.hpp"
#include "particle/run.hpp"

namespace twinflow::particle::detail {

template <int D, class C>
RunOutput run_family(const ParticleParameters& p, const C& conservative, const RunControl& control);
template <int D, class C>
BenchResult bench_family(const ParticleParameters& p, const C& conservative, long steps);

// The families (each instantiated once, in its unit).
#define TWINFLOW_PARTICLE_FAMILY(D, C)                                                             \
  template RunOutput run_family<D, C>(const ParticleParameters&, const C&, const RunControl&);     \
  template BenchResult bench_family<D, C>(const ParticleParameters&, const C&, long);
// The library's own level also compiles every member of its models' simulations for the other
// units that use them (simulation.hpp); the other levels' copies stay local to their object.
#ifdef TWINFLOW_SHARED_SIMULATIONS
#define TWINFLOW_FAMILY_SIMULATIONS(D, C) TWINFLOW_EACH_SIMULATION(, D, C)
#else
#define TWINFLOW_FAMILY_SIMULATIONS(D, C)
#endif
#define TWINFLOW_EXTERN_PARTICLE_FAMILY(D, C)                                                      \
  extern template RunOutput run_family<D, C>(const ParticleParameters&, const C&,                  \
                                             const RunControl&);                                   \
  extern template BenchResult bench_family<D, C>(const ParticleParameters&, const C&, long);
TWINFLOW_EXTERN_PARTICLE_FAMILY(2, NoConservative)
TWINFLOW_EXTERN_PARTICLE_FAMILY(2, ConstantRepulsion)
TWINFLOW_EXTERN_PARTICLE_FAMILY(2, TemperatureRepulsion)
TWINFLOW_EXTERN_PARTICLE_FAMILY(3, NoConservative)
TWINFLOW_EXTERN_PARTICLE_FAMILY(3, ConstantRepulsion)
TWINFLOW_EXTERN_PARTICLE_FAMILY(3, TemperatureRepulsion)
#undef TWINFLOW_EXTERN_PARTICLE_FAMILY

// One family's entry points, with the conservative force built from the parameters.
struct FamilyEntry {
  RunOutput (*run)(const ParticleParameters&, const RunControl&);
  BenchResult (*bench)(const ParticleParameters&, long);
};
// One compiled set: [dimension 2, 3][ConservativeForce None, Constant, TemperatureDependent].
struct Families {
  FamilyEntry family[2][3];
};

} // namespace twinflow::particle::detail
