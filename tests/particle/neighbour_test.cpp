// The cell search against a brute-force O(N^2) loop: every pair closer than rc exactly once.
#include <gtest/gtest.h>

#include <set>
#include <utility>

#include "particle/system.hpp"

using namespace twinflow::particle;

namespace {
// n particles at rest, uniformly at random in the box; ids descending in storage order (not the
// order a sort leaves) or ascending.
template <int D>
State<D> random_state(const std::array<double, D>& box, std::size_t n, unsigned seed,
                      bool descending_ids) {
  State<D> s;
  s.box = box;
  std::srand(seed);
  for (int d = 0; d < D; ++d) s.x[d].resize(n), s.v[d].assign(n, 0.0);
  s.id.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    s.id[i] = static_cast<std::uint32_t>(descending_ids ? n - 1 - i : i);
    for (int d = 0; d < D; ++d) s.x[d][i] = box[d] * (std::rand() / (RAND_MAX + 1.0));
  }
  return s;
}

template <int D>
void check(const std::array<double, D>& box, double rc, std::size_t n, unsigned seed) {
  State<D> s = random_state<D>(box, n, seed, true);
  Carried<D> carried;
  CellGrid<D> grid(box, rc);
  grid.sort(s, carried);
  std::set<std::pair<std::uint32_t, std::uint32_t>> brute, cells;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      double dx[D], r2 = 0;
      grid.separation(s, i, j, dx);
      for (int d = 0; d < D; ++d) r2 += dx[d] * dx[d];
      if (r2 < rc * rc) brute.insert(std::minmax(s.id[i], s.id[j]));
    }
  std::size_t visits = 0;
  grid.for_each_pair(s, rc, [&](std::size_t i, std::size_t j, const double* dx, double r2) {
    double check_r2 = 0;
    for (int d = 0; d < D; ++d) check_r2 += dx[d] * dx[d];
    EXPECT_EQ(check_r2, r2);
#pragma omp critical
    {
      cells.insert(std::minmax(s.id[i], s.id[j]));
      ++visits;
    }
  });
  EXPECT_EQ(visits, brute.size()) << "a pair visited twice";
  EXPECT_EQ(cells, brute);
  // ids ascend inside every cell: the canonical order that makes results sort-independent
  for (int c = 0; c < grid.cells(); ++c)
    for (std::size_t i = grid.begin(c) + 1; i < grid.end(c); ++i) EXPECT_LT(s.id[i - 1], s.id[i]);
}
} // namespace

TEST(Neighbours, CellSearchMatchesBruteForce3D) {
  check<3>({{10, 7, 6.5}}, 1.0, 1200, 1);
  check<3>({{2.5, 3.2, 9.1}}, 1.0, 300, 2); // fewer than 3 cells in x: minimum image
  check<3>({{6, 6, 6}}, 1.3, 800, 3);       // cutoff not dividing the box
}

TEST(Neighbours, CellSearchMatchesBruteForce2D) {
  check<2>({{16, 9}}, 1.0, 600, 4);
  check<2>({{2.1, 12}}, 1.0, 200, 5);
  check<2>({{4, 4}}, 1.24, 150, 6);
}

namespace {
// The pair list (build_pairs + for_each_pair_block) holds exactly the pairs of for_each_pair.
template <int D>
void check_list(const std::array<double, D>& box, double rc, std::size_t n, unsigned seed,
                std::array<bool, D> periodic) {
  State<D> s = random_state<D>(box, n, seed, false);
  Carried<D> carried;
  CellGrid<D> grid(box, rc, periodic);
  grid.sort(s, carried);
  std::set<std::pair<std::uint32_t, std::uint32_t>> reference, listed;
  grid.for_each_pair_serial(s, rc, [&](std::size_t i, std::size_t j, const double*, double) {
    reference.insert(std::minmax(s.id[i], s.id[j]));
  });
  EXPECT_FALSE(grid.has_pairs());
  grid.build_pairs(s, rc);
  ASSERT_TRUE(grid.has_pairs());
  std::size_t visits = 0;
  grid.for_each_pair_block([&](const std::uint32_t* i, const std::uint32_t* j, std::size_t count) {
#pragma omp critical
    for (std::size_t k = 0; k < count; ++k, ++visits)
      listed.insert(std::minmax(s.id[i[k]], s.id[j[k]]));
  });
  EXPECT_EQ(visits, reference.size()) << "a pair listed twice";
  EXPECT_EQ(grid.pair_count(), reference.size());
  EXPECT_EQ(listed, reference);
  grid.sort(s, carried);
  EXPECT_FALSE(grid.has_pairs()) << "a sort invalidates the list";
}
} // namespace

TEST(Neighbours, PairListMatchesCellSearch) {
  check_list<3>({{8.5, 6.2, 7.9}}, 1.0, 1500, 3, {{true, true, true}});
  check_list<3>({{2.5, 6.2, 3.9}}, 1.0, 300, 4, {{true, true, true}});  // single cells, wraps
  check_list<3>({{6.5, 5.2, 4.4}}, 1.0, 600, 5, {{true, false, true}}); // walls in y
  check_list<3>({{6.5, 5.2, 5.1}}, 1.0, 600, 6, {{false, true, false}});
  check_list<2>({{12.3, 9.7}}, 1.0, 900, 7, {{true, true}});
  check_list<2>({{12.3, 3.7}}, 1.0, 300, 8, {{true, false}});
}

// A row of cells with more than 65536 particles: the list's 16-bit offsets of i start new
// segments inside the row (a long thin 2D box: one cell across, one row of 20000 cells).
TEST(Neighbours, PairListSplitsRowsOfManyParticles) {
  check_list<2>({{20000, 2.5}}, 1.0, 150000, 9, {{true, true}});
}
