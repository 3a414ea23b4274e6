/* The cost of the particle solver's exchange over this MPI library: two ranks each send b bytes
 * to the other with one MPI_Sendrecv (the halo's pattern), and an MPI_Allreduce of one double
 * (the list check's); prints "sendrecv <bytes> <seconds per call>" for b = 8 B .. 8 MB and
 * "allreduce 8 <seconds>", medians of 5 batches. Used by bench/scaling.sh. */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

static int by_value(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const int other = rank ^ 1;
  if (size != 2) {
    if (rank == 0) fprintf(stderr, "mpi_exchange: run on 2 ranks\n");
    MPI_Finalize();
    return 2;
  }
  char *send = malloc(8 << 20), *receive = malloc(8 << 20);
  for (int i = 0; i < (8 << 20); ++i) send[i] = (char)i;
  double batch[5];
  for (long bytes = 8; bytes <= (8 << 20); bytes *= 4) {
    const int reps = bytes < 65536 ? 2000 : bytes < (1 << 20) ? 200 : 20;
    for (int b = 0; b < 5; ++b) {
      MPI_Barrier(MPI_COMM_WORLD);
      const double t0 = MPI_Wtime();
      for (int k = 0; k < reps; ++k)
        MPI_Sendrecv(send, (int)bytes, MPI_BYTE, other, 1, receive, (int)bytes, MPI_BYTE, other, 1,
                     MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      batch[b] = (MPI_Wtime() - t0) / reps;
    }
    qsort(batch, 5, sizeof batch[0], by_value);
    if (rank == 0) printf("sendrecv %ld %.4g\n", bytes, batch[2]);
  }
  for (int b = 0; b < 5; ++b) {
    double x = rank, t0;
    MPI_Barrier(MPI_COMM_WORLD);
    t0 = MPI_Wtime();
    for (int k = 0; k < 2000; ++k) MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    batch[b] = (MPI_Wtime() - t0) / 2000;
  }
  qsort(batch, 5, sizeof batch[0], by_value);
  if (rank == 0) printf("allreduce 8 %.4g\n", batch[2]);
  free(send), free(receive);
  MPI_Finalize();
  return 0;
}
