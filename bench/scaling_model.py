#!/usr/bin/env python3
"""The particle solver's scaling model on MPI, from bench/scaling.sh's measurements (raw.txt).

Time per step of one rank holding n = N/R particles of the bench scene (3D, box 2L x L x L,
rho = 3, split into slabs of cell planes along z; planes = floor(L / (rc + skin)) = floor(L/1.2)):

  T(R) = n t1 (1 + w + i(R)) + m (alpha + b g / beta) + c alpha_c log2(R) + v R / beta

  t1       compute per particle-step on one core (1 rank x 1 thread);
  g        ghost particles per rank: one plane, N / planes;
  m, b     halo messages per step and bytes per ghost particle per step (measured with the PMPI
           counter on 2 ranks);
  alpha, beta  MPI_Sendrecv latency and bandwidth between two ranks (mpi_exchange);
  c        collectives per step (the list check's MPI_Allreduce, MPI_Allgather), alpha_c their
           2-rank latency, assumed to grow as log2(R) (a tree);
  v        bytes per rank per step of the far movers every rank sends to every rank (the list
           check's MPI_Allgatherv): each rank receives R v;
  w        the rest of the measured 2-rank time, as a fraction of the compute (the ranks wait for
           each other at every exchange: scheduling jitter and the unequal slabs);
  i(R)     the unequal slabs' growth with R: the largest of R slab populations exceeds the mean by
           sqrt(2 ln R / n) (Poisson counts), against its value at R = 2.
The model is checked against the measured 2-rank runs at each size, then projected.
"""
import math
import statistics as st
import sys
from collections import defaultdict

from host import host_block

raw = sys.argv[1] if len(sys.argv) > 1 else "bench/runs/scaling/raw.txt"
exchange, counts, speed = {}, defaultdict(dict), defaultdict(list)
for line in open(raw):
    w = line.split()
    if not w:
        continue
    if w[0] == "exchange":
        exchange[(w[1], int(w[2]))] = float(w[3])
    elif w[0] == "counts":
        n, integ, rank = w[1].split(":")
        counts[(int(n), integ)].setdefault(w[2], []).append([float(x) for x in w[3:6]])
    elif w[0] == "speed" and len(w) > 2 and w[2]:
        n, integ, layout = w[1].split(":")
        speed[(int(n), integ, layout)].append(float(w[2]))

# alpha: the smallest message; beta: least squares of t = alpha + bytes / beta over >= 128 kB
alpha = exchange[("sendrecv", 8)]
big = [(b, t) for (k, b), t in exchange.items() if k == "sendrecv" and b >= 131072]
beta = sum(b * b for b, _ in big) / sum(b * (t - alpha) for b, t in big)
alpha_c = exchange[("allreduce", 8)]


def per_rank(c, kind, column):  # the larger rank's value per step (column 0 calls, 1 bytes, 2 s)
    return max(r[column] for r in c.get(kind, [[0, 0, 0]]))


def planes_of(n):
    return math.floor((n / 6) ** (1 / 3) / 1.2)


print("# Scaling model of the particle solver on MPI (bench/scaling.sh)\n")
print("Host:\n\n" + host_block(raw))
print(f"MPI_Sendrecv between 2 ranks: alpha = {alpha * 1e6:.2f} us, beta = {beta / 1e9:.1f} GB/s; "
      f"MPI_Allreduce of one double: {alpha_c * 1e6:.2f} us\n")
print("| N | integrator | 1x1 | 1x2 | 2x1 | 2x1 / 1x2 | 2x1 / (2 x 1x1) | ghosts per rank | "
      "halo messages / step | halo bytes / ghost / step | collectives / step | "
      "time in MPI / step (measured) | latency + bandwidth part (model) | w |")
print("|" + "---|" * 14)
model = {}
for (n, integ), c in sorted(counts.items()):
    s = {k: st.median(speed[(n, integ, k)]) for k in ("1x1", "1x2", "2x1") if speed[(n, integ, k)]}
    if len(s) < 3:
        continue
    ranks_n = n / 2
    t1 = 1 / s["1x1"]
    ghosts = n / planes_of(n)
    m = per_rank(c, "sendrecv", 0)
    b = per_rank(c, "sendrecv", 1) / ghosts
    coll = per_rank(c, "allreduce", 0) + per_rank(c, "allgather", 0)
    v = per_rank(c, "allgatherv", 1)
    mpi_seconds = sum(per_rank(c, k, 2) for k in c)
    wire = m * (alpha + b * ghosts / m / beta) + coll * alpha_c + 2 * v / beta
    t2 = ranks_n / (s["2x1"] / 2)  # measured time per step on 2 ranks
    w = (t2 - ranks_n * t1 - wire) / (ranks_n * t1)
    model[(n, integ)] = dict(t1=t1, b=b, m=m, coll=coll, v=v / ranks_n, w=w)
    print(f"| {n} | {integ} | {s['1x1']:.3g} | {s['1x2']:.3g} | {s['2x1']:.3g} | "
          f"{s['2x1'] / s['1x2']:.2f} | {s['2x1'] / (2 * s['1x1']):.2f} | {ghosts:.0f} | {m:.1f} | "
          f"{b:.0f} | {coll:.1f} | {mpi_seconds * 1e3:.3f} ms | {wire * 1e3:.3f} ms | {w:.3f} |")


# The check: w fitted at one size predicts the 2-rank speed at the other.
for (n, integ), p in sorted(model.items()):
    for (n2, integ2), p2 in sorted(model.items()):
        if integ2 != integ or n2 == n:
            continue
        ranks_n = n2 / 2
        ghosts = n2 / planes_of(n2)
        t = (ranks_n * p2["t1"] * (1 + p["w"]) + p2["m"] * alpha + p2["b"] * ghosts / beta
             + p2["coll"] * alpha_c + p2["v"] * n2 / beta)
        measured = st.median(speed[(n2, integ, "2x1")])
        print(f"\nCheck, {integ}: w = {p['w']:.3f} from N = {n} predicts 2 ranks x 1 thread at "
              f"N = {n2}: {2 * ranks_n / t:.3g} particle-steps/s, measured {measured:.3g} "
              f"({100 * (2 * ranks_n / t / measured - 1):+.0f}%)")


def efficiency(p, N, R):
    n = N / R
    planes = planes_of(N)
    if planes < 2 * R:
        return None
    ghosts = N / planes
    imbalance = math.sqrt(2 * math.log(R) / n) - math.sqrt(2 * math.log(2) / n)
    t = (n * p["t1"] * (1 + p["w"] + imbalance) + p["m"] * alpha + p["b"] * ghosts / beta
         + p["coll"] * alpha_c * math.log2(R) + p["v"] * n * R / beta)
    return n * p["t1"] / t


print("\nProjected parallel efficiency (time of the same n = N/R particles on one core against "
      "one rank's step on R ranks; '-' where the slabs would be thinner than 2 cell planes, "
      "the one-axis split's limit R <= planes / 2):\n")
sizes = [10**6, 10**7, 10**8, 10**9]
for (n, integ), p in sorted(model.items()):
    print(f"From N = {n}, {integ} (w = {p['w']:.3f}):\n")
    print("| N | planes | R = 8 | R = 64 | R = 512 | largest R |")
    print("|---|---|---|---|---|---|")
    for N in sizes:
        cells = [efficiency(p, N, R) for R in (8, 64, 512)]
        text = ["-" if e is None else f"{100 * e:.0f}%" for e in cells]
        print(f"| {N:.0e} | {planes_of(N)} | " + " | ".join(text) + f" | {planes_of(N) // 2} |")
    print()
