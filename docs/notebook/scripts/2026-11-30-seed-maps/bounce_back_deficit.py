# The carriers' conduction deficit beside an adiabatic bounce-back wall (no-slip, v -> -v), for
# Ornstein-Uhlenbeck velocities (relaxation tau_v = D / T, m = 1): a flip reverses v_x, so
# <v_x(0) v_x(t)> at height h is T exp(-t/tau_v) erf(h / sqrt(2 s^2(t))), s^2 the free path's
# variance 2 D (t - tau_v (1 - exp(-t/tau_v))). The deficit length, int_0^inf (1 - D_x(h) / D) dh,
# is 2 tau_v sqrt(T / pi) I with I = int_0^inf exp(-s) sqrt(s - 1 + exp(-s)) ds.
import numpy as np
from scipy.integrate import quad
I = quad(lambda s: np.exp(-s) * np.sqrt(s - 1 + np.exp(-s)), 0, np.inf)[0]
print(f"I = {I:.4f}")
for T, D in [(0.887, 0.325), (1.5, 0.786), (0.5, 0.110)]:  # measured D (transport stage)
    tau = D / T
    print(f"T {T}: tau_v {tau:.3f}, deficit {2 * tau * np.sqrt(T / np.pi) * I:.3f} rc per wall")
