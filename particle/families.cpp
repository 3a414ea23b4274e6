// The six families as one table. particle/CMakeLists.txt compiles this unit with the families'
// units once per instruction-set level and names each level's table (TWINFLOW_FAMILIES); run.cpp
// picks the table of io::kernel_isa().
#include "particle/run_models.hpp"

namespace twinflow::particle::detail {

namespace {
template <class C> C conservative_of(const ParticleParameters& p);
template <> NoConservative conservative_of(const ParticleParameters&) {
  return {};
}
template <> ConstantRepulsion conservative_of(const ParticleParameters& p) {
  return {p.a0, p.conservative_cutoff, 1 / p.conservative_cutoff};
}
template <> TemperatureRepulsion conservative_of(const ParticleParameters& p) {
  const double rc = p.conservative_cutoff;
  return {p.a0, rc, 1 / rc, 0.5 / p.reference_temperature};
}

template <int D, class C> RunOutput run(const ParticleParameters& p, const RunControl& control) {
  return run_family<D>(p, conservative_of<C>(p), control);
}
template <int D, class C> BenchResult bench(const ParticleParameters& p, long steps) {
  return bench_family<D>(p, conservative_of<C>(p), steps);
}
template <int D> constexpr FamilyEntry none{&run<D, NoConservative>, &bench<D, NoConservative>};
template <int D>
constexpr FamilyEntry constant{&run<D, ConstantRepulsion>, &bench<D, ConstantRepulsion>};
template <int D>
constexpr FamilyEntry temperature{&run<D, TemperatureRepulsion>, &bench<D, TemperatureRepulsion>};
} // namespace

extern "C" const Families TWINFLOW_FAMILIES{
    {{none<2>, constant<2>, temperature<2>}, {none<3>, constant<3>, temperature<3>}}};

} // namespace twinflow::particle::detail
