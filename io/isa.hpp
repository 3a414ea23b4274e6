#pragma once
// The instruction-set level the particle kernels run on (particle/families.cpp, one compiled set
// per level): the best level this build carries and the host's CPU supports, or a lower one asked
// for with TWINFLOW_ISA (baseline, avx2, avx512). A build with TWINFLOW_NATIVE carries one set,
// compiled for the build host (-march=native).

#include <string>
#include <vector>

namespace twinflow::io {

enum class Isa { native, baseline, avx2, avx512 };

// Chosen once per process; an InputError for a TWINFLOW_ISA this build or host cannot run.
Isa kernel_isa();
// "x86-64-v4 (AVX-512)", ...; what --version and every summary.json's provenance name.
std::string isa_name(Isa isa);
// "avx512", ...: TWINFLOW_ISA's value for it.
std::string isa_key(Isa isa);
// The levels this build carries and this host runs, lowest first.
std::vector<Isa> runnable_isas();

} // namespace twinflow::io
