/*
 * parallel.c - the serial-below threshold of the parallel loops (see
 * parallel.h).
 */
#include "config.h"

#include "parallel.h"

#include <stdlib.h>

long sph_omp_min(void) {
  static long value = -1;
  long v = value;
  if (v < 0) {
    const char *e = getenv("SPH_OMP_MIN");
    char *end;
    v = 2048;
    if (e && *e) {
      long x = strtol(e, &end, 10);
      if (*end == '\0' && x >= 0) v = x;
    }
    value = v; /* the same value whichever thread stores it */
  }
  return v;
}
