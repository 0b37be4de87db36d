/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * shape.c - the shapes of fluid blocks (shape.h): inside tests, bounding
 * boxes, areas and volumes, and the simple-polygon check.
 *
 * The polygon's inside is its winding number (Sunday 2001, as in
 * doc/references.md: each edge that crosses the point's horizontal line
 * upward with the point on its left adds one, downward with the point on
 * its right takes one away), nonzero inside, so the vertices may run
 * either way round.
 */
#include "config.h"

#include "case/shape.h"

#include "case/mesh.h"

#include <math.h>
#include <stdio.h>

const char *sph_shape_name(sph_shape_kind k) {
  switch (k) {
  case SPH_SHAPE_POLYGON: return "polygon";
  case SPH_SHAPE_BALL: return SPH_DIM == 2 ? "circle" : "sphere";
  case SPH_SHAPE_CYLINDER: return "cylinder";
  case SPH_SHAPE_MESH: return "mesh";
  default: return "box";
  }
}

/* Twice the signed area of the triangle (a, b, p): > 0 with p left of a->b. */
static double cross(const double *a, const double *b, double px, double py) {
  return (b[0] - a[0]) * (py - a[1]) - (px - a[0]) * (b[1] - a[1]);
}

static int polygon_inside(const sph_shape *s, double px, double py) {
  int wn = 0;
  for (size_t i = 0; i < s->n; i++) {
    const double *a = s->vertex + 2 * i, *b = s->vertex + 2 * ((i + 1) % s->n);
    if (a[1] <= py) {
      if (b[1] > py && cross(a, b, px, py) > 0.0) wn++;
    } else if (b[1] <= py && cross(a, b, px, py) < 0.0) {
      wn--;
    }
  }
  return wn != 0;
}

/* Inside the shape s, or the box lo..hi for a box. */
static int inside(const sph_shape *s, const double *lo, const double *hi, const double *x);

int sph_shape_inside(const sph_fluid_block *f, const double *x) {
  return inside(&f->shape, f->lo, f->hi, x);
}

int sph_shape_winding_of(const void *shape, const double *x) {
  const sph_shape *s = shape;
  if (SPH_DIM == 3 && s->kind == SPH_SHAPE_MESH) return sph_mesh_winding(s->mesh, x);
  return inside(s, NULL, NULL, x);
}

static int inside(const sph_shape *s, const double *lo, const double *hi, const double *x) {
  switch (s->kind) {
  case SPH_SHAPE_MESH: return SPH_DIM == 3 && sph_mesh_winding(s->mesh, x) != 0;
  case SPH_SHAPE_POLYGON: return polygon_inside(s, x[0], x[SPH_UP]);
  case SPH_SHAPE_BALL: {
    double r2 = 0.0;
    for (int a = 0; a < SPH_DIM; a++)
      r2 += (x[a] - s->centre[a]) * (x[a] - s->centre[a]);
    return r2 < s->radius * s->radius;
  }
  case SPH_SHAPE_CYLINDER: {
    double u[3], w[3], uu = 0.0, wu = 0.0;
    for (int a = 0; a < 3 && a < SPH_DIM; a++) {
      u[a] = s->end[a] - s->centre[a];
      w[a] = x[a] - s->centre[a];
      uu += u[a] * u[a];
      wu += w[a] * u[a];
    }
    if (!(wu > 0.0 && wu < uu)) return 0; /* beyond an end */
    const double t = wu / uu;
    double d2 = 0.0;
    for (int a = 0; a < 3 && a < SPH_DIM; a++)
      d2 += (w[a] - t * u[a]) * (w[a] - t * u[a]);
    return d2 < s->radius * s->radius;
  }
  default:
    for (int a = 0; a < SPH_DIM; a++)
      if (!(x[a] > lo[a] && x[a] < hi[a])) return 0;
    return 1;
  }
}

void sph_shape_bounds(const sph_shape *s, double lo[SPH_DIM], double hi[SPH_DIM]) {
  switch (s->kind) {
  case SPH_SHAPE_POLYGON:
    lo[0] = hi[0] = s->vertex[0];
    lo[SPH_UP] = hi[SPH_UP] = s->vertex[1];
    for (size_t i = 1; i < s->n; i++) {
      lo[0] = fmin(lo[0], s->vertex[2 * i]);
      hi[0] = fmax(hi[0], s->vertex[2 * i]);
      lo[SPH_UP] = fmin(lo[SPH_UP], s->vertex[2 * i + 1]);
      hi[SPH_UP] = fmax(hi[SPH_UP], s->vertex[2 * i + 1]);
    }
    break;
  case SPH_SHAPE_BALL:
    for (int a = 0; a < SPH_DIM; a++) {
      lo[a] = s->centre[a] - s->radius;
      hi[a] = s->centre[a] + s->radius;
    }
    break;
  case SPH_SHAPE_MESH: {
    double l[3], h[3];
    sph_mesh_bounds(s->mesh, l, h);
    for (int a = 0; a < SPH_DIM; a++)
      lo[a] = l[a], hi[a] = h[a];
    break;
  }
  case SPH_SHAPE_CYLINDER: { /* each end's disc reaches r sqrt(1 - u_a^2 / |u|^2) along a */
    double uu = 0.0;
    for (int a = 0; a < SPH_DIM; a++)
      uu += (s->end[a] - s->centre[a]) * (s->end[a] - s->centre[a]);
    for (int a = 0; a < SPH_DIM; a++) {
      const double ua = s->end[a] - s->centre[a];
      const double reach = s->radius * sqrt(fmax(0.0, 1.0 - ua * ua / uu));
      lo[a] = fmin(s->centre[a], s->end[a]) - reach;
      hi[a] = fmax(s->centre[a], s->end[a]) + reach;
    }
    break;
  }
  default: break;
  }
}

/* The polygon's signed area (shoelace). */
static double polygon_area(const double *v, size_t n) {
  double a = 0.0;
  for (size_t i = 0; i < n; i++) {
    const size_t k = (i + 1) % n;
    a += v[2 * i] * v[2 * k + 1] - v[2 * k] * v[2 * i + 1];
  }
  return 0.5 * a;
}

double sph_case_block_measure(const sph_fluid_block *f) {
  const sph_shape *s = &f->shape;
  const double pi = 3.14159265358979323846;
  switch (s->kind) {
  case SPH_SHAPE_POLYGON: {
    const double a = fabs(polygon_area(s->vertex, s->n));
    return SPH_DIM == 2 ? a : a * (f->hi[1] - f->lo[1]);
  }
  case SPH_SHAPE_BALL:
    return SPH_DIM == 2 ? pi * s->radius * s->radius
                        : 4.0 / 3.0 * pi * s->radius * s->radius * s->radius;
  case SPH_SHAPE_CYLINDER: {
    double uu = 0.0;
    for (int a = 0; a < SPH_DIM; a++)
      uu += (s->end[a] - s->centre[a]) * (s->end[a] - s->centre[a]);
    return pi * s->radius * s->radius * sqrt(uu);
  }
  case SPH_SHAPE_MESH: return sph_mesh_volume(s->mesh);
  default: {
    double m = 1.0;
    for (int a = 0; a < SPH_DIM; a++)
      m *= f->hi[a] - f->lo[a];
    return m;
  }
  }
}

/* The sign of the orientation of (a, b, c): 1 left turn, -1 right, 0 collinear. */
static int orient(const double *a, const double *b, const double *c) {
  const double d = cross(a, b, c[0], c[1]);
  return (d > 0.0) - (d < 0.0);
}

/* c on the segment a-b, given the three collinear. */
static int on_segment(const double *a, const double *b, const double *c) {
  return fmin(a[0], b[0]) <= c[0] && c[0] <= fmax(a[0], b[0]) && fmin(a[1], b[1]) <= c[1] &&
         c[1] <= fmax(a[1], b[1]);
}

/* The closed segments p1-p2 and q1-q2 meet. */
static int segments_meet(const double *p1, const double *p2, const double *q1, const double *q2) {
  const int o1 = orient(p1, p2, q1), o2 = orient(p1, p2, q2);
  const int o3 = orient(q1, q2, p1), o4 = orient(q1, q2, p2);
  if (o1 != o2 && o3 != o4) return 1;
  return (o1 == 0 && on_segment(p1, p2, q1)) || (o2 == 0 && on_segment(p1, p2, q2)) ||
         (o3 == 0 && on_segment(q1, q2, p1)) || (o4 == 0 && on_segment(q1, q2, p2));
}

int sph_polygon_defect(const double *v, size_t n, char *why, size_t len) {
  for (size_t i = 0; i < n; i++) {
    const size_t k = (i + 1) % n;
    if (v[2 * i] == v[2 * k] && v[2 * i + 1] == v[2 * k + 1]) {
      snprintf(why, len, "vertices %zu and %zu are the same point [%g, %g]", i, k, v[2 * i],
               v[2 * i + 1]);
      return -1;
    }
  }
  if (polygon_area(v, n) == 0.0) {
    snprintf(why, len, "its area is zero (its vertices are on one line)");
    return -1;
  }
  for (size_t i = 0; i < n; i++) {
    const double *a = v + 2 * i, *b = v + 2 * ((i + 1) % n);
    /* the next edge turns back along this one: they overlap beyond their common vertex */
    const double *c = v + 2 * ((i + 2) % n);
    if (orient(a, b, c) == 0 &&
        (c[0] - b[0]) * (b[0] - a[0]) + (c[1] - b[1]) * (b[1] - a[1]) < 0.0) {
      snprintf(why, len, "its edges %zu-%zu and %zu-%zu overlap (the outline turns back on itself)",
               i, (i + 1) % n, (i + 1) % n, (i + 2) % n);
      return -1;
    }
    for (size_t j = i + 2; j < n; j++) {
      if (i == 0 && j == n - 1) continue; /* the closing edge is adjacent to the first */
      const double *p = v + 2 * j, *q = v + 2 * ((j + 1) % n);
      if (segments_meet(a, b, p, q)) {
        snprintf(why, len,
                 "its edges %zu-%zu and %zu-%zu cross or touch (expected a simple polygon: "
                 "an outline that does not meet itself)",
                 i, (i + 1) % n, j, (j + 1) % n);
        return -1;
      }
    }
  }
  return 0;
}

long sph_case_block_points(const sph_fluid_block *f, double dx) {
  long n[3] = {1, 1, 1};
  for (int a = 0; a < SPH_DIM; a++)
    n[a] = sph_case_lattice_points(f->lo[a], f->hi[a], dx);
  if (f->shape.kind == SPH_SHAPE_BOX) return n[0] * n[1] * n[2];
  long in = 0;
  for (long k = 0; k < n[2]; k++)
    for (long j = 0; j < n[1]; j++)
      for (long i = 0; i < n[0]; i++) {
        const long idx[3] = {i, j, k};
        double x[SPH_DIM];
        for (int a = 0; a < SPH_DIM; a++)
          x[a] = f->lo[a] + ((double)idx[a] + 0.5) * dx;
        in += sph_shape_inside(f, x);
      }
  return in;
}

/* ---- the way out: the mirror offsets of a shaped obstacle's wall particles ---- */

/* The closest point c to p on the segment a-b (2-D), and the squared distance. */
static double closest_on_segment(const double *a, const double *b, double px, double py,
                                 double c[2]) {
  const double ex = b[0] - a[0], ey = b[1] - a[1], ee = ex * ex + ey * ey;
  double t = ee > 0.0 ? ((px - a[0]) * ex + (py - a[1]) * ey) / ee : 0.0;
  t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
  c[0] = a[0] + t * ex;
  c[1] = a[1] + t * ey;
  return (c[0] - px) * (c[0] - px) + (c[1] - py) * (c[1] - py);
}

/* Whether the polygon's edge i lies at or below the floor's height. */
static int on_floor(const sph_shape *s, size_t i, double floor) {
  return s->vertex[2 * i + 1] <= floor && s->vertex[2 * ((i + 1) % s->n) + 1] <= floor;
}

void sph_shape_offset_of(const void *shape, const double *x, double floor, double *m) {
  const sph_shape *s = shape;
  double n[SPH_DIM] = {0.0}, d = 0.0; /* the outward normal at the closest point, the distance */
  switch (s->kind) {
  case SPH_SHAPE_POLYGON: { /* out through the nearest edge, or the sum over the edges that
                             * tie (diagonally out of a corner, as a box's offsets go) */
    double best = INFINITY;
    size_t e = 0;
    for (size_t i = 0; i < s->n; i++) {
      double ci[2];
      if (on_floor(s, i, floor)) continue;
      const double d2 = closest_on_segment(s->vertex + 2 * i, s->vertex + 2 * ((i + 1) % s->n),
                                           x[0], x[SPH_UP], ci);
      if (d2 < best) best = d2, e = i;
    }
    if (best > 0.0) {
      double sum[2] = {0.0, 0.0};
      for (size_t i = 0; i < s->n; i++) {
        double ci[2];
        if (!on_floor(s, i, floor) &&
            closest_on_segment(s->vertex + 2 * i, s->vertex + 2 * ((i + 1) % s->n), x[0], x[SPH_UP],
                               ci) <= best * (1.0 + 1e-9)) /* a tie to round-off */
          sum[0] += ci[0] - x[0], sum[1] += ci[1] - x[SPH_UP];
      }
      m[0] = 2.0 * sum[0];
      m[SPH_UP] = 2.0 * sum[1];
      if (SPH_DIM == 3) m[1] = 0.0;
      return;
    }
    const double *a = s->vertex + 2 * e, *b = s->vertex + 2 * ((e + 1) % s->n);
    const double sign = polygon_area(s->vertex, s->n) > 0.0 ? 1.0 : -1.0; /* anticlockwise: right */
    const double ex = b[0] - a[0], ey = b[1] - a[1], len = hypot(ex, ey);
    n[0] = sign * ey / len;
    n[SPH_UP] = -sign * ex / len;
    break;
  }
  case SPH_SHAPE_BALL: {
    double r2 = 0.0;
    for (int a = 0; a < SPH_DIM; a++)
      r2 += (x[a] - s->centre[a]) * (x[a] - s->centre[a]);
    const double rho = sqrt(r2);
    d = s->radius - rho;
    for (int a = 0; a < SPH_DIM; a++)
      n[a] = rho > 0.0 ? (x[a] - s->centre[a]) / rho : a == SPH_UP;
    break;
  }
  case SPH_SHAPE_CYLINDER: {
    double u[3] = {0.0, 0.0, 0.0}, w[3] = {0.0, 0.0, 0.0}, len = 0.0, t = 0.0, rho = 0.0;
    for (int a = 0; a < SPH_DIM; a++) {
      u[a] = s->end[a] - s->centre[a];
      len += u[a] * u[a];
    }
    len = sqrt(len);
    for (int a = 0; a < SPH_DIM; a++) {
      u[a] /= len;
      w[a] = x[a] - s->centre[a];
      t += w[a] * u[a];
    }
    double q[3] = {0.0, 0.0, 0.0}; /* from the axis */
    for (int a = 0; a < SPH_DIM; a++) {
      q[a] = w[a] - t * u[a];
      rho += q[a] * q[a];
    }
    rho = sqrt(rho);
    /* an end whose centre is at or below the floor (a cylinder standing on it) is no way out */
    const double side = s->radius - rho, lo = s->centre[SPH_UP] <= floor ? INFINITY : t,
                 hi = s->end[SPH_UP] <= floor ? INFINITY : len - t;
    d = fmin(side, fmin(lo, hi));
    for (int a = 0; a < SPH_DIM; a++)
      n[a] = d == side && rho > 0.0 ? q[a] / rho : d == lo ? -u[a] : u[a];
    break;
  }
  case SPH_SHAPE_MESH:
    if (SPH_DIM == 3) {
      double c[3], nt[3];
      d = sph_mesh_nearest(s->mesh, x, floor, c, nt);
      for (int a = 0; a < SPH_DIM; a++)
        n[a] = d > 0.0 ? (c[a] - x[a]) / d : nt[a];
    }
    break;
  default: break;
  }
  for (int a = 0; a < SPH_DIM; a++)
    m[a] = 2.0 * d * n[a];
}
