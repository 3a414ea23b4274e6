// dim = 2 instantiation (one translation unit per dimension: compile memory, build-notes).
#include "continuum/backend_serial.templates.hpp"
#include "continuum/flow_problem.templates.hpp"
#include "continuum/low_mach.hpp"

template class twinflow::continuum::FlowProblem<2, twinflow::continuum::LowMachModel<2>,
                                                twinflow::continuum::SerialBackend<2>>;
