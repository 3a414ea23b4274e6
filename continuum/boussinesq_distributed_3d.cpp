// dim = 3 instantiation of the distributed, iterative Boussinesq solver (own unit: compile memory).
#include "continuum/backend_distributed.templates.hpp"
#include "continuum/boussinesq_distributed.hpp"
#include "continuum/flow_problem.templates.hpp"

template class twinflow::continuum::FlowProblem<3, twinflow::continuum::BoussinesqModel<3>,
                                                twinflow::continuum::DistributedBackend<3>>;
