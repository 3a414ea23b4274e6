#pragma once
// The distributed, iterative Boussinesq solver: the Boussinesq model (boussinesq.hpp) on the
// distributed backend (backend_distributed.hpp: p4est, Trilinos, FGMRES with a block-triangular
// AMG preconditioner), for 3D boxes that a direct solver cannot factorise. Runs on one process
// or under mpirun; steady or in time as the serial solver. Instantiated for dim = 3
// (flow_distributed_3d.cpp). Not computed on this path: stream function, probes, local
// wall Nu under mpirun.

#include "continuum/backend_distributed.hpp"
#include "continuum/boussinesq.hpp"

namespace twinflow::continuum {

template <int dim>
using DistributedBoussinesqProblem =
    FlowProblem<dim, BoussinesqModel<dim>, DistributedBackend<dim>>;
extern template class FlowProblem<3, BoussinesqModel<3>, DistributedBackend<3>>;

} // namespace twinflow::continuum
