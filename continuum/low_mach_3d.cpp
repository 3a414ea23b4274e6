// dim = 3 instantiation (one translation unit per dimension: compile memory, build-notes).
#include "continuum/backend_serial.templates.hpp"
#include "continuum/flow_problem.templates.hpp"
#include "continuum/low_mach.hpp"

template class twinflow::continuum::FlowProblem<3, twinflow::continuum::LowMachModel<3>,
                                                twinflow::continuum::SerialBackend<3>>;
