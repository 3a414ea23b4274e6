// dim = 3 instantiation of the distributed flow solver, Boussinesq on p4est + Trilinos (own unit:
// ~2 GB to compile).
#include "continuum/backend_distributed.templates.hpp"
#include "continuum/boussinesq_distributed.hpp"
#include "continuum/flow_problem.templates.hpp"

namespace twinflow::continuum {
template class FlowProblem<3, BoussinesqModel<3>, DistributedBackend<3>>;
} // namespace twinflow::continuum
