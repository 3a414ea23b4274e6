// The particle models of 2D with constant conservative force (run_models.tpp).
#include "particle/run_models.tpp"

namespace twinflow::particle {
TWINFLOW_FAMILY_SIMULATIONS(2, ConstantRepulsion)
namespace detail {
TWINFLOW_PARTICLE_FAMILY(2, ConstantRepulsion)
} // namespace detail
} // namespace twinflow::particle
