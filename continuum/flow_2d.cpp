// dim = 2 instantiations of the serial flow solver, both models in one unit (they share the
// driver's code: ~1.8 GB and ~50 s to compile, half of two units; one dimension per unit).
#include "continuum/backend_serial.templates.hpp"
#include "continuum/boussinesq.hpp"
#include "continuum/flow_problem.templates.hpp"
#include "continuum/low_mach.hpp"

namespace twinflow::continuum {
template class FlowProblem<2, BoussinesqModel<2>, SerialBackend<2>>;
template class FlowProblem<2, LowMachModel<2>, SerialBackend<2>>;
} // namespace twinflow::continuum
