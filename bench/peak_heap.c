// Peak live heap of a process, for memory per particle without the allocator's noise: peak RSS
// also counts freed pages the allocator keeps, which scattered the 2-rank measurement by
// 133-473 bytes per particle at N/R = 24000 (docs/performance.md, "On MPI").
//
// An LD_PRELOAD library: every malloc family call is passed to glibc and its usable size added
// to (free: taken from) a live-byte counter; the largest value it reached is written at exit to
// stderr, one line per process: "peak_heap pid=P bytes=B".
//   cc -O2 -shared -fPIC -o /tmp/peak_heap.so bench/peak_heap.c
//   LD_PRELOAD=/tmp/peak_heap.so mpirun -np 2 -x LD_PRELOAD build/app/twinflow bench ...
#define _GNU_SOURCE
#include <errno.h>
#include <malloc.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

extern void* __libc_malloc(size_t);
extern void* __libc_calloc(size_t, size_t);
extern void* __libc_realloc(void*, size_t);
extern void* __libc_memalign(size_t, size_t);
extern void __libc_free(void*);

static atomic_long live, peak;

static void* counted(void* p) {
  if (p) {
    const long now = atomic_fetch_add(&live, (long)malloc_usable_size(p)) + (long)malloc_usable_size(p);
    long old = atomic_load(&peak);
    while (now > old && !atomic_compare_exchange_weak(&peak, &old, now)) {
    }
  }
  return p;
}
static void uncount(void* p) {
  if (p) atomic_fetch_sub(&live, (long)malloc_usable_size(p));
}

void* malloc(size_t n) { return counted(__libc_malloc(n)); }
void* calloc(size_t k, size_t n) { return counted(__libc_calloc(k, n)); }
void free(void* p) {
  uncount(p);
  __libc_free(p);
}
void* realloc(void* p, size_t n) {
  uncount(p);
  return counted(__libc_realloc(p, n));
}
void* memalign(size_t a, size_t n) { return counted(__libc_memalign(a, n)); }
void* aligned_alloc(size_t a, size_t n) { return counted(__libc_memalign(a, n)); }
int posix_memalign(void** out, size_t a, size_t n) {
  void* p = __libc_memalign(a, n);
  if (!p) return ENOMEM;
  *out = counted(p);
  return 0;
}

__attribute__((destructor)) static void report(void) {
  char line[96];
  const int k = snprintf(line, sizeof line, "peak_heap pid=%d bytes=%ld\n", (int)getpid(),
                         atomic_load(&peak));
  if (k > 0) (void)!write(2, line, (size_t)k);
}
