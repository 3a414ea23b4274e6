"""(a) periodic-box slope check: s(P) = lambda_tail/A from exact lattice sums."""
import numpy as np
from modes import periodic
Ks = {'2pi/1': 2*np.pi, '2pi/0.7': 2*np.pi/0.7}
Ps = [10, 20, 40, 80, 160]
print('s(P) = lambda_tail/A ;  slope per ln P between successive P ;  s - ln(P K/2pi)')
for kn, K in Ks.items():
    for reg in ['hard', 'gauss']:
        s = np.array([periodic(P, K, reg if reg=='gauss' else 'hard2') for P in Ps])
        sl = np.diff(s)/np.log(2)
        c = s - np.log(np.array(Ps)*K/(2*np.pi))
        print(f'K={kn:8s} {reg:6s} s=', np.round(s,4), ' slopes=', np.round(sl,4), ' const=', np.round(c,4))
c_p, T, chi, nu = 13.0, 0.887, 0.384, 0.333
A = c_p*T/(4*np.pi*(chi+nu))
print('A = c_p kT/(4 pi (chi+nu)) =', A)
