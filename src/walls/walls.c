/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * walls.c - the walls of a run (see walls.h). Wall particles are appended
 * to the store in the order tank, then segments, so their ids (and so the
 * bits of every later sum) depend only on the case.
 */
#include "config.h"

#include <math.h>
#include <stdlib.h>

#include "core/exact_sum.h"
#include "core/parallel.h"

#include "walls/walls.h"

#include "walls/motion.h"

/* An adami wall's free slip is AHA12's (no viscous pair term, adami.h), not the normal part
 * of the other models' forces (SPH_FLAG_FREE_SLIP). */
static uint8_t wall_flags(sph_boundary_kind b, int extrapolated, int free_slip) {
  if (b == SPH_BOUNDARY_ADAMI)
    return (uint8_t)(SPH_FLAG_ADAMI | (free_slip ? SPH_FLAG_INVISCID : 0));
  return (uint8_t)((b == SPH_BOUNDARY_REPULSIVE ? SPH_FLAG_REPULSIVE : 0) |
                   (b == SPH_BOUNDARY_MDBC ? SPH_FLAG_MDBC : 0) |
                   (extrapolated ? SPH_FLAG_NO_SLIP : 0) | (free_slip ? SPH_FLAG_FREE_SLIP : 0));
}

/* Dynamic particles and Morris' fixed layers: density from continuity,
 * bounded by dbc.h. */
static int is_dbc(sph_boundary_kind b) {
  return b == SPH_BOUNDARY_DYNAMIC || b == SPH_BOUNDARY_FIXED_LAYERS;
}

/* Drops the particles [first, p->n) that lie closer than dx/2 to one of
 * [from, first), the walls made before (issue 39, D7: crossing walls made
 * pairs 0.1 dx apart); the others move down, their ids their new indices.
 * Returns how many were dropped, or -1 out of memory. Only the earlier
 * particles inside the new ones' box, widened by dx/2, are compared. */
/* drop_overlaps' test: particle i closer than sqrt(d2) to one of near[0 .. m - 1]. */
typedef struct overlap {
  const size_t *near;
  size_t m;
  double d2;
} overlap;
static int overlaps(const void *ctx, const sph_particles *p, size_t i) {
  const overlap *o = ctx;
  for (size_t k = 0; k < o->m; k++) {
    const double ex = p->x[i] - p->x[o->near[k]], ey = p->y[i] - p->y[o->near[k]];
    SPH_IF3(const double ez = p->z[i] - p->z[o->near[k]];)
    if (SPH_NORM2(ex, ey, ez) < o->d2) return 1;
  }
  return 0;
}

static long drop_overlaps(sph_particles *p, size_t from, size_t first, double dx) {
  const double d = 0.5 * dx, d2 = d * d;
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  SPH_IF3(double z0 = INFINITY, z1 = -INFINITY;)
  for (size_t i = first; i < p->n; i++) {
    x0 = fmin(x0, p->x[i] - d), x1 = fmax(x1, p->x[i] + d);
    y0 = fmin(y0, p->y[i] - d), y1 = fmax(y1, p->y[i] + d);
    SPH_IF3(z0 = fmin(z0, p->z[i] - d), z1 = fmax(z1, p->z[i] + d);)
  }
#define IN_BOX(j)                                                                                  \
  (p->x[j] >= x0 && p->x[j] <= x1 && p->y[j] >= y0 &&                                              \
   p->y[j] <= y1 SPH_IF3(&&p->z[j] >= z0 && p->z[j] <= z1))
  size_t m = 0;
  for (size_t j = from; j < first; j++)
    m += IN_BOX(j);
  if (m == 0) return 0;
  size_t *near_box = malloc(m * sizeof *near_box);
  if (!near_box) return -1;
  m = 0;
  for (size_t j = from; j < first; j++)
    if (IN_BOX(j)) near_box[m++] = j;
#undef IN_BOX
  const overlap o = {near_box, m, d2};
  const long dropped = (long)sph_particles_drop_if(p, first, overlaps, &o);
  free(near_box);
  return dropped;
}

/* The tank's faces reach into its corners by the wall's thickness: the floor past both side
 * walls, the side walls below the floor (not above their top, where fluid is outside the tank),
 * so that a particle that crossed two faces within a step, into the wall's corner, is kept off
 * both; with the faces ending at the corners it was kept off neither (an adami guard at the face
 * let particle 0 of the Martin & Moyce dam break at a/100 through the back wall's corner, and
 * out of the domain, at t = 0.457 s). */
static void corners(sph_walls *w, const sph_tank *tank) {
  const double r = w->face_reach;
#if SPH_DIM == 2
  (void)tank;
  /* sph_mirror_tank_lines: the floor (t = +x), the left wall (t = -y), the right (t = +y), the
   * lid (t = -x) */
  if (w->n_face < 3) return;
  w->face[0].t0 -= r;
  w->face[0].t1 += r;
  w->face[1].t1 += r;
  w->face[2].t0 -= r;
  if (w->n_face < 4) return;
  w->face[1].t0 -= r, w->face[2].t1 += r; /* (the side walls up into the lid's corners) */
  w->face[3].t0 -= r, w->face[3].t1 += r;
#else
  for (size_t l = 0; l < w->n_plane; l++) {
    sph_wall_plane *f = &w->plane[l];
    for (int b = 0; b < 3; b++) {
      if (b == f->axis || tank->open_along == 1 + b) continue; /* (a periodic axis: no corner) */
      f->lo[b] -= r;
      if (b != SPH_UP || tank->lid) f->hi[b] += r;
    }
  }
#endif
}

int sph_walls_create(sph_walls *w, sph_particles *p, const sph_tank *tank,
                     const sph_wall_segment *segments, size_t n_segments,
                     const sph_obstacle *obstacles, size_t n_obstacles, double dx, double rho0,
                     double h, double mirror_reach, sph_error *err) {
  const double wall_mass = sph_lattice_mass(rho0, dx);
  const size_t walls_from = p->n; /* the fluid's particles come first */
  *w = (sph_walls){0};
  w->mirror_reach = mirror_reach;
  w->segments = segments;
  w->n_segments = n_segments;
  w->no_slip = tank->present && tank->extrapolated;
  w->free_slip = tank->present && tank->free_slip && tank->boundary != SPH_BOUNDARY_ADAMI;
  for (size_t k = 0; k < n_segments; k++) {
    w->no_slip |= segments[k].extrapolated;
    w->free_slip |= segments[k].free_slip && segments[k].boundary != SPH_BOUNDARY_ADAMI;
  }
  if (tank->present) {
    if (tank->boundary == SPH_BOUNDARY_MIRROR) {
#if SPH_DIM == 2
      w->n_mirror += sph_mirror_tank_lines(tank, mirror_reach, w->mirror);
#else /* mirror planes, kept off as the faces of a particle tank are */
      w->n_plane = sph_tank_planes(tank, mirror_reach, w->plane);
      w->n_mirror = w->n_plane;
      w->face_reach = mirror_reach;
#endif
    } else {
      if (sph_boundary_add_tank(p, tank, dx, rho0, wall_mass, h,
                                wall_flags(tank->boundary, tank->extrapolated, tank->free_slip),
                                err))
        return -1;
        /* the faces, along their length only: fluid above a side wall's top
         * is outside the tank */
#if SPH_DIM == 2
      w->n_face = sph_mirror_tank_lines(tank, 0.0, w->face);
      w->face_reach = (tank->stagger ? 0.5 : 1.0) * dx * (double)tank->layers;
#else /* (a 3-D tank's layers are dx apart) */
      w->n_plane = sph_tank_planes(tank, 0.0, w->plane);
      w->face_reach = dx * (double)tank->layers;
#endif
      corners(w, tank);
    }
    if (tank->boundary == SPH_BOUNDARY_REPULSIVE) w->repulsive = 1;
    if (tank->boundary == SPH_BOUNDARY_MDBC) w->mdbc = 1;
    if (tank->boundary == SPH_BOUNDARY_ADAMI) w->adami = w->adami_tank = 1;
    if (is_dbc(tank->boundary)) w->dbc = 1;
  }
  for (size_t k = 0; k < n_segments; k++) {
    const sph_wall_segment *ws = &segments[k];
    if (ws->boundary == SPH_BOUNDARY_MIRROR) {
      if (SPH_DIM == 3) return sph_error_set(err, "mirror wall segments are 2-D only so far");
      if (w->n_mirror == SPH_MIRROR_MAX_LINES)
        return sph_error_set(err, "more than %zu mirror walls", w->n_mirror);
      w->mirror[w->n_mirror++] = sph_mirror_segment_line(ws->x0, ws->y0, ws->x1, ws->y1);
      continue;
    }
    if (ws->boundary == SPH_BOUNDARY_REPULSIVE) w->repulsive = 1;
    if (ws->boundary == SPH_BOUNDARY_MDBC) w->mdbc = 1;
    if (ws->boundary == SPH_BOUNDARY_ADAMI) w->adami = 1;
    if (is_dbc(ws->boundary)) w->dbc = 1;
    const size_t first = p->n;
    const uint8_t flags = wall_flags(ws->boundary, ws->extrapolated, ws->free_slip);
#if SPH_DIM == 2
    if (sph_boundary_add_segment(p, ws->x0, ws->y0, ws->x1, ws->y1, ws->layers, ws->stagger, 0, dx,
                                 rho0, wall_mass, h, flags, err))
      return -1;
#else
    if (sph_boundary_add_plate(p, ws, dx, rho0, wall_mass, h, flags, err)) return -1;
#endif
    const long dropped = drop_overlaps(p, walls_from, first, dx);
    if (dropped < 0) return sph_error_set(err, "out of memory");
    w->n_dropped += (size_t)dropped;
    if (ws->motion.kind != SPH_MOTION_NONE) {
      w->moving = 1;
      sph_particles_use(p, SPH_ARRAYS_REST);
      for (size_t i = first; i < p->n; i++)
        p->body[i] = (int32_t)k;
    }
  }
  w->obstacles = obstacles;
  w->n_obstacles = n_obstacles;
  w->obstacle_floor = tank->present ? tank->lo[SPH_UP] + 0.5 * dx : -INFINITY;
  for (size_t k = 0; k < n_obstacles; k++) { /* boxes: any but mirror walls (the reader) */
    const sph_obstacle *o = &obstacles[k];
    if (is_dbc(o->boundary)) w->dbc = 1;
    if (o->boundary == SPH_BOUNDARY_MDBC) w->mdbc = 1;
    if (o->boundary == SPH_BOUNDARY_ADAMI) w->adami = 1;
    if (o->boundary == SPH_BOUNDARY_REPULSIVE) w->repulsive = 1;
    const size_t first = p->n;
    if (sph_boundary_add_box(p, o, w->obstacle_floor, dx, rho0, wall_mass, h,
                             wall_flags(o->boundary, 0, 0), err))
      return -1;
    const long dropped = drop_overlaps(p, walls_from, first, dx);
    if (dropped < 0) return sph_error_set(err, "out of memory");
    w->n_dropped += (size_t)dropped;
  }
  return 0;
}

void sph_walls_move(const sph_walls *w, sph_particles *p, double t) {
  if (!w->moving) return;
  for (size_t i = 0; i < p->n; i++) {
    if (p->body[i] < 0) continue;
    double r[SPH_DIM], x[SPH_DIM], v[SPH_DIM];
    for (int a = 0; a < SPH_DIM; a++)
      r[a] = p->rest[a][i];
    sph_motion_point(&w->segments[p->body[i]].motion, t, r, x, v);
    for (int a = 0; a < SPH_DIM; a++) {
      p->pos[a][i] = x[a];
      p->vel[a][i] = v[a];
    }
  }
}

/* ---- keeping the fluid off: box obstacles (both dimensions), the 2-D
 * build's lines, the 3-D build's planes ---- */

/* The guard's distance for a tank face and for obstacle o: d_min, but 0 (the face itself) for
 * adami walls (walls.h). */
static inline double tank_guard(const sph_walls *w, double d_min) {
  return w->adami_tank ? 0.0 : d_min;
}
static inline double box_guard(const sph_obstacle *o, double d_min) {
  return o->boundary == SPH_BOUNDARY_ADAMI ? 0.0 : d_min;
}

/* Whether particle i lies inside obstacle o grown by d_min (a box; a shaped obstacle has no
 * guard, sph_obstacle). */
static inline int in_box(const sph_obstacle *o, const sph_particles *p, size_t i, double d_min) {
  if (o->inside) return 0;
  for (int a = 0; a < SPH_DIM; a++)
    if (!(p->pos[a][i] > o->lo[a] - d_min && p->pos[a][i] < o->hi[a] + d_min)) return 0;
  return 1;
}

/* Moves particle i to distance 2 d_min - d in front of the plane normal to
 * axis a (normal dir, d its distance in front now), turns its normal
 * velocity (and half-step velocity) into the fluid, adds to kick. */
static void reflect_along(sph_particles *p, size_t i, int a, int dir, double d, double d_min,
                          int half_step, double *kick) {
  const double shift = 2.0 * (d_min - d) * (double)dir, m = p->mass[i];
  p->pos[a][i] += shift;
  if (kick) kick[a] += m * shift;
  const double vn = p->vel[a][i] * (double)dir;
  if (vn < 0.0) {
    p->vel[a][i] -= 2.0 * vn * (double)dir;
    if (kick) kick[SPH_DIM + a] -= m * 2.0 * vn * (double)dir;
  }
  if (half_step && p->velh[a][i] * (double)dir < 0.0) p->velh[a][i] = -p->velh[a][i];
}

/* The obstacles on particle i (a fluid one): out of each box grown by
 * d_min that it is inside, through the face it is nearest to (its
 * distance in front of each face, negative inside: the largest wins; a
 * bottom standing on the tank's floor is no way out). The number of
 * reflections. */
static size_t keep_off_boxes(const sph_walls *w, sph_particles *p, size_t i, double d_min,
                             int half_step, double *kick) {
  size_t moved = 0;
  for (size_t k = 0; k < w->n_obstacles; k++) {
    const sph_obstacle *o = &w->obstacles[k];
    const double dg = box_guard(o, d_min);
    if (!in_box(o, p, i, dg)) continue;
    int best_a = -1, best_dir = 0;
    double best = -INFINITY;
    for (int a = 0; a < SPH_DIM; a++)
      for (int dir = -1; dir <= 1; dir += 2) {
        const double face = dir < 0 ? o->lo[a] : o->hi[a];
        if (a == SPH_UP && dir < 0 && face <= w->obstacle_floor) continue; /* on the floor */
        const double d = (p->pos[a][i] - face) * (double)dir;
        if (d > best) best = d, best_a = a, best_dir = dir;
      }
    if (best_a < 0) continue;
    reflect_along(p, i, best_a, best_dir, best, dg, half_step, kick);
    moved++;
  }
  return moved;
}

#if SPH_DIM == 2
/* Whether (x, y) lies closer than d_min to the wall side of line L (or
 * behind it); reflect() then checks the reach and the segment's ends. */
static inline int closer(const sph_mirror_line *L, double x, double y, double d_min) {
  return (x - L->px) * L->nx + (y - L->py) * L->ny < d_min;
}

/* The reflection of particle i off line L (closer() holds) if it is not
 * beyond the reach behind it and within the segment; 1 if it was moved.
 * kick (if not NULL) gains its m dx, m dy, m dvx, m dvy. */

static int reflect(const sph_mirror_line *L, sph_particles *p, size_t i, double d_min, double reach,
                   int half_step, double *kick) {
  const double rx = p->x[i] - L->px, ry = p->y[i] - L->py;
  const double d = rx * L->nx + ry * L->ny;
  const double s = rx * L->ny - ry * L->nx;
  if (d <= -reach || s < L->t0 || s > L->t1) return 0;
  const double shift = 2.0 * (d_min - d), m = p->mass[i];
  p->x[i] += shift * L->nx;
  p->y[i] += shift * L->ny;
  const double vn = p->vx[i] * L->nx + p->vy[i] * L->ny;
  if (kick) {
    kick[0] += m * shift * L->nx;
    kick[1] += m * shift * L->ny;
  }
  if (vn < 0.0) {
    p->vx[i] -= 2.0 * vn * L->nx;
    p->vy[i] -= 2.0 * vn * L->ny;
    if (kick) {
      kick[2] -= m * 2.0 * vn * L->nx;
      kick[3] -= m * 2.0 * vn * L->ny;
    }
  }
  if (half_step) {
    const double hn = p->vxh[i] * L->nx + p->vyh[i] * L->ny;
    if (hn < 0.0) {
      p->vxh[i] -= 2.0 * hn * L->nx;
      p->vyh[i] -= 2.0 * hn * L->ny;
    }
  }
  return 1;
}

#else
/* Particle i's signed distance in front of plane f (negative: behind it). */
static inline double plane_distance(const sph_wall_plane *f, const sph_particles *p, size_t i) {
  return (p->pos[f->axis][i] - f->at) * (double)f->dir;
}
#endif

/* Whether fluid particle i is near a wall it may have to be kept off. */
static inline int near_any(const sph_walls *w, const sph_particles *p, size_t i, double d_min) {
  int any = 0;
#if SPH_DIM == 2
  for (size_t l = 0; l < w->n_mirror; l++)
    any |= closer(&w->mirror[l], p->x[i], p->y[i], d_min);
  for (size_t l = 0; l < w->n_face; l++)
    any |= closer(&w->face[l], p->x[i], p->y[i], tank_guard(w, d_min));
#else
  for (size_t l = 0; l < w->n_plane; l++)
    any |= plane_distance(&w->plane[l], p, i) < (w->n_mirror ? d_min : tank_guard(w, d_min));
#endif
  for (size_t k = 0; k < w->n_obstacles; k++)
    any |= in_box(&w->obstacles[k], p, i, box_guard(&w->obstacles[k], d_min));
  return any;
}

/* Every wall on fluid particle i, in a fixed order (the mirror lines, the
 * tank's faces, the obstacles); the number of reflections. */
static size_t keep_off_one(const sph_walls *w, sph_particles *p, size_t i, double d_min,
                           int half_step, double *kick) {
  size_t moved = 0;
#if SPH_DIM == 2
  /* the distance test inline; the rare reflection out of line */
  for (size_t l = 0; l < w->n_mirror; l++)
    if (closer(&w->mirror[l], p->x[i], p->y[i], d_min))
      moved += (size_t)reflect(&w->mirror[l], p, i, d_min, w->mirror_reach, half_step, kick);
  const double df = tank_guard(w, d_min);
  for (size_t l = 0; l < w->n_face; l++)
    if (closer(&w->face[l], p->x[i], p->y[i], df))
      moved += (size_t)reflect(&w->face[l], p, i, df, w->face_reach, half_step, kick);
#else
  /* (a mirror tank's planes are its mirror planes: d_min) */
  const double df = w->n_mirror ? d_min : tank_guard(w, d_min);
  for (size_t l = 0; l < w->n_plane; l++) {
    const sph_wall_plane *f = &w->plane[l];
    const double d = plane_distance(f, p, i);
    if (!(d < df) || d <= -w->face_reach) continue;
    int within = 1; /* on the face's span along the other axes */
    for (int b = 0; b < 3; b++)
      if (b != f->axis && (p->pos[b][i] < f->lo[b] || p->pos[b][i] > f->hi[b])) within = 0;
    if (!within) continue;
    reflect_along(p, i, f->axis, f->dir, d, df, half_step, kick);
    moved++;
  }
#endif
  return moved + keep_off_boxes(w, p, i, d_min, half_step, kick);
}

size_t sph_walls_keep_off(const sph_walls *w, sph_particles *p, double d_min, int half_step,
                          double kick[2 * SPH_DIM]) {
  size_t moved = 0;
#if SPH_DIM == 2
  if (w->n_mirror == 0 && w->n_face == 0 && w->n_obstacles == 0) return 0;
#else
  if (w->n_plane == 0 && w->n_obstacles == 0) return 0;
#endif
  /* First, in parallel, whether any fluid particle stands near a wall: at
   * most steps none does, and then nothing moves. A particle near no wall
   * keeps its position through the loop below (it reflects off none), so
   * the loop, serial in index order with the kick's sums in that order,
   * runs only when it has something to do. */
  const long n = (long)p->n;
  int any = 0;
#pragma omp parallel for schedule(static) reduction(| : any) if (n > SPH_OMP_MIN)
  for (long li = 0; li < n; li++) {
    const size_t i = (size_t)li;
    if (p->kind[i] == SPH_KIND_FLUID) any |= near_any(w, p, i, d_min);
  }
  if (!any) return 0;
  /* each particle's kick on its own, the sums over particles exact
   * (exact_sum.h): the same bits in any order */
  sph_xsum sum[2 * SPH_DIM];
  for (int c = 0; c < 2 * SPH_DIM; c++)
    sph_xsum_init(&sum[c]);
  for (size_t i = 0; i < p->n; i++) {
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    double one[2 * SPH_DIM] = {0.0};
    const size_t m = keep_off_one(w, p, i, d_min, half_step, kick ? one : NULL);
    moved += m;
    if (m && kick)
      for (int c = 0; c < 2 * SPH_DIM; c++)
        sph_xsum_add(&sum[c], one[c]);
  }
  if (kick)
    for (int c = 0; c < 2 * SPH_DIM; c++)
      kick[c] += sph_xsum_round(&sum[c]);
  return moved;
}
