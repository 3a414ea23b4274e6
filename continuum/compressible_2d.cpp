// dim = 2 instantiation of the serial flow solver with the compressible model (its own unit:
// compile memory, as flow_2d.cpp).
#include "continuum/backend_serial.templates.hpp"
#include "continuum/compressible.hpp"
#include "continuum/flow_problem.templates.hpp"

namespace twinflow::continuum {
template class FlowProblem<2, CompressibleModel<2>, SerialBackend<2>>;
} // namespace twinflow::continuum
