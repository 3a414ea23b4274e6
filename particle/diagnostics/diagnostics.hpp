#pragma once
// The list of diagnostics a scene needs: the one place that decides which exist.

#include "particle/diagnostics/diagnostic.hpp"

namespace twinflow::particle {

// In the order their results are written (a fit after the fields it reads).
template <int D> DiagnosticList<D> make_diagnostics(const ParticleParameters& p, const RunFacts& m);

} // namespace twinflow::particle
