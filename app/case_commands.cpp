#include <iostream>

#include "app/case/case.hpp"
#include "app/commands.hpp"

namespace twinflow::app {

int check_case(const CommandLine& cl) {
  Case c;
  const CaseParameters p = c.load(cl.target, cl.overrides);
  std::cout << "# " << cl.target << ": valid (case '" << p.name << "', " << p.scene.dim << "D, "
            << p.particle.particle_count() << " particles)\n";
  c.registry().print_resolved(std::cout);
  return 0;
}

int print_parameters(const CommandLine&) {
  Case c;
  std::cout << "# twinflow case-file parameters: every key with its default, allowed values and "
               "documentation.\n# Set them in a .prm file (subsection/set/end; 'include FILE' "
               "reads another file) or with --set 'Section/Key=value'.\n";
  c.registry().print_documented(std::cout);
  return 0;
}

} // namespace twinflow::app
