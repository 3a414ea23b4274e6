// The particle models of 3D with constant conservative force (run_models.tpp).
#include "particle/run_models.tpp"

namespace twinflow::particle {
TWINFLOW_FAMILY_SIMULATIONS(3, ConstantRepulsion)
namespace detail {
TWINFLOW_PARTICLE_FAMILY(3, ConstantRepulsion)
} // namespace detail
} // namespace twinflow::particle
