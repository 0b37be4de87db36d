/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * contour.c - marching squares (see contour.h).
 *
 * Corners of a cell, counted around it: 0 (i, j), 1 (i+1, j), 2 (i+1, j+1),
 * 3 (i, j+1); edge e joins corner e and corner e+1 (mod 4). The line
 * crosses an edge whose corners differ in sign; a cell has two or four such
 * edges. With two, they are joined; with four (a saddle), each crossing
 * is joined to the next one around the cell, starting either at edge 0
 * or at edge 1 so that the pairs enclose the corners whose sign differs
 * from the sign of the cell's mean value.
 */
#include "config.h"

#include "contour.h"

#include <math.h>
#include <stddef.h>

static double value(const double *phi, int nx, int i, int j) {
  double v = phi[(size_t)j * nx + i];
  return isnan(v) ? -1.0 : v;
}

void rcontour(const double *phi, const unsigned char *keep, int nx, int ny, rcontour_segment seg,
              void *ctx) {
  static const int ci[4] = {0, 1, 1, 0}, cj[4] = {0, 0, 1, 1};
  for (int j = 0; j + 1 < ny; j++) {
    for (int i = 0; i + 1 < nx; i++) {
      double v[4];
      int any = keep == NULL, veto = 0, mask = 0;
      for (int k = 0; k < 4; k++) {
        v[k] = value(phi, nx, i + ci[k], j + cj[k]);
        if (v[k] >= 0.0) mask |= 1 << k;
        if (keep) {
          unsigned char b = keep[(size_t)(j + cj[k]) * nx + i + ci[k]];
          any |= b & 1;
          veto |= b & 2;
        }
      }
      if (!any || veto || mask == 0 || mask == 15) continue;
      double ex[4], ey[4];
      int nc = 0;
      for (int e = 0; e < 4; e++) {
        int a = e, b = (e + 1) % 4;
        if (((mask >> a) & 1) == ((mask >> b) & 1)) continue;
        double t = v[a] / (v[a] - v[b]);
        ex[nc] = i + 0.5 + ci[a] + t * (ci[b] - ci[a]);
        ey[nc] = j + 0.5 + cj[a] + t * (cj[b] - cj[a]);
        nc++;
      }
      if (nc == 2) {
        seg(ctx, ex[0], ey[0], ex[1], ey[1]);
      } else if (nc == 4) {
        /* crossings on edges 0, 1, 2, 3: pair (0,1)(2,3) cuts off corners
         * 1 and 3; pair (3,0)(1,2) cuts off corners 0 and 2 */
        double mean = 0.25 * (v[0] + v[1] + v[2] + v[3]);
        int corner1_in = (mask >> 1) & 1;
        int cut_13 = (mean >= 0.0) != corner1_in; /* corners 1, 3 are the minority */
        if (cut_13) {
          seg(ctx, ex[0], ey[0], ex[1], ey[1]);
          seg(ctx, ex[2], ey[2], ex[3], ey[3]);
        } else {
          seg(ctx, ex[3], ey[3], ex[0], ey[0]);
          seg(ctx, ex[1], ey[1], ex[2], ey[2]);
        }
      }
    }
  }
}
