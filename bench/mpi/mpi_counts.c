/* Counts what a run sends through MPI, per call kind: calls, bytes sent by this rank, seconds
 * inside the call. A PMPI interposer (LD_PRELOAD=libmpi_counts.so), used by bench/scaling.sh to
 * measure the particle solver's messages per step; it changes nothing in the run. At
 * MPI_Finalize each rank writes "kind calls bytes seconds" lines to $MPI_COUNTS_OUT.<rank>. */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

enum { SENDRECV, ALLREDUCE, ALLTOALL, ALLTOALLV, ALLGATHER, ALLGATHERV, GATHERV, OTHER, KINDS };
static const char* names[KINDS] = {"sendrecv",  "allreduce",  "alltoall", "alltoallv",
                                   "allgather", "allgatherv", "gatherv",  "other"};
static double calls[KINDS], bytes[KINDS], seconds[KINDS];

static double size_of(MPI_Datatype t) {
  int s = 0;
  PMPI_Type_size(t, &s);
  return s;
}
#define TIMED(kind, nbytes, call)                                                                  \
  do {                                                                                             \
    double t0 = PMPI_Wtime();                                                                      \
    int result_ = call;                                                                              \
    seconds[kind] += PMPI_Wtime() - t0, calls[kind] += 1, bytes[kind] += (nbytes);                 \
    return result_;                                                                                \
  } while (0)

int MPI_Sendrecv(const void* sb, int sc, MPI_Datatype st, int dest, int stag, void* rb, int rc,
                 MPI_Datatype rt, int src, int rtag, MPI_Comm comm, MPI_Status* status) {
  TIMED(SENDRECV, dest == MPI_PROC_NULL ? 0 : sc * size_of(st),
        PMPI_Sendrecv(sb, sc, st, dest, stag, rb, rc, rt, src, rtag, comm, status));
}
int MPI_Allreduce(const void* sb, void* rb, int c, MPI_Datatype t, MPI_Op op, MPI_Comm comm) {
  TIMED(ALLREDUCE, c * size_of(t), PMPI_Allreduce(sb, rb, c, t, op, comm));
}
int MPI_Alltoall(const void* sb, int sc, MPI_Datatype st, void* rb, int rc, MPI_Datatype rt,
                 MPI_Comm comm) {
  int n = 1;
  PMPI_Comm_size(comm, &n);
  TIMED(ALLTOALL, n * sc * size_of(st), PMPI_Alltoall(sb, sc, st, rb, rc, rt, comm));
}
int MPI_Alltoallv(const void* sb, const int* sc, const int* sd, MPI_Datatype st, void* rb,
                  const int* rc, const int* rd, MPI_Datatype rt, MPI_Comm comm) {
  int n = 1;
  double total = 0;
  PMPI_Comm_size(comm, &n);
  for (int r = 0; r < n; ++r) total += sc[r];
  TIMED(ALLTOALLV, total * size_of(st), PMPI_Alltoallv(sb, sc, sd, st, rb, rc, rd, rt, comm));
}
int MPI_Allgather(const void* sb, int sc, MPI_Datatype st, void* rb, int rc, MPI_Datatype rt,
                  MPI_Comm comm) {
  TIMED(ALLGATHER, sc * size_of(st), PMPI_Allgather(sb, sc, st, rb, rc, rt, comm));
}
int MPI_Allgatherv(const void* sb, int sc, MPI_Datatype st, void* rb, const int* rc,
                   const int* rd, MPI_Datatype rt, MPI_Comm comm) {
  TIMED(ALLGATHERV, sc * size_of(st), PMPI_Allgatherv(sb, sc, st, rb, rc, rd, rt, comm));
}
int MPI_Gatherv(const void* sb, int sc, MPI_Datatype st, void* rb, const int* rc, const int* rd,
                MPI_Datatype rt, int root, MPI_Comm comm) {
  TIMED(GATHERV, sc * size_of(st), PMPI_Gatherv(sb, sc, st, rb, rc, rd, rt, root, comm));
}

int MPI_Finalize(void) {
  const char* out = getenv("MPI_COUNTS_OUT");
  int rank = 0;
  PMPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (out) {
    char path[4096];
    snprintf(path, sizeof path, "%s.%d", out, rank);
    FILE* f = fopen(path, "w");
    if (f) {
      for (int k = 0; k < KINDS; ++k)
        if (calls[k] > 0) fprintf(f, "%s %.0f %.0f %.9f\n", names[k], calls[k], bytes[k], seconds[k]);
      fclose(f);
    }
  }
  return PMPI_Finalize();
}
