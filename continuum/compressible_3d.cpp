// dim = 3 instantiation of the serial flow solver with the compressible model (its own unit:
// compile memory, as flow_3d.cpp).
#include "continuum/backend_serial.templates.hpp"
#include "continuum/compressible.hpp"
#include "continuum/flow_problem.templates.hpp"

namespace twinflow::continuum {
template class FlowProblem<3, CompressibleModel<3>, SerialBackend<3>>;
} // namespace twinflow::continuum
