#include "io/isa.hpp"

#include <cstdlib>

#include "io/files.hpp"

namespace twinflow::io {

namespace {
// Each level's TWINFLOW_ISA value and its name, in the enum's order.
struct Level {
  const char* key;
  const char* name;
};
constexpr Level kLevels[] = {{"native", "native (-march=native)"},
                             {"baseline", "x86-64 (baseline)"},
                             {"avx2", "x86-64-v3 (AVX2)"},
                             {"avx512", "x86-64-v4 (AVX-512)"}};

bool host_runs(Isa isa) {
  __builtin_cpu_init();
  switch (isa) {
  case Isa::avx512:
    return __builtin_cpu_supports("x86-64-v4");
  case Isa::avx2:
    return __builtin_cpu_supports("x86-64-v3");
  default:
    return true;
  }
}

Isa choose() {
  const std::vector<Isa> levels = runnable_isas();
  const char* asked = std::getenv("TWINFLOW_ISA");
  if (!asked || !*asked) return levels.back();
  std::string offered;
  for (const Isa isa : levels) {
    if (asked == isa_key(isa)) return isa;
    offered += (offered.empty() ? "" : ", ") + isa_key(isa);
  }
  throw InputError(std::string("TWINFLOW_ISA=") + asked +
                   ": this build on this host runs only: " + offered);
}
} // namespace

std::vector<Isa> runnable_isas() {
#ifdef TWINFLOW_NATIVE
  return {Isa::native};
#else
  std::vector<Isa> levels{Isa::baseline};
  for (const Isa isa : {Isa::avx2, Isa::avx512})
    if (host_runs(isa)) levels.push_back(isa);
  return levels;
#endif
}

Isa kernel_isa() {
  static const Isa chosen = choose();
  return chosen;
}

std::string isa_key(Isa isa) {
  return kLevels[static_cast<int>(isa)].key;
}

std::string isa_name(Isa isa) {
  return kLevels[static_cast<int>(isa)].name;
}

} // namespace twinflow::io
