// The particle models of 3D with no conservative force (run_models.tpp).
#include "particle/run_models.tpp"

namespace twinflow::particle {
TWINFLOW_FAMILY_SIMULATIONS(3, NoConservative)
namespace detail {
TWINFLOW_PARTICLE_FAMILY(3, NoConservative)
} // namespace detail
} // namespace twinflow::particle
