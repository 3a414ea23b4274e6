// The pair passes of ec-verlet and shardlow (included from simulation.hpp): one row of cells'
// pairs at a time from the grid's pair list; the per-pair algebra (geometry, Philox noise, weights,
// forces) in loops over the block that vectorise, then the updates of the particles in pair order.

#include <omp.h>

#include <limits>
#include <tuple>

#include "particle/simd.hpp"

namespace twinflow::particle {

// Per-thread scratch of one block of pairs.
template <int D> struct PairScratch {
  std::vector<double> e[D], dv[D], r, wd, wr, wh, swh, xi, zeta, a, b, c, ui, uj;
  std::vector<std::uint32_t> i, j; // the block's pairs closer than the cutoff
  static PairScratch& get(std::size_t n) {
    static thread_local PairScratch s;
    if (s.r.size() < n) {
      const std::size_t size = n + n / 2 + 16;
      s.i.resize(size), s.j.resize(size);
      for (int d = 0; d < D; ++d) s.e[d].resize(size), s.dv[d].resize(size);
      for (auto* v :
           {&s.r, &s.wd, &s.wr, &s.wh, &s.swh, &s.xi, &s.zeta, &s.a, &s.b, &s.c, &s.ui, &s.uj})
        v->resize(size);
    }
    return s;
  }
};

// D column pointers held as scalars (an array of pointers indexed by d keeps a loop from
// vectorising; after unrolling over d the selects fold away).
template <class T> struct Columns {
  T *c0 = nullptr, *c1 = nullptr, *c2 = nullptr;
  template <class V> explicit Columns(V& arrays) {
    c0 = arrays[0].data();
    if constexpr (std::tuple_size<V>::value > 1) c1 = arrays[1].data();
    if constexpr (std::tuple_size<V>::value > 2) c2 = arrays[2].data();
  }
  explicit Columns(std::vector<double>* arrays, int dims) {
    c0 = arrays[0].data();
    if (dims > 1) c1 = arrays[1].data();
    if (dims > 2) c2 = arrays[2].data();
  }
  T* operator[](int d) const { return d == 0 ? c0 : d == 1 ? c1 : c2; }
};

// Unit vectors e_ij = (x_i - x_j)/r_ij (minimum image) and distances of a block. With a skin the
// list also holds pairs beyond the cutoff: those are dropped (order kept) and I, J then point to
// the scratch's copy of the rest. Returns the number of pairs left.
template <class M>
std::size_t Simulation<M>::pair_geometry(const std::uint32_t*& I, const std::uint32_t*& J,
                                         std::size_t n, PairScratch<D>& s) const {
  const std::size_t m = pairs_within_cutoff(I, J, n, s);
  const Columns<double> e(s.e, D);
  double* __restrict r = s.r.data();
  for (std::size_t k = 0; k < m; ++k) { // vectorises
    const double rk = std::sqrt(r[k]), inv_r = 1 / rk;
    for (int d = 0; d < D; ++d) e[d][k] *= inv_r;
    r[k] = rk;
  }
  I = s.i.data(), J = s.j.data();
  return m;
}

// What the cutoff pass reads (positions, periodic images, the cutoff) and where it writes the
// kept pairs (their separations, r^2, i and j). Passed by value: a store through its pointers
// then cannot alias it.
template <int D> struct CutoffPass {
  Columns<const double> x;
  double box[3], inv_box[3], rc2;
  Columns<double> e;
  double* r;
  std::uint32_t *i, *j;
};

// Pairs [k, n) one at a time, branch-free: the kept ones are written once at m, not copied
// afterwards. Returns the new m.
template <int D>
std::size_t cutoff_scalar(const CutoffPass<D> p, const std::uint32_t* I, const std::uint32_t* J,
                          std::size_t k, std::size_t n, std::size_t m) {
  for (; k < n; ++k) {
    const std::uint32_t i = I[k], j = J[k];
    double r2 = 0;
    for (int d = 0; d < D; ++d) {
      double c = p.x[d][i] - p.x[d][j];
      c -= p.box[d] * std::nearbyint(c * p.inv_box[d]); // as in the pair search: the same r2
      p.e[d][m] = c;
      r2 += c * c;
    }
    p.i[m] = i, p.j[m] = j, p.r[m] = r2;
    m += r2 < p.rc2;
  }
  return m;
}

// The vector part: eight pairs at a time (AVX-512: gathers, compress) or four (AVX2: scalar loads,
// a permutation for the compress; simd.hpp), bitwise as cutoff_scalar; the scratch has room for
// the full-width stores past m. Returns the pairs it took (the rest are cutoff_scalar's); m
// advanced. Without either, takes none.
template <int D>
std::size_t cutoff_wide(const CutoffPass<D> p, const std::uint32_t* I, const std::uint32_t* J,
                        std::size_t n, std::size_t& m) {
  std::size_t k = 0;
#ifdef TWINFLOW_AVX512
  const __m512d limit = _mm512_set1_pd(p.rc2);
  for (; k < n; k += 8) {
    const auto live = n - k >= 8 ? __mmask8(0xFF) : static_cast<__mmask8>((1u << (n - k)) - 1);
    const __m256i vi = _mm256_maskz_loadu_epi32(live, I + k);
    const __m256i vj = _mm256_maskz_loadu_epi32(live, J + k);
    __m512d c[D], r2 = _mm512_setzero_pd();
    for (int d = 0; d < D; ++d) {
      const __m512d zero = _mm512_setzero_pd();
      c[d] = minimum_image(_mm512_sub_pd(_mm512_mask_i32gather_pd(zero, live, vi, p.x[d], 8),
                                         _mm512_mask_i32gather_pd(zero, live, vj, p.x[d], 8)),
                           p.box[d], p.inv_box[d]);
      r2 = _mm512_add_pd(r2, _mm512_mul_pd(c[d], c[d]));
    }
    const __mmask8 keep = _mm512_mask_cmp_pd_mask(live, r2, limit, _CMP_LT_OQ);
    for (int d = 0; d < D; ++d) _mm512_storeu_pd(p.e[d] + m, _mm512_maskz_compress_pd(keep, c[d]));
    _mm512_storeu_pd(p.r + m, _mm512_maskz_compress_pd(keep, r2));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p.i + m), _mm256_maskz_compress_epi32(keep, vi));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p.j + m), _mm256_maskz_compress_epi32(keep, vj));
    m += static_cast<std::size_t>(__builtin_popcount(keep));
  }
#elif defined(TWINFLOW_AVX2)
  const __m256d limit = _mm256_set1_pd(p.rc2);
  for (; k + 4 <= n; k += 4) {
    const __m128i vi = _mm_loadu_si128(reinterpret_cast<const __m128i*>(I + k));
    const __m128i vj = _mm_loadu_si128(reinterpret_cast<const __m128i*>(J + k));
    __m256d c[D], r2 = _mm256_setzero_pd();
    for (int d = 0; d < D; ++d) {
      c[d] = minimum_image(_mm256_sub_pd(gather(p.x[d], I + k), gather(p.x[d], J + k)), p.box[d],
                           p.inv_box[d]);
      r2 = _mm256_add_pd(r2, _mm256_mul_pd(c[d], c[d]));
    }
    const int keep = _mm256_movemask_pd(_mm256_cmp_pd(r2, limit, _CMP_LT_OQ));
    for (int d = 0; d < D; ++d) _mm256_storeu_pd(p.e[d] + m, compress(c[d], keep));
    _mm256_storeu_pd(p.r + m, compress(r2, keep));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(p.i + m), compress(vi, keep));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(p.j + m), compress(vj, keep));
    m += static_cast<std::size_t>(__builtin_popcount(keep));
  }
#else
  (void)p, (void)I, (void)J, (void)n, (void)m;
#endif
  return k;
}

// The pairs of a block closer than the cutoff (all of them without a skin), in list order: their
// separations x_i - x_j (minimum image) into s.e, r^2 into s.r, i and j into s.i and s.j.
template <class M>
std::size_t Simulation<M>::pairs_within_cutoff(const std::uint32_t* I, const std::uint32_t* J,
                                               std::size_t n, PairScratch<D>& s) const {
  const double rc2 = skin_ == 0 ? std::numeric_limits<double>::infinity() : model_.rc * model_.rc;
  CutoffPass<D> p{Columns<const double>(state_.x), {},         {},         rc2,
                  Columns<double>(s.e, D),         s.r.data(), s.i.data(), s.j.data()};
  for (int d = 0; d < D; ++d) p.box[d] = grid_.image_box(d), p.inv_box[d] = grid_.inv_box(d);
  std::size_t m = 0;
  const std::size_t k = cutoff_wide(p, I, J, n, m);
  return cutoff_scalar(p, I, J, k, n, m);
}

// Gathers u_i, u_j (DPDE) and, with velocities, v_i - v_j of a block into the scratch.
template <class M>
void Simulation<M>::pair_gather(const std::uint32_t* I, const std::uint32_t* J, std::size_t n,
                                PairScratch<D>& s, bool velocities) const {
  if constexpr (M::has_energy) {
    const double* u = state_.u.data();
    double* __restrict ui = s.ui.data();
    double* __restrict uj = s.uj.data();
    for (std::size_t k = 0; k < n; ++k) ui[k] = u[I[k]], uj[k] = u[J[k]];
  }
  if (velocities) {
    const Columns<const double> v(state_.v);
    const Columns<double> dv(s.dv, D);
    for (std::size_t k = 0; k < n; ++k)
      for (int d = 0; d < D; ++d) dv[d][k] = v[d][I[k]] - v[d][J[k]];
  }
}

// Conservative forces and potentials only (shardlow's velocity-Verlet part).
template <class M> void Simulation<M>::conservative_blocks() {
  if constexpr (M::Conservative::active) {
    const auto cons = model_.conservative;
    const double inv_cv = 1 / model_.cv;
    double* f[D];
    for (int d = 0; d < D; ++d) f[d] = carried_.f[d].data();
    double* pot = carried_.potential.data();
    grid_.for_each_pair_block([&](const std::uint32_t* I, const std::uint32_t* J, std::size_t n) {
      auto& s = PairScratch<D>::get(n);
      n = pair_geometry(I, J, n, s);
      pair_gather(I, J, n, s, false);
      double* __restrict fc = s.a.data();
      double* __restrict phi = s.b.data();
      const double *r = s.r.data(), *ui = s.ui.data(), *uj = s.uj.data();
#pragma omp simd
      for (std::size_t k = 0; k < n; ++k) {
        double th_i = 1, th_j = 1, fk, pk;
        if constexpr (M::has_energy) th_i = ui[k] * inv_cv, th_j = uj[k] * inv_cv;
        cons.eval(r[k], th_i, th_j, fk, pk);
        const bool in = r[k] < cons.rc;
        fc[k] = in ? fk : 0;
        phi[k] = in ? pk : 0;
      }
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t i = I[k], j = J[k];
        for (int d = 0; d < D; ++d) {
          const double fd = fc[k] * s.e[d][k];
          f[d][i] += fd;
          f[d][j] -= fd;
        }
        pot[i] += 0.5 * phi[k];
        pot[j] += 0.5 * phi[k];
      }
    });
  }
}

// The block's pair noises and weights into s (after pair_geometry): xi, zeta; w_D, w_R; and the
// heat law's weights where the model conducts heat.
template <class M>
void Simulation<M>::pair_noise_and_weights(const PairNoise& noise, const std::uint32_t* I,
                                           const std::uint32_t* J, std::size_t n,
                                           PairScratch<D>& s) const {
  // The weights as locals, as in the sweeps: the stores into s cannot alias them.
  const auto friction = model_.friction.w;
  noise.pairs(n, I, J, state_.id.data(), s.xi.data(), s.zeta.data());
  friction.eval(n, s.r.data(), s.wd.data(), s.wr.data());
  if constexpr (M::Heat::active) {
    const auto heat = model_.heat.w;
    heat.eval(n, s.r.data(), s.wh.data(), s.swh.data());
  }
}

// All pair forces at the current state (ec-verlet): F^C + F^D + F^R along e_ij, potentials and
// heat rates q_ij (docs/theory.md; 002:(3), (7)); the same algebra as pair_force.
template <class M> void Simulation<M>::force_blocks(const PairNoise& noise) {
  const auto cons = model_.conservative;
  const auto fr = model_.friction;
  const auto heat = model_.heat;
  const double inv_cv = 1 / model_.cv, inv_sqrt_dt = inv_sqrt_dt_;
  double* f[D];
  for (int d = 0; d < D; ++d) f[d] = carried_.f[d].data();
  double* pot = carried_.potential.data();
  double* q = carried_.q.data();
  grid_.for_each_pair_block([&](const std::uint32_t* I, const std::uint32_t* J, std::size_t n) {
    auto& s = PairScratch<D>::get(n);
    n = pair_geometry(I, J, n, s);
    pair_gather(I, J, n, s, true);
    pair_noise_and_weights(noise, I, J, n, s);
    double* __restrict fe = s.a.data();
    double* __restrict phi = s.b.data();
    double* __restrict qk = s.c.data();
    const double *r = s.r.data(), *wd = s.wd.data(), *wr = s.wr.data(), *xi = s.xi.data();
    const double *wh = s.wh.data(), *swh = s.swh.data(), *zeta = s.zeta.data();
    const double *ui = s.ui.data(), *uj = s.uj.data();
    const Columns<const double> e(s.e, D), dv(s.dv, D);
#pragma omp simd
    for (std::size_t k = 0; k < n; ++k) {
      double th_i = 1, th_j = 1, fc = 0, pk = 0;
      if constexpr (M::has_energy) th_i = ui[k] * inv_cv, th_j = uj[k] * inv_cv;
      if constexpr (M::Conservative::active) {
        cons.eval(r[k], th_i, th_j, fc, pk);
        const bool in = r[k] < cons.rc;
        fc = in ? fc : 0;
        pk = in ? pk : 0;
      }
      double ev = 0;
      for (int d = 0; d < D; ++d) ev += e[d][k] * dv[d][k];
      // Noise amplitude at the pre-point; the friction carries 003:(18)'s drift correction.
      const double sigma = fr.sigma_of(fr.harmonic(th_i, th_j));
      fe[k] = fc - fr.ito_gamma(th_i, th_j) * wd[k] * ev + sigma * wr[k] * xi[k] * inv_sqrt_dt;
      phi[k] = pk;
      if constexpr (M::Heat::active) {
        double rate, amplitude;
        heat.eval_w(wh[k], swh[k], th_i, th_j, rate, amplitude);
        qk[k] = rate + amplitude * zeta[k] * inv_sqrt_dt; // q_ij, docs/theory.md
      }
    }
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = I[k], j = J[k];
      for (int d = 0; d < D; ++d) {
        const double fd = fe[k] * e[d][k];
        f[d][i] += fd;
        f[d][j] -= fd;
      }
      pot[i] += 0.5 * phi[k];
      pot[j] += 0.5 * phi[k];
      if constexpr (M::Heat::active) q[i] += qk[k], q[j] -= qk[k];
    }
  });
}

// One pair's heat exchange over dt, q_ij dt with q_ij = rate + amplitude zeta / sqrt(dt)
// (002:(7)): into u_i, out of u_j.
template <class Heat>
inline void exchange_heat(const Heat& heat, double wh, double swh, double zeta, double dt,
                          double sqrt_dt, double th_i, double th_j, double& ui, double& uj) {
  double rate, amplitude;
  heat.eval_w(wh, swh, th_i, th_j, rate, amplitude);
  const double dq = std::fma(rate, dt, amplitude * zeta * sqrt_dt); // q_ij dt
  ui += dq;
  uj -= dq;
}

// A pair's kinetic change dk paid by the two internal energies in equal halves, so the pair
// conserves energy (002 Appendix A).
inline void pay_kinetic_change(double dk, double& ui, double& uj) {
  ui = std::fma(-0.5, dk, ui);
  uj = std::fma(-0.5, dk, uj);
}

// The Shardlow sweep over all pairs at r(t): per pair, heat exchange, then Shardlow's S1
// splitting of the pair's dissipative+random update (explicit half, implicit half, same xi), the
// kinetic change of each half taken from the pair's internal energies, so energy is conserved
// per half (Lisal et al. 2011; LAMMPS fix shardlow). Pairs in list order: each update sees the
// previous ones, and the two phases of planes keep them exact in parallel.
template <class M> void Simulation<M>::shardlow_sweep(const PairNoise& noise) {
  if (!grid_.has_pairs()) update_neighbours(true);
  grid_.for_each_pair_block([&](const std::uint32_t* I, const std::uint32_t* J, std::size_t n) {
    // Everything the sequential loop reads, as locals: the stores to u and v cannot alias them,
    // so they stay in registers instead of being reloaded after every pair's update.
    const auto fr = model_.friction;
    const auto heat = model_.heat;
    const double dt = dt_, sqrt_dt = sqrt_dt_, m = model_.mass, inv_m = 1 / m;
    const double inv_cv = 1 / model_.cv;
    double* __restrict u = state_.u.data();
    const Columns<double> v(state_.v);
    auto& s = PairScratch<D>::get(n);
    n = pair_geometry(I, J, n, s);
    pair_noise_and_weights(noise, I, J, n, s);
    const double *wd = s.wd.data(), *wr = s.wr.data(), *xi = s.xi.data();
    const double *wh = s.wh.data(), *swh = s.swh.data(), *zeta = s.zeta.data();
    const Columns<const double> e(s.e, D);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = I[k], j = J[k];
      // u and v of i and j in registers for the whole pair (i != j): a store and reload through
      // memory would sit on the chain of the pair's dependent updates.
      double ui = 0, uj = 0, th_i = 1, th_j = 1;
      if constexpr (M::has_energy) ui = u[i], uj = u[j], th_i = ui * inv_cv, th_j = uj * inv_cv;
      if constexpr (M::Heat::active) {
        exchange_heat(heat, wh[k], swh[k], zeta[k], dt, sqrt_dt, th_i, th_j, ui, uj);
        th_i = ui * inv_cv, th_j = uj * inv_cv;
      }
      double vi[D], vj[D], vr = 0;
      for (int d = 0; d < D; ++d) vi[d] = v[d][i], vj[d] = v[d][j], vr += e[d][k] * (vi[d] - vj[d]);
      // The noise amplitude is taken at the pre-point for both halves (Ito), so the friction
      // carries 003:(18)'s drift correction (a no-op for constant sigma).
      const double kick = fr.sigma_of(fr.harmonic(th_i, th_j)) * wr[k] * xi[k] * sqrt_dt;
      // Half 1, explicit: dp = 1/2 (-gamma w_D v_r dt + sigma w_R xi sqrt(dt))
      const double dp1 = 0.5 * kick - fr.ito_gamma_times(th_i, th_j, 0.5 * wd[k] * dt * vr);
      const double vr1 = std::fma(2 * inv_m, dp1, vr);
      if constexpr (M::has_energy) {
        pay_kinetic_change(dp1 * 0.5 * (vr + vr1), ui, uj); // the pair's exact change
        th_i = ui * inv_cv, th_j = uj * inv_cv;
      }
      // Half 2, implicit in v_r: v_r2 (1 + gamma' w_D dt/m) = v_r1 + sigma w_R xi sqrt(dt)/m
      const double vr2 = fr.implicit_half(vr1 + kick * inv_m, th_i, th_j, wd[k] * dt * inv_m);
      const double dp2 = 0.5 * m * (vr2 - vr1);
      if constexpr (M::has_energy) {
        pay_kinetic_change(dp2 * 0.5 * (vr1 + vr2), ui, uj);
        u[i] = ui, u[j] = uj;
      }
      const double dv = (dp1 + dp2) * inv_m;
      for (int d = 0; d < D; ++d) {
        v[d][i] = std::fma(dv, e[d][k], vi[d]);
        v[d][j] = std::fma(-dv, e[d][k], vj[d]);
      }
    }
  });
}

} // namespace twinflow::particle
