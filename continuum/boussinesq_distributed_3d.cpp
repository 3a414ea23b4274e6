// dim = 3 instantiation of the distributed, iterative Boussinesq solver (own unit: compile memory).
#include "continuum/boussinesq_distributed.templates.hpp"

template class twinflow::continuum::DistributedBoussinesqProblem<3>;
