// Test main for tests that touch MPI, HDF5-parallel, Trilinos or p4est: MPI initialised once.
#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

int main(int argc, char** argv) {
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1); // 1 thread: deterministic
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
