#include <stdio.h>
#include <stdlib.h>
#include <omp.h>
int main(){ long n=1L<<25; double *a=malloc(n*8*2); for(long i=0;i<2*n;i++)a[i]=i;
double t0=omp_get_wtime(); double s=0;
#pragma omp parallel reduction(+:s)
{ int t=omp_get_thread_num(); double *p=a+t*n; for(int r=0;r<10;r++) for(long i=0;i<n;i++) s+=p[i]; }
printf("%d threads %.3f s GB/s %.1f\n", omp_get_max_threads(), omp_get_wtime()-t0, 10.0*n*8*omp_get_max_threads()/(omp_get_wtime()-t0)/1e9);}
