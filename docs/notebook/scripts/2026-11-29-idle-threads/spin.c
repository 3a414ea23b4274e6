#include <stdio.h>
#include <omp.h>
int main(){ double t0=omp_get_wtime(); double s=0;
#pragma omp parallel reduction(+:s)
{ double a=1.0,b=1.0000001,c=0.9999999,d=1.0; for(long i=0;i<2000000000L;i++){a=a*b+1e-9; d=d*c+1e-9;} s+=a+d; }
printf("%d threads %.3f s (%g)\n", omp_get_max_threads(), omp_get_wtime()-t0, s);}
