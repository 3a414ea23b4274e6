#include <stdio.h>
#include <stdlib.h>
#include <omp.h>
static double busy(double us) { double t0 = omp_get_wtime(), x = 0; while ((omp_get_wtime() - t0) * 1e6 < us) x += 1; return x; }
int main(int argc, char** argv) {
  double gaps[] = {0, 5, 20, 100, 500};
  for (int g = 0; g < 5; ++g) {
    int reps = g < 3 ? 20000 : 4000;
    double sink = 0, work = 50; // each region: 50 us of work on each thread
    double t0 = omp_get_wtime();
    for (int r = 0; r < reps; ++r) {
      sink += busy(gaps[g]);
#pragma omp parallel reduction(+:sink)
      sink += busy(work);
    }
    double t = omp_get_wtime() - t0;
    printf("gap %5.0f us: overhead per region %6.1f us\n", gaps[g], t / reps * 1e6 - gaps[g] - work);
    if (sink < 0) puts("");
  }
}
