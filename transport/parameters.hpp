#pragma once
// What the transport stage measures, and how (case file section Transport).

#include <string>

namespace twinflow::transport {

struct TransportParameters {
  std::string source = "estimated";   // estimated | measured
  bool measure_flows = false;         // also kappa and eta by the relaxation of sine modes
  double temperature = 0;             // state point; 0: the walls' mean, else Scene/Temperature
  double flow_particles = 4000;       // particles of the square/cubic base box of the flow runs
  int flow_repeats = 4;               // independent relaxation runs (their spread is the error)
  int diffusion_repeats = 4;          // independent bulk runs for D (their spread is the error)
  double temperature_spread = 0;      // > 0: also at T (1 -+ spread), power laws kappa(T), eta(T)
  bool kappa_from_slabs = true;       // with measure_flows in a scene with a heated direction:
                                      // kappa and its law from periodic heat slabs at its scale
  bool viscosity_along_isobar = true; // with measure_flows in a scene with a heated direction:
                                      // eta also at the walls' (n, T), its law through them
  bool kappa_from_walls = false;      // kappa by conduction between the scene's thermal walls
  long wall_steps = 100000;           // its sampled steps (after as many / 5 to settle)
};

// The version of the measurement: part of its cache key and of its stage inputs in `run`, bumped
// when a measurement changes (results of an older method are not reused).
constexpr int kMeasurementMethod =
    12; // 3: relaxation fit window from the noise (decay_fit.hpp);
        // 4: the wall run's slope and flux errors from the blockings;
        // 5: D over independent repeats;
        // 6: D's error the repeats' spread alone, their
        //    seeds hashed (particle/seeds.hpp);
        // 7: the excess pressure's fit (the compressible
        //    twin's equation of state)
        // 8: the laws c(n, T) (laws.hpp), kappa from heat
        //    slabs at the scene's scale, D's power of T
        // 9: the slabs' sampled time from the error they need
        // 10: the slabs' profile read along their direction
        // 11: eta's law through the isobar's ends
        // 12: kappa's pair part measured in the slabs

} // namespace twinflow::transport
