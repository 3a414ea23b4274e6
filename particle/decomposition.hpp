#pragma once
// The particle box split over MPI ranks into slabs of cell planes along its last direction (z in
// 3D, y in 2D). Cell indices grow fastest along x, slowest along the last direction, so a slab is
// a contiguous range of cells, and the particles of every rank, each sorted by (cell, id),
// concatenated in rank order are the one-process run's particles in its storage order: a sum
// taken in that order on rank 0 over gathered particles is the one-process sum, bit for bit.
//
// Slabs start at even planes, so the pair passes' two phases of planes (CellGrid) line up with
// rank boundaries: every even unit (a plane and the next) lies inside one rank, and only the
// last odd unit of a rank reaches into the plane above it, held as a ghost copy of the upper
// rank's first plane. Without MPI, or on one rank, nothing here is used and the solver is the
// one-process code.

#ifndef OMPI_SKIP_MPICXX
#define OMPI_SKIP_MPICXX 1 // the C API only (OpenMPI's C++ bindings warn)
#endif
#include <mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "io/files.hpp"

namespace twinflow::particle {

// The ranks of the run (MPI_COMM_WORLD when MPI is initialised and has more than one rank).
struct Slabs {
  MPI_Comm comm = MPI_COMM_WORLD;
  int ranks = 1, rank = 0;
  int planes = 1;         // cell planes along the last direction, in the whole box
  std::vector<int> first; // first plane of each rank, then `planes`
  int lower = MPI_PROC_NULL, upper = MPI_PROC_NULL; // the ranks of the slabs below and above

  bool active() const { return ranks > 1; }
  bool root() const { return rank == 0; }
  int begin() const { return first[rank]; }
  int end() const { return first[rank + 1]; }
  int owner(int plane) const {
    int r = 0;
    while (plane >= first[r + 1]) ++r;
    return r;
  }

  // The ranks of the process, or one if MPI is not initialised (tests, library users).
  static int world_size() {
    int initialised = 0, finalised = 0;
    MPI_Initialized(&initialised);
    MPI_Finalized(&finalised);
    if (!initialised || finalised) return 1;
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    return size;
  }
  static int world_rank() {
    if (world_size() == 1) return 0;
    int r = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
  }

  // Pairs of planes dealt out evenly; a rank holds at least one pair.
  static Slabs split(int planes, bool periodic, const char* axis) {
    Slabs s;
    s.ranks = world_size();
    s.rank = world_rank();
    s.planes = planes;
    const int pairs = (planes + 1) / 2;
    if (s.ranks > 1 && pairs < s.ranks)
      throw io::InputError("the particle box has " + std::to_string(planes) +
                           " cell planes along " + axis + ": at most " + std::to_string(pairs) +
                           " MPI ranks (two planes each), not " + std::to_string(s.ranks) +
                           "; run on fewer ranks or a longer box");
    s.first.resize(static_cast<std::size_t>(s.ranks) + 1);
    for (int r = 0; r <= s.ranks; ++r)
      s.first[r] = std::min(planes, 2 * static_cast<int>(static_cast<long>(pairs) * r / s.ranks));
    if (s.ranks > 1) {
      s.upper = s.rank + 1 < s.ranks ? s.rank + 1 : periodic ? 0 : MPI_PROC_NULL;
      s.lower = s.rank > 0 ? s.rank - 1 : periodic ? s.ranks - 1 : MPI_PROC_NULL;
    }
    return s;
  }
};

template <class T> MPI_Datatype mpi_type();
template <> inline MPI_Datatype mpi_type<double>() {
  return MPI_DOUBLE;
}
template <> inline MPI_Datatype mpi_type<float>() {
  return MPI_FLOAT;
}
template <> inline MPI_Datatype mpi_type<std::uint32_t>() {
  return MPI_UINT32_T;
}
template <> inline MPI_Datatype mpi_type<long>() {
  return MPI_LONG;
}

// A range of one array, as part of a message (sendrecv_spans).
struct ArraySpan {
  void* data;
  std::size_t count;
  MPI_Datatype type;
  template <class T>
  ArraySpan(T* p, std::size_t n) : data(p), count(n), type(mpi_type<std::remove_const_t<T>>()) {}
};

// One message whose parts are ranges of several arrays, sent from and received into the arrays
// themselves (a struct datatype of absolute addresses, MPI_BOTTOM): no buffer as large as the
// message on either side, which on two ranks was ~25 bytes per owned particle at the peak.
inline void sendrecv_spans(const std::vector<ArraySpan>& send, int to,
                           const std::vector<ArraySpan>& receive, int from, int tag,
                           MPI_Comm comm) {
  const auto type_of = [](const std::vector<ArraySpan>& spans) {
    std::vector<int> lengths;
    std::vector<MPI_Aint> addresses;
    std::vector<MPI_Datatype> types;
    for (const ArraySpan& s : spans) {
      if (s.count == 0) continue;
      MPI_Aint a;
      MPI_Get_address(s.data, &a);
      lengths.push_back(static_cast<int>(s.count)), addresses.push_back(a), types.push_back(s.type);
    }
    MPI_Datatype t;
    MPI_Type_create_struct(static_cast<int>(lengths.size()), lengths.data(), addresses.data(),
                           types.data(), &t);
    MPI_Type_commit(&t);
    return t;
  };
  MPI_Datatype out = type_of(send), in = type_of(receive);
  MPI_Sendrecv(MPI_BOTTOM, 1, out, to, tag, MPI_BOTTOM, 1, in, from, tag, comm, MPI_STATUS_IGNORE);
  MPI_Type_free(&out), MPI_Type_free(&in);
}

// The ranks' arrays concatenated in rank order on rank 0 (elsewhere `out` is left empty).
template <class T>
void gather_in_rank_order(const Slabs& s, const T* local, std::size_t count, std::vector<T>& out) {
  int n = static_cast<int>(count);
  std::vector<int> counts(static_cast<std::size_t>(s.ranks)), offsets(counts.size() + 1, 0);
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, s.comm);
  for (std::size_t r = 0; r < counts.size(); ++r) offsets[r + 1] = offsets[r] + counts[r];
  out.assign(s.root() ? static_cast<std::size_t>(offsets.back()) : 0, T{});
  MPI_Gatherv(local, n, mpi_type<T>(), out.data(), counts.data(), offsets.data(), mpi_type<T>(), 0,
              s.comm);
}

// A sum of doubles with the same bits in any order (threads, ranks): each term rounded to fixed
// point at 2^-64 and added in 128 bits (|sum| < 2^63).
class ExactSum {
public:
  void add(double x) { sum_ += static_cast<Fixed>(std::nearbyint(std::ldexp(x, 64))); }
  double value() const { return std::ldexp(static_cast<double>(sum_), -64); }
  // Collective on several ranks: every rank's sum, on every rank.
  void add_over_ranks(const Slabs& s) {
    if (!s.active()) return;
    std::vector<Fixed> all(static_cast<std::size_t>(s.ranks));
    MPI_Allgather(&sum_, sizeof(Fixed), MPI_BYTE, all.data(), sizeof(Fixed), MPI_BYTE, s.comm);
    sum_ = 0;
    for (const Fixed a : all) sum_ += a;
  }

private:
  __extension__ typedef __int128 Fixed;
  Fixed sum_ = 0;
};

// Running sums (the walls' energy and momentum) that one process adds particle by particle in
// storage order. On several ranks each rank logs its terms with the number of the pass (a loop
// over the particles; end_pass) they came from, and flush() replays them on rank 0 pass by pass,
// the ranks in order: each sum then takes its terms in the one-process order, so it is the
// one-process sum, bit for bit. Rank 0 holds the sums.
class OrderedTally {
public:
  // 0-5 energy into each wall, 6-11 momentum, 12-17 wall heat moves proposed, 18-23 accepted
  static constexpr int slots = 24;
  void add(int slot, double value) {
    if (logging_)
      log_.push_back(static_cast<double>(pass_)), log_.push_back(slot), log_.push_back(value);
    else
      sum_[slot] += value;
  }
  void count(long n) { count_ += n; } // an integer tally (exact in any order)
  void end_pass() { ++pass_; }
  void start_logging() { logging_ = true; }
  // Collective on several ranks: rank 0 adds every rank's logged terms and counts.
  void flush(const Slabs& s) {
    if (!logging_) return;
    std::vector<double> all;
    gather_in_rank_order(s, log_.data(), log_.size(), all);
    log_.clear();
    long counted = 0;
    MPI_Reduce(&count_, &counted, 1, MPI_LONG, MPI_SUM, 0, s.comm);
    count_ = 0;
    if (!s.root()) return;
    count_total_ += counted;
    std::vector<std::size_t> order(all.size() / 3);
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return all[3 * a] < all[3 * b]; // by pass; the ranks, and each rank's terms, keep order
    });
    for (const std::size_t k : order) sum_[static_cast<int>(all[3 * k + 1])] += all[3 * k + 2];
  }
  std::array<double, slots>& sums() { return sum_; }
  const std::array<double, slots>& sums() const { return sum_; }
  long counted() const { return logging_ ? count_total_ : count_; }
  void set_counted(long n) { (logging_ ? count_total_ : count_) = n; }

private:
  bool logging_ = false;
  std::array<double, slots> sum_{};
  long count_ = 0, count_total_ = 0; // count_total_: rank 0's flushed total when logging
  long pass_ = 0;
  std::vector<double> log_; // (pass, slot, term) triples
};

// An OrderedTally's terms from one particle loop: straight into the tally (one thread), or into
// a thread's log that is replayed into it after the loop, chunk after chunk in particle order,
// so that the sums are the one-thread sums, bit for bit (Simulation::for_particles_tallied).
class TallyTerms {
public:
  explicit TallyTerms(OrderedTally& tally) : tally_(&tally) {}
  explicit TallyTerms(std::vector<std::pair<int, double>>& log) : log_(&log) {}
  void add(int slot, double value) {
    if (tally_)
      tally_->add(slot, value);
    else
      log_->emplace_back(slot, value);
  }
  void count(long n) { counted_ += n; }
  // Into the tally: the logged terms in their order, then the count.
  void replay_into(OrderedTally& tally) const {
    if (log_)
      for (const auto& [slot, value] : *log_) tally.add(slot, value);
    tally.count(counted_);
  }

private:
  OrderedTally* tally_ = nullptr;
  std::vector<std::pair<int, double>>* log_ = nullptr;
  long counted_ = 0;
};

} // namespace twinflow::particle
