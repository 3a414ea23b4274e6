#include "app/case/case.hpp"
#include "app/commands.hpp"

namespace twinflow::app {

int continuum_stage(const CommandLine& cl) {
  Case c;
  c.load(cl.target, cl.overrides);
  throw NotImplemented("'continuum' is not implemented yet");
}

} // namespace twinflow::app
