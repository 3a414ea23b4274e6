#include "app/case/case.hpp"
#include "app/commands.hpp"

namespace twinflow::app {

int particle_stage(const CommandLine& cl) {
  Case c;
  c.load(cl.target, cl.overrides);
  throw NotImplemented("'particle' is not implemented yet");
}

int bench(const CommandLine&) {
  throw NotImplemented("'bench' is not implemented yet");
}

int run_all(const CommandLine& cl) {
  Case c;
  c.load(cl.target, cl.overrides);
  throw NotImplemented("'run' is not implemented yet");
}

} // namespace twinflow::app
