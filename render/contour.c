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
 *
 * Every crossing is named by its grid edge (a key: 2 (j nx + i) for the
 * edge from point (i, j) to (i+1, j), one more for the edge to (i, j+1))
 * and placed from that edge's two values in one order, whichever cell asks:
 * the two cells that share an edge put its crossing at the same point, bit
 * for bit. The polylines are the pieces joined at shared keys: an edge's
 * crossing belongs to at most two pieces (one per cell beside it), so the
 * ends, sorted by key, pair up; a chain that reaches an end without a
 * partner (a cell left out by keep, the grid's border) is open, the rest
 * close. Chains start at the open ends in piece order, then at the first
 * piece not yet taken: the result is a pure function of the grid.
 */
#include "config.h"

#include "contour.h"

#include <math.h>
#include <stdlib.h>

static double value(const double *phi, int nx, int i, int j) {
  double v = phi[(size_t)j * nx + i];
  return isnan(v) ? -1.0 : v;
}

/* The crossing on the edge named key, in grid coordinates. */
static void crossing(const double *phi, int nx, long key, double *x, double *y) {
  const long q = key >> 1;
  const int i = (int)(q % nx), j = (int)(q / nx);
  const double a = value(phi, nx, i, j);
  if (key & 1) {
    const double b = value(phi, nx, i, j + 1);
    *x = i + 0.5;
    *y = j + 0.5 + a / (a - b);
  } else {
    const double b = value(phi, nx, i + 1, j);
    *x = i + 0.5 + a / (a - b);
    *y = j + 0.5;
  }
}

/* The pieces of the line in cell (i, j) as pairs of edge keys (0, 1 or 2
 * pieces). */
static int cell_pieces(const double *phi, const unsigned char *keep, int nx, int i, int j,
                       long piece[2][2]) {
  static const int ci[4] = {0, 1, 1, 0}, cj[4] = {0, 0, 1, 1};
  const long base = 2L * ((long)j * nx + i);
  /* the keys of edges 0..3: below, right, above, left */
  const long key[4] = {base, base + 2 + 1, base + 2L * nx, base + 1};
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
  if (!any || veto || mask == 0 || mask == 15) return 0;
  long e[4];
  int nc = 0;
  for (int k = 0; k < 4; k++)
    if (((mask >> k) & 1) != ((mask >> ((k + 1) % 4)) & 1)) e[nc++] = key[k];
  if (nc == 2) {
    piece[0][0] = e[0];
    piece[0][1] = e[1];
    return 1;
  }
  /* a saddle, crossings on edges 0, 1, 2, 3: pair (0,1)(2,3) cuts off
   * corners 1 and 3; pair (3,0)(1,2) cuts off corners 0 and 2 */
  const double mean = 0.25 * (v[0] + v[1] + v[2] + v[3]);
  const int corner1_in = (mask >> 1) & 1;
  if ((mean >= 0.0) != corner1_in) { /* corners 1, 3 are the minority */
    piece[0][0] = e[0], piece[0][1] = e[1], piece[1][0] = e[2], piece[1][1] = e[3];
  } else {
    piece[0][0] = e[3], piece[0][1] = e[0], piece[1][0] = e[1], piece[1][1] = e[2];
  }
  return 2;
}

void rcontour(const double *phi, const unsigned char *keep, int nx, int ny, rcontour_segment seg,
              void *ctx) {
  for (int j = 0; j + 1 < ny; j++)
    for (int i = 0; i + 1 < nx; i++) {
      long piece[2][2];
      const int n = cell_pieces(phi, keep, nx, i, j, piece);
      for (int k = 0; k < n; k++) {
        double x0, y0, x1, y1;
        crossing(phi, nx, piece[k][0], &x0, &y0);
        crossing(phi, nx, piece[k][1], &x1, &y1);
        seg(ctx, x0, y0, x1, y1);
      }
    }
}

typedef struct end_ref {
  long key;
  long end; /* 2 piece + (0 or 1) */
} end_ref;

static int by_key(const void *a, const void *b) {
  const end_ref *p = a, *q = b;
  if (p->key != q->key) return p->key < q->key ? -1 : 1;
  return p->end < q->end ? -1 : p->end > q->end;
}

/* Follows the chain from end `from` (an end of a piece not yet taken),
 * writing its points into xy; the number of points. */
static size_t follow(const double *phi, int nx, const long *keys, const long *partner,
                     unsigned char *taken, long from, double *xy) {
  size_t n = 0;
  long e = from;
  crossing(phi, nx, keys[e], &xy[0], &xy[1]);
  n = 1;
  for (;;) {
    taken[e >> 1] = 1;
    const long out = e ^ 1; /* the piece's other end */
    crossing(phi, nx, keys[out], &xy[2 * n], &xy[2 * n + 1]);
    n++;
    const long next = partner[out];
    if (next < 0 || taken[next >> 1]) break;
    e = next;
  }
  return n;
}

int rcontour_lines(const double *phi, const unsigned char *keep, int nx, int ny,
                   rcontour_polyline line, void *ctx) {
  size_t cap = 1024, np = 0;
  long *keys = malloc(2 * cap * sizeof *keys);
  if (!keys) return -1;
  for (int j = 0; j + 1 < ny; j++)
    for (int i = 0; i + 1 < nx; i++) {
      long piece[2][2];
      const int n = cell_pieces(phi, keep, nx, i, j, piece);
      if (np + (size_t)n > cap) {
        long *k2 = realloc(keys, 4 * cap * sizeof *keys);
        if (!k2) {
          free(keys);
          return -1;
        }
        keys = k2;
        cap *= 2;
      }
      for (int k = 0; k < n; k++, np++) {
        keys[2 * np] = piece[k][0];
        keys[2 * np + 1] = piece[k][1];
      }
    }
  int rc = 0;
  end_ref *ends = malloc((2 * np + 1) * sizeof *ends);
  long *partner = malloc((2 * np + 1) * sizeof *partner);
  unsigned char *taken = calloc(np + 1, 1);
  double *xy = malloc((2 * np + 2) * 2 * sizeof *xy);
  if (!ends || !partner || !taken || !xy) rc = -1;
  for (size_t e = 0; !rc && e < 2 * np; e++) {
    ends[e] = (end_ref){keys[e], (long)e};
    partner[e] = -1;
  }
  if (!rc) qsort(ends, 2 * np, sizeof *ends, by_key);
  for (size_t k = 0; !rc && k + 1 < 2 * np; k++)
    if (ends[k].key == ends[k + 1].key) {
      partner[ends[k].end] = ends[k + 1].end;
      partner[ends[k + 1].end] = ends[k].end;
      k++;
    }
  /* open chains from their free ends, then the closed ones */
  for (size_t e = 0; !rc && e < 2 * np; e++)
    if (partner[e] < 0 && !taken[e >> 1])
      line(ctx, xy, follow(phi, nx, keys, partner, taken, (long)e, xy), 0);
  for (size_t p = 0; !rc && p < np; p++)
    if (!taken[p]) {
      const size_t n = follow(phi, nx, keys, partner, taken, (long)(2 * p), xy);
      line(ctx, xy, n - 1, 1); /* the last point is the first again */
    }
  free(keys);
  free(ends);
  free(partner);
  free(taken);
  free(xy);
  return rc;
}
