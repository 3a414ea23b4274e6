// dim = 3 instantiation (one translation unit per dimension: ~1.5 GB to compile, build-notes).
#include "continuum/backend_serial.templates.hpp"
#include "continuum/boussinesq.hpp"
#include "continuum/flow_problem.templates.hpp"

template class twinflow::continuum::FlowProblem<3, twinflow::continuum::BoussinesqModel<3>,
                                                twinflow::continuum::SerialBackend<3>>;
