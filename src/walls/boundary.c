/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * boundary.c - building walls of dynamic particles (see boundary.h).
 *
 * Positions are computed from the segment end points and integer indices
 * (never by accumulating a step), so the same case always gives the same
 * bits.
 */
#include "config.h"

#include "walls/boundary.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#if SPH_DIM == 2
int sph_boundary_add_segment(sph_particles *p, double ax, double ay, double bx, double by,
                             int layers, int stagger, int extend, double dx, double rho,
                             double mass, double h, uint8_t flags, sph_error *err) {
  const double lx = bx - ax, ly = by - ay;
  const double len = sqrt(lx * lx + ly * ly);
  if (!(len > 0.0)) return sph_error_set(err, "wall segment has zero length");
  const double tx = lx / len, ty = ly / len; /* along the wall */
  const double nx = -ty, ny = tx;            /* left normal */
  long count = (long)floor(len / dx + 0.5);
  if (count < 1) count = 1;
  const double sp = len / (double)count;
  /* the offsets' readers: mdbc, no-slip and free-slip walls */
  if (flags & SPH_WALL_NORMAL) sph_particles_use(p, SPH_ARRAYS_OFFSET);
  const int offsets = (p->live & SPH_ARRAYS_OFFSET) != 0;
  for (int k = 0; k < layers; k++) {
    const double off = (stagger ? 0.5 : 1.0) * dx * (double)k;
    const int odd = stagger && k % 2;
    /* unstaggered layers reach `extend` spacings past both ends */
    const long past = stagger ? 0 : extend;
    const long npts = odd ? count + 2 : count + 1 + 2 * past;
    /* the wall face lies dx/2 in front of layer 0, on the fluid side */
    const double depth = 0.5 * dx + off;
    for (long i = 0; i < npts; i++) {
      const double s = odd ? ((double)i - 0.5) * sp : (double)(i - past) * sp;
      const double x = ax + s * tx + off * nx;
      const double y = ay + s * ty + off * ny;
      const long idx = sph_particles_add(p, x, y, 0.0, 0.0, rho, mass, h, SPH_KIND_WALL, err);
      if (idx < 0) return -1;
      p->flags[idx] = flags;
      if (offsets) {
        p->mx[idx] = -2.0 * depth * nx;
        p->my[idx] = -2.0 * depth * ny;
      }
    }
  }
  return 0;
}
#else
int sph_boundary_add_plate(sph_particles *p, const sph_wall_segment *w, double dx, double rho,
                           double mass, double h, uint8_t flags, sph_error *err) {
  const double lx = w->x1 - w->x0, lz = w->z1 - w->z0;
  const double len = sqrt(lx * lx + lz * lz);
  if (!(len > 0.0)) return sph_error_set(err, "wall segment has zero length");
  const double tx = lx / len, tz = lz / len; /* along the wall, in the x-z plane */
  const double nx = -tz, nz = tx;            /* left normal (x right, z up) */
  long count = (long)floor(len / dx + 0.5), ny = (long)floor((w->y1 - w->y0) / dx + 0.5);
  if (count < 1) count = 1;
  if (ny < 1) ny = 1;
  const double sp = len / (double)count, sy = (w->y1 - w->y0) / (double)ny;
  if (flags & SPH_WALL_NORMAL) sph_particles_use(p, SPH_ARRAYS_OFFSET);
  const int offsets = (p->live & SPH_ARRAYS_OFFSET) != 0;
  const double v[3] = {0.0, 0.0, 0.0};
  for (int k = 0; k < w->layers; k++) {
    const double off = dx * (double)k, depth = 0.5 * dx + off;
    for (long i = 0; i <= count; i++)
      for (long j = 0; j < ny; j++) {
        const double s = (double)i * sp;
        const double x[3] = {w->x0 + s * tx + off * nx, w->y0 + ((double)j + 0.5) * sy,
                             w->z0 + s * tz + off * nz};
        const long idx = sph_particles_add_at(p, x, v, rho, mass, h, SPH_KIND_WALL, err);
        if (idx < 0) return -1;
        p->flags[idx] = flags;
        if (offsets) {
          p->mx[idx] = -2.0 * depth * nx;
          p->my[idx] = 0.0;
          p->mz[idx] = -2.0 * depth * nz;
        }
      }
  }
  return 0;
}
#endif

/* The depth of a box obstacle's lattice point idx (n points along each
 * axis): the points between it and the nearest face, the bottom counted
 * unless on_floor. */
static long box_depth(const long idx[3], const long n[3], int on_floor) {
  long depth = LONG_MAX;
  for (int a = 0; a < SPH_DIM; a++) {
    const long below = on_floor && a == SPH_UP ? LONG_MAX : idx[a], above = n[a] - 1 - idx[a];
    const long d = below < above ? below : above;
    if (d < depth) depth = d;
  }
  return depth;
}

/* The mirror offset of a box obstacle's particle at lattice index idx:
 * twice its distance to the nearest face (not the bottom of a box on the
 * floor), out through that face; through every face that is nearest (an
 * edge's or a corner's particle mirrors diagonally, out of the box's edge
 * or corner). */
static void box_offset(const long idx[3], const long n[3], int on_floor, double dx,
                       double m[SPH_DIM]) {
  const long depth = box_depth(idx, n, on_floor);
  const double dist = 2.0 * ((double)depth + 0.5) * dx;
  for (int a = 0; a < SPH_DIM; a++) {
    const long below = on_floor && a == SPH_UP ? LONG_MAX : idx[a], above = n[a] - 1 - idx[a];
    m[a] = above == depth ? dist : below == depth ? -dist : 0.0; /* (the upper face on a tie) */
  }
}

/* A shaped obstacle (o->inside): the lattice points of its bounding box inside the shape with a
 * point outside it (or beyond the box) within o->layers spacings along every axis at once: the
 * shape's outside grown by a cube of side 2 layers + 1, one axis at a time. */
static int add_shaped(sph_particles *p, const sph_obstacle *o, const long n[3], double floor_level,
                      double dx, double rho, double mass, double h, uint8_t flags, sph_error *err) {
  const long L = o->layers;
  /* an obstacle's shell lies inside its surface, among the box's points; a
   * vessel's outside it, among the points of the box grown by L: there
   * "outside" below reads "inside", and the shell is the inside grown by L
   * less the inside */
  const int vessel = o->vessel;
  const char *what = vessel ? "a vessel" : "an obstacle";
  long m[3] = {1, 1, 1}; /* the grid with L points of outside around it */
  for (int a = 0; a < SPH_DIM; a++)
    m[a] = n[a] + 2 * L;
  const size_t cells = (size_t)m[0] * (size_t)m[1] * (size_t)m[2];
  /* outside0: the shape's outside; out: grown by the layers; grown: one axis's growth */
  unsigned char *outside0 = malloc(cells), *out = malloc(cells), *grown = malloc(cells);
  if (!outside0 || !out || !grown) {
    free(outside0);
    free(out);
    free(grown);
    return sph_error_set(err, "out of memory for %s of %ld x %ld x %ld points", what, n[0], n[1],
                         n[2]);
  }
  const long pad[3] = {L, SPH_DIM > 1 ? L : 0, SPH_DIM > 2 ? L : 0};
  int crossing = 0;
  double where[SPH_DIM] = {0.0};
  for (long k = 0; k < m[2]; k++)
    for (long j = 0; j < m[1]; j++)
      for (long i = 0; i < m[0]; i++) {
        const long idx[3] = {i - pad[0], j - pad[1], k - pad[2]};
        int in = 1;
        double x[SPH_DIM];
        for (int a = 0; a < SPH_DIM; a++) {
          in &= idx[a] >= 0 && idx[a] < n[a];
          x[a] = o->lo[a] + ((double)idx[a] + 0.5) * dx;
        }
        const int wn = in ? o->inside(o->shape, x) : 0;
        if (wn != 0 && wn != 1 && !crossing) crossing = wn, memcpy(where, x, sizeof where);
        outside0[((size_t)k * (size_t)m[1] + (size_t)j) * (size_t)m[0] + (size_t)i] =
            vessel ? wn == 1 : wn == 0;
      }
  if (crossing) {
    free(outside0);
    free(out);
    free(grown);
    return sph_error_set(err,
                         "%s's surface winds %d times around (%g, %g" SPH_IF3(
                             ", %g") "): expected a surface that does not cross or overlap itself",
                         what, crossing, where[0], where[1] SPH_IF3(, where[2]));
  }
  memcpy(out, outside0, cells);
  const size_t stride[3] = {1, (size_t)m[0], (size_t)m[0] * (size_t)m[1]};
  for (int a = 0; a < SPH_DIM; a++) { /* grow the outside by L along axis a */
    for (size_t c = 0; c < cells; c++) {
      const long at = (long)(c / stride[a] % (size_t)m[a]);
      unsigned char g = 0;
      for (long d = -L; d <= L && !g; d++)
        if (at + d >= 0 && at + d < m[a]) g = out[(size_t)((long)c + d * (long)stride[a])];
      grown[c] = g;
    }
    memcpy(out, grown, cells);
  }
  const double v[SPH_DIM] = {0.0};
  if (flags & SPH_WALL_NORMAL) sph_particles_use(p, SPH_ARRAYS_OFFSET);
  const int offsets = (p->live & SPH_ARRAYS_OFFSET) != 0;
  int rc = 0;
  const long from = vessel ? -L : 0; /* a vessel's shell: the grown box's points */
  for (long k = SPH_DIM > 2 ? from : 0; k < n[2] + (SPH_DIM > 2 ? -from : 0) && !rc; k++)
    for (long j = from; j < n[1] - from && !rc; j++)
      for (long i = from; i < n[0] - from && !rc; i++) {
        double x[SPH_DIM];
        const long idx[3] = {i, j, k};
        for (int a = 0; a < SPH_DIM; a++)
          x[a] = o->lo[a] + ((double)idx[a] + 0.5) * dx;
        const size_t c =
            ((size_t)(k + pad[2]) * (size_t)m[1] + (size_t)(j + pad[1])) * (size_t)m[0] +
            (size_t)(i + pad[0]);
        if (!out[c] || outside0[c]) continue; /* deep inside, or outside (a vessel: the reverse) */
        const long q = sph_particles_add_at(p, x, v, rho, mass, h, SPH_KIND_WALL, err);
        if (q < 0) {
          rc = -1;
          continue;
        }
        p->flags[q] = flags;
        if (offsets) { /* out to the surface along its normal (a vessel: in to it) */
          double off[SPH_DIM];
          o->offset(o->shape, x, vessel ? -INFINITY : floor_level, off);
          for (int a = 0; a < SPH_DIM; a++)
            p->mirror_offset[a][q] = off[a];
        }
      }
  free(outside0);
  free(out);
  free(grown);
  return rc;
}

int sph_boundary_add_box(sph_particles *p, const sph_obstacle *o, double floor_level, double dx,
                         double rho, double mass, double h, uint8_t flags, sph_error *err) {
  const int on_floor = o->lo[SPH_UP] <= floor_level;
  long n[3] = {1, 1, 1};
  for (int a = 0; a < SPH_DIM; a++) {
    n[a] = (long)floor((o->hi[a] - o->lo[a]) / dx + 0.5);
    if (n[a] < 1) n[a] = 1;
  }
  if (o->inside) return add_shaped(p, o, n, floor_level, dx, rho, mass, h, flags, err);
  /* the offsets' readers: mdbc, no-slip and free-slip walls */
  if (flags & SPH_WALL_NORMAL) sph_particles_use(p, SPH_ARRAYS_OFFSET);
  const int offsets = (p->live & SPH_ARRAYS_OFFSET) != 0;
  const double v[SPH_DIM] = {0.0};
  for (long k = 0; k < n[2]; k++)
    for (long j = 0; j < n[1]; j++)
      for (long i = 0; i < n[0]; i++) {
        const long idx3[3] = {i, j, k};
        const long depth = box_depth(idx3, n, 0);
        if (depth >= o->layers) continue; /* inside the shell */
        double x[SPH_DIM];
        for (int a = 0; a < SPH_DIM; a++)
          x[a] = o->lo[a] + ((double)idx3[a] + 0.5) * dx;
        const long q = sph_particles_add_at(p, x, v, rho, mass, h, SPH_KIND_WALL, err);
        if (q < 0) return -1;
        p->flags[q] = flags;
        if (offsets) {
          double m[SPH_DIM];
          box_offset(idx3, n, on_floor, dx, m);
          for (int a = 0; a < SPH_DIM; a++)
            p->mirror_offset[a][q] = m[a];
        }
      }
  return 0;
}

#if SPH_DIM == 3
/* The 3-D tank: every lattice point x0 + (i + 1/2) dx, ... of the box grown by
 * `layers` spacings sideways and below (up to z1 above) that lies outside the
 * inner box: layers dx apart behind each face, edges and corners filled. A
 * tank open along x or y (t->open_along) is not grown along that axis: it
 * has no faces normal to it, and its floor and other walls run across the
 * period as the lattice does. Walls with a normal (mdbc, no-slip,
 * free-slip) carry their mirror offsets. */
int sph_boundary_add_tank(sph_particles *p, const sph_tank *t, double dx, double rho, double mass,
                          double h, uint8_t flags, sph_error *err) {
  const int L = t->layers;
  const long nx = (long)floor((t->x1 - t->x0) / dx + 0.5),
             ny = (long)floor((t->y1 - t->y0) / dx + 0.5);
  const long nz = (long)floor((t->z1 - t->z0) / dx + 0.5);
  const double v[3] = {0.0, 0.0, 0.0};
  const long Lx = t->open_along == 1 ? 0 : L, Ly = t->open_along == 2 ? 0 : L;
  /* the offsets' readers: mdbc, no-slip and free-slip walls */
  if (flags & SPH_WALL_NORMAL) sph_particles_use(p, SPH_ARRAYS_OFFSET);
  const int offsets = (p->live & SPH_ARRAYS_OFFSET) != 0;
  const double lo[3] = {t->x0, t->y0, t->z0}, hi[3] = {t->x1, t->y1, t->z1};
  for (long k = -L; k < nz + (t->lid ? L : 0); k++) /* (the lid's layers over the top) */
    for (long j = -Ly; j < ny + Ly; j++)
      for (long i = -Lx; i < nx + Lx; i++) {
        if (k >= 0 && k < nz && j >= 0 && j < ny && i >= 0 && i < nx) continue; /* inside */
        const double x[3] = {t->x0 + ((double)i + 0.5) * dx, t->y0 + ((double)j + 0.5) * dx,
                             t->z0 + ((double)k + 0.5) * dx};
        const long idx = sph_particles_add_at(p, x, v, rho, mass, h, SPH_KIND_WALL, err);
        if (idx < 0) return -1;
        p->flags[idx] = flags;
        if (!offsets) continue;
        /* the mirror point through each face the particle lies behind: through
         * one face behind a wall, diagonally through the edge or corner
         * behind an edge or a corner */
        const long at[3] = {i, j, k}, top[3] = {nx, ny, nz};
        for (int a = 0; a < 3; a++)
          p->mirror_offset[a][idx] = at[a] < 0         ? 2.0 * (lo[a] - x[a])
                                     : at[a] >= top[a] ? 2.0 * (hi[a] - x[a])
                                                       : 0.0;
      }
  return 0;
}
#else
int sph_boundary_add_tank(sph_particles *p, const sph_tank *t, double dx, double rho, double mass,
                          double h, uint8_t flags, sph_error *err) {
  const double e = 0.5 * dx;
  const int L = t->layers, st = t->stagger;
  /* floor, right to left so that the left normal points down (outwards);
   * unstaggered, its layers reach under the side walls' layers, filling the
   * corners */
  if (sph_boundary_add_segment(p, t->x1 + e, t->y0 - e, t->x0 - e, t->y0 - e, L, st, L - 1, dx, rho,
                               mass, h, flags, err))
    return -1;
  /* unstaggered, the side walls lie on the fluid's rows, y0 + (j + 1/2) dx for the ny rows of
   * the tank's height (a 3-D tank's lattice), dx apart: run from the first row to the top
   * itself, a wall of H/dx - 1/2 spacings took H/dx or H/dx - 1 of them as rounding fell, 0.6-1.7
   * % closer or farther apart than the fluid's rows, and pulled the still water beside it toward
   * the wall (0.9 m/s^2 at mid-depth in a tank 0.15 m high at dx = 2.5 mm). Staggered layers
   * (dx/2 apart, off the fluid's lattice) still run to the top: on them (tests/test_walls, dx = 5
   * mm) the rows dx apart moved the still water's largest speed after 0.1 s from 0.55 to 0.68 %
   * of (g H)^1/2 on dynamic walls and from 5.5 to 9.7 % on a repulsive one */
  const long ny = (long)floor((t->y1 - t->y0) / dx + 0.5);
  /* (at least two rows: a side wall of one point has no direction) */
  const double top = st ? t->y1 : t->y0 + ((double)(ny > 1 ? ny : 2) - 0.5) * dx;
  /* left wall, upwards (left normal points to -x) */
  if (sph_boundary_add_segment(p, t->x0 - e, t->y0 + e, t->x0 - e, top, L, st, 0, dx, rho, mass, h,
                               flags, err))
    return -1;
  /* right wall, downwards (left normal points to +x) */
  if (sph_boundary_add_segment(p, t->x1 + e, top, t->x1 + e, t->y0 + e, L, st, 0, dx, rho, mass, h,
                               flags, err))
    return -1;
  /* the lid, left to right (left normal points up, outwards), over the side walls' layers as
   * the floor is under them; unstaggered its first layer the row over the side walls' last, as
   * a 3-D tank's lattice continued (dx/2 over the top where the height is a whole number of dx),
   * staggered dx/2 over the top */
  const double lid = st ? t->y1 + e : top + dx;
  if (t->lid && sph_boundary_add_segment(p, t->x0 - e, lid, t->x1 + e, lid, L, st, L - 1, dx, rho,
                                         mass, h, flags, err))
    return -1;
  return 0;
}
#endif

/* ---- mirror particles ------------------------------------------------------------ */

/* Positions along a line are s = (r - P).t with the tangent t = (ny, -nx). */
size_t sph_mirror_tank_lines(const sph_tank *t, double reach, sph_mirror_line out[4]) {
  const double w = t->x1 - t->x0, hgt = t->y1 - t->y0;
  out[0] = (sph_mirror_line){t->x0, t->y0, 0.0, 1.0, -reach, w + reach};    /* floor, t = +x */
  out[1] = (sph_mirror_line){t->x0, t->y0, 1.0, 0.0, -hgt - reach, reach};  /* left, t = -y */
  out[2] = (sph_mirror_line){t->x1, t->y0, -1.0, 0.0, -reach, hgt + reach}; /* right, t = +y */
  if (!t->lid) return 3;
  out[3] = (sph_mirror_line){t->x0, t->y1, 0.0, -1.0, -w - reach, reach}; /* lid, t = -x */
  return 4;
}

sph_mirror_line sph_mirror_segment_line(double ax, double ay, double bx, double by) {
  const double lx = bx - ax, ly = by - ay, len = sqrt(lx * lx + ly * ly);
  /* the fluid is on the right of A -> B, as for particle walls (whose layers
   * go to the left): normal (ly, -lx)/len; tangent (-lx, -ly)/len, so
   * s = 0 at A and -len at B */
  return (sph_mirror_line){ax, ay, ly / len, -lx / len, -len, 0.0};
}

/* An image's id: a function of its particle's id and of the lines or
 * planes it is reflected in (slot: a line's index; 64 + 64 A + B for the
 * corner of lines A and B; in 3-D the set of planes as a bit mask), above
 * every particle's own id, so that the grid's sort (cell, then id: grid.h)
 * places it where the storage order of its particle cannot move it. */
#define SPH_IMAGE_ID_BASE ((int64_t)1 << 40)
#define SPH_IMAGE_SLOTS 8192
static inline int64_t image_id(const sph_particles *p, size_t i, int slot) {
  return SPH_IMAGE_ID_BASE + p->id[i] * SPH_IMAGE_SLOTS + slot;
}

/* The image of fluid particle i at x with the id `id` (image_id): its
 * velocity reflected in the line(s) or plane(s), v, and its no-slip
 * velocity -v_i in velh; its density, and pressure, never below rho0 and 0. */
static long add_image(sph_particles *p, size_t i, const double x[SPH_DIM], const double v[SPH_DIM],
                      double rho0, int64_t id, sph_error *err) {
  const int tension = p->rho[i] < rho0;
  const long k = sph_particles_add_at(p, x, v, tension ? rho0 : p->rho[i], p->mass[i], p->h[i],
                                      SPH_KIND_MIRROR, err);
  if (k < 0) return k;
  p->id[k] = id;
  p->flags[k] = p->flags[i] & SPH_FLAG_GHOST; /* a ghost's image: a ghost (solver/ranks.c) */
  p->p[k] = tension ? 0.0 : p->p[i];
  for (int a = 0; a < SPH_DIM; a++)
    p->velh[a][k] = -p->vel[a][i];
  return k;
}

#if SPH_DIM == 2

/* v reflected in the line with unit normal (nx, ny). */
static void reflect_velocity(double nx, double ny, double *vx, double *vy) {
  const double vn = *vx * nx + *vy * ny;
  *vx -= 2.0 * vn * nx;
  *vy -= 2.0 * vn * ny;
}
#endif

long sph_mirror_add(sph_particles *p, const sph_mirror_line *lines, size_t n_lines, double reach,
                    double rho0, sph_error *err) {
#if SPH_DIM == 3
  (void)p, (void)lines, (void)n_lines, (void)reach, (void)rho0;
  return sph_error_set(err, "mirror walls are 2-D only so far");
#else
  const size_t n = p->n;
  long added = 0;
  sph_particles_use(p, SPH_ARRAYS_HALF_STEP); /* the images' no-slip velocity */
  for (size_t i = 0; i < n; i++) {
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    int near[SPH_MIRROR_MAX_LINES], nn = 0;
    for (size_t l = 0; l < n_lines && l < SPH_MIRROR_MAX_LINES; l++) {
      const sph_mirror_line *L = &lines[l];
      const double rx = p->x[i] - L->px, ry = p->y[i] - L->py;
      const double d = rx * L->nx + ry * L->ny;
      const double s = rx * L->ny - ry * L->nx;
      if (d < 0.0 || d >= reach || s < L->t0 || s > L->t1) continue;
      near[nn++] = (int)l;
      double vx = p->vx[i], vy = p->vy[i];
      reflect_velocity(L->nx, L->ny, &vx, &vy);
      const double at[2] = {p->x[i] - 2.0 * d * L->nx, p->y[i] - 2.0 * d * L->ny}, v[2] = {vx, vy};
      if (add_image(p, i, at, v, rho0, image_id(p, i, (int)l), err) < 0) return -1;
      added++;
    }
    for (int a = 0; a < nn; a++) /* corners: the image through two perpendicular lines */
      for (int b = a + 1; b < nn; b++) {
        const sph_mirror_line *A = &lines[near[a]], *B = &lines[near[b]];
        if (A->nx * B->nx + A->ny * B->ny != 0.0) continue;
        const double da = (p->x[i] - A->px) * A->nx + (p->y[i] - A->py) * A->ny;
        const double db = (p->x[i] - B->px) * B->nx + (p->y[i] - B->py) * B->ny;
        const double x = p->x[i] - 2.0 * da * A->nx - 2.0 * db * B->nx;
        const double y = p->y[i] - 2.0 * da * A->ny - 2.0 * db * B->ny;
        double vx = p->vx[i], vy = p->vy[i];
        reflect_velocity(A->nx, A->ny, &vx, &vy);
        reflect_velocity(B->nx, B->ny, &vx, &vy);
        const double at[2] = {x, y}, v[2] = {vx, vy};
        if (add_image(p, i, at, v, rho0, image_id(p, i, 64 + 64 * near[a] + near[b]), err) < 0)
          return -1;
        added++;
      }
  }
  return added;
#endif
}

#if SPH_DIM == 3
size_t sph_tank_planes(const sph_tank *t, double reach, sph_wall_plane out[6]) {
  const double lo[3] = {t->x0, t->y0, t->z0}, hi[3] = {t->x1, t->y1, t->z1};
  size_t n = 0;
  for (int a = 0; a < 3; a++) {
    if (t->open_along == 1 + a) continue;
    for (int side = 0; side < (a == 2 && !t->lid ? 1 : 2); side++) { /* a lid if it has one */
      sph_wall_plane *f = &out[n++];
      f->axis = a;
      f->dir = side ? -1 : 1;
      f->at = side ? hi[a] : lo[a];
      for (int b = 0; b < 3; b++) {
        const double grow = b == a || t->open_along == 1 + b ? 0.0 : reach;
        f->lo[b] = lo[b] - grow, f->hi[b] = hi[b] + grow;
      }
    }
  }
  return n;
}

long sph_mirror_add_planes(sph_particles *p, const sph_wall_plane *planes, size_t n_planes,
                           double reach, double rho0, sph_error *err) {
  const size_t n = p->n;
  long added = 0;
  sph_particles_use(p, SPH_ARRAYS_HALF_STEP); /* the images' no-slip velocity */
  for (size_t i = 0; i < n; i++) {
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    int near[5], nn = 0;
    double dist[5];
    for (size_t l = 0; l < n_planes && l < 5; l++) {
      const sph_wall_plane *f = &planes[l];
      const double d = (p->pos[f->axis][i] - f->at) * (double)f->dir;
      if (d < 0.0 || d >= reach) continue;
      int within = 1;
      for (int b = 0; b < 3; b++)
        if (b != f->axis && (p->pos[b][i] < f->lo[b] || p->pos[b][i] > f->hi[b])) within = 0;
      if (!within) continue;
      near[nn] = (int)l;
      dist[nn++] = d;
    }
    /* every non-empty set of the near planes with distinct axes: through one
     * face, an edge (two), a corner (three) */
    for (unsigned mask = 1; mask < 1u << nn; mask++) {
      double x[3], v[3];
      unsigned axes = 0;
      int ok = 1;
      for (int a = 0; a < 3; a++)
        x[a] = p->pos[a][i], v[a] = p->vel[a][i];
      for (int k = 0; k < nn && ok; k++) {
        if (!(mask >> k & 1u)) continue;
        const sph_wall_plane *f = &planes[near[k]];
        if (axes >> f->axis & 1u) ok = 0;
        axes |= 1u << f->axis;
        x[f->axis] -= 2.0 * dist[k] * (double)f->dir;
        v[f->axis] = -v[f->axis];
      }
      if (!ok) continue;
      unsigned planes_hit = 0; /* the set of planes, by their index */
      for (int k = 0; k < nn; k++)
        if (mask >> k & 1u) planes_hit |= 1u << near[k];
      if (add_image(p, i, x, v, rho0, image_id(p, i, (int)planes_hit), err) < 0) return -1;
      added++;
    }
  }
  return added;
}
#endif

void sph_mirror_remove(sph_particles *p, size_t *perm, void *work) {
  size_t kept = 0;
  for (size_t i = 0; i < p->n; i++)
    if (p->kind[i] != SPH_KIND_MIRROR) perm[kept++] = i;
  if (kept == p->n) return;
  p->n = kept;
  sph_particles_permute(p, perm, work);
}
