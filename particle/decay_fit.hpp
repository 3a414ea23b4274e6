#pragma once
#include <vector>

#include "io/json.hpp"

namespace twinflow::particle {

// Seed 004's relaxation method: a mode of wavenumber k decays as exp(-D k^2 t) (D = chi for the
// heat mode, nu for the transverse momentum mode), on top of the mode's own thermal noise, of a
// constant size sigma and relaxing at the same rate (Onsager's regression). The fit:
//  1. a line through ln a from the first sample below 80% of a(0) (after the fastest transients)
//     to the first below 30% (well above the noise);
//  2. sigma: the rms of a - fit after that window (the tail), later after the start;
//  3. three passes of a weighted line through ln a + sigma^2 / (2 fit^2) (the second-order bias of
//     a noisy log), weights fit^2 / sigma^2 (var ln a = sigma^2 / a^2), over the samples where the
//     fit stands 3 sigma above the noise. The window's end comes from the fit, not from a noisy
//     sample's first crossing of a level (which cut the old 80%-10% window early or late and made
//     its rates 1.4-1.6x as scattered: 11 seeds, and a simulation).
// The slope's error is the weighted residuals' standard error widened by sqrt((1 + r)/(1 - r)),
// r = exp(-rate dt_sample), the noise's correlation between samples; a simulation of the decay
// with that noise gives a spread within 10% of this error.
// t: sample times (evenly spaced), a: the mode's amplitude; diffusivity names D in the result
// ("chi" or "nu"), with D_stderr, decay_rate(_stderr), points, the fit window and the noise.
io::Json decay_fit(double wavenumber, const std::vector<double>& t, const std::vector<double>& a,
                   const char* diffusivity);

} // namespace twinflow::particle
