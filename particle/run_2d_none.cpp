// The particle models of 2D with no conservative force (run_models.tpp).
#include "particle/run_models.tpp"

namespace twinflow::particle {
TWINFLOW_FAMILY_SIMULATIONS(2, NoConservative)
namespace detail {
TWINFLOW_PARTICLE_FAMILY(2, NoConservative)
} // namespace detail
} // namespace twinflow::particle
