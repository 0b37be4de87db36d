/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * setup.c - making a simulation from a case (sph_sim_create) and freeing
 * it.
 *
 * Fluid blocks are filled on the lattice x0 + (i + 1/2) dx (with the
 * block's seeded jitter, if any); walls come from src/walls/. With a
 * hydrostatic start the density of a fluid particle is the Tait density
 * of p = rho0 |g| (surface - y), and a wall particle within 2h of a
 * block's x-range gets the same law for that block's surface, so walls
 * hold the column up from the first step. Every particle has mass
 * rho0 dx^2 and smoothing length h = h_factor dx. The boxes (the view, the
 * domain whose leaving is a blow-up, the floor of the front measure) are
 * fixed here, and the first interaction pass gives the initial rates.
 */
#include "config.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "case/domain.h"
#include "case/shape.h"
#include "physics/eos.h"
#include "physics/kernel.h"
#include "solver/diffusion.h"
#include "solver/procs.h"
#include "solver/sim_internal.h"

static double sph_skin_fraction(void) {
  const char *e = getenv("SPH_TEST_SKIN");
  if (e && *e) return atof(e);
  return SPH_SKIN_DEFAULT;
}

/* SPH_TEST_SHUFFLE=SEED (doc/testing.md): the store in a random order
 * before the first sort, a permutation drawn from SEED (a 64-bit LCG,
 * Fisher-Yates). The first sort puts every particle where its position and
 * id say (grid.h), so the run's every output is the unshuffled run's: the
 * test that the summation order does not depend on the storage order. */
static int shuffle_store(sph_particles *p, sph_error *err) {
  const char *e = getenv("SPH_TEST_SHUFFLE");
  if (!e || !*e || p->n < 2) return 0;
  uint64_t r = strtoull(e, NULL, 10) * 2862933555777941757ull + 3037000493ull;
  size_t *perm = malloc(p->n * sizeof *perm);
  void *work = malloc(p->n * 8);
  if (!perm || !work) {
    free(perm);
    free(work);
    return sph_error_set(err, "out of memory");
  }
  for (size_t i = 0; i < p->n; i++)
    perm[i] = i;
  for (size_t i = p->n - 1; i > 0; i--) {
    r = r * 6364136223846793005ull + 1442695040888963407ull;
    const size_t k = (size_t)((r >> 11) % (uint64_t)(i + 1));
    const size_t t = perm[i];
    perm[i] = perm[k], perm[k] = t;
  }
  sph_particles_permute(p, perm, work);
  free(perm);
  free(work);
  return 0;
}

/* Whether the wall particles' neighbour rows may hold their fluid
 * neighbours only (grid.h, wall_fluid_only): where every wall-wall pair
 * adds +-0 to every sum a wall row feeds. A wall row sums the continuity
 * (v_ij = 0 between walls at rest), the step rule's sigma (v_ij . r_ij =
 * 0) and the density diffusion (a wall neighbour's diffusing mass is 0 in
 * a wall row: interact_row.h), with the ledger its heat (of its pairs
 * with fluid only), and the density bound looks for fluid neighbours only
 * (dbc.c); mdbc walls take their density from their mirror points, on a
 * grid of their own (wall_velocity.c), and of the walls' rows only the
 * fluid entries are read as meeting a wall (forces.c, nwall). Not so, and
 * so every neighbour listed, with moving walls or mirror particles
 * (sigma), the strain-rate pass and the corrected gradients (a wall
 * particle's sums over its walls), no-slip and free-slip walls (their
 * velocities and normal parts), repulsive walls, Antuono's diffusion (its
 * c_i) and the density filters (which may filter walls). 3-D only: in
 * 2-D the shorter rows would move the lanes' sums of wall rows, and the
 * golden files with them (a 2-D row is short: doc/memory.md). */
static int wall_rows_fluid_only(const sph_sim *s) {
  const sph_force_params *fp = &s->fp;
  return SPH_DIM == 3 && !fp->moving_walls && !fp->mirror && !fp->sps &&
         fp->viscosity != SPH_VISCOSITY_STRESS_TENSOR && !fp->gradient_correction &&
         !fp->corrected_gradient && !fp->no_slip && !fp->free_slip && !fp->repulsive &&
         fp->diffusion != SPH_DIFFUSION_ANTUONO && s->c->density_filter == SPH_FILTER_NONE;
}

/* The interaction loop: the default, or the one the test hook
 * SPH_TEST_LANES names (portable, avx, avx512 or scalar; doc/testing.md), for the
 * tests that compare the loops through whole runs. */
static sph_force_loop sph_test_loop(void) {
  const char *e = getenv("SPH_TEST_LANES");
  if (!e) return SPH_LOOP_AUTO;
  if (strcmp(e, "portable") == 0) return SPH_LOOP_LANES;
  if (strcmp(e, "avx") == 0) return SPH_LOOP_LANES_AVX;
  if (strcmp(e, "avx512") == 0) return SPH_LOOP_LANES_AVX512;
  if (strcmp(e, "scalar") == 0) return SPH_LOOP_SCALAR;
  return SPH_LOOP_AUTO;
}

/* A counter-based generator (the splitmix64 finaliser applied to the
 * seed, block and lattice indices in turn): each particle's draw depends
 * on its own indices only, never on the order particles are made in. */
static uint64_t mix64(uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/* Adds the block's seeded jitter (if any) to the lattice position x of
 * its particle (i, j) (i, j, k in 3-D); block is the block's index in the
 * case. The draw depends only on (seed, block, k, j, i), so it is the same on
 * every run and platform and for any creation order. */
static void fluid_jitter(const sph_fluid_block *fb, size_t block, long i, long j, long k, double dx,
                         double x[SPH_DIM]) {
  if (!(fb->jitter > 0.0)) return;
  uint64_t h = mix64((uint64_t)(uint32_t)fb->seed);
  h = mix64(h ^ (uint64_t)block);
  if (SPH_DIM == 3) h = mix64(h ^ (uint64_t)k);
  h = mix64(h ^ (uint64_t)j);
  h = mix64(h ^ (uint64_t)i);
  uint64_t draw = h;
  for (int d = 0; d < SPH_DIM; d++) {
    x[d] += fb->jitter * dx * (2.0 * ((double)(draw >> 11) * 0x1.0p-53) - 1.0);
    draw = mix64(draw);
  }
}

/* The downward component of gravity (0 if it points up): the weight of a
 * hydrostatic start. */
static double gravity_down(const sph_case *c) {
  return -c->gravity[SPH_UP] > 0.0 ? -c->gravity[SPH_UP] : 0.0;
}

/* A shaped block's lattice point x inside an earlier block, or a box block's inside a later
 * shaped one: the two would put particles in the same place (twice the mass there). The reader
 * refuses boxes that overlap (geometry.c); shapes are seen here, point by point. */
static int shaped_overlap(const sph_case *c, size_t b, const double x[SPH_DIM], sph_error *err) {
  for (size_t k = 0; k < c->n_fluid; k++) {
    if (k == b || !sph_shape_inside(&c->fluid[k], x)) continue;
    const size_t first = k < b ? k : b, second = k < b ? b : k;
    char line[32] = "";
    if (c->fluid[second].line) snprintf(line, sizeof line, ":%zu", c->fluid[second].line);
    return sph_error_set(err,
                         "%s%s: geometry.fluid[%zu]: expected a block apart from "
                         "geometry.fluid[%zu], got one that overlaps it at (%g, %g" SPH_IF3(
                             ", %g") ") (their particles would overlap)",
                         c->path ? c->path : "the case", line, second, first, x[0],
                         x[1] SPH_IF3(, x[2]));
  }
  return 0;
}

/* The lattice points lo + (i + 1/2) dx of the box lo..hi along each axis (1 along an axis the
 * dimension lacks), and the point of indices idx. */
static void lattice_size(const double *lo, const double *hi, double dx, long n[3]) {
  n[0] = n[1] = n[2] = 1;
  for (int a = 0; a < SPH_DIM; a++)
    n[a] = sph_case_lattice_points(lo[a], hi[a], dx);
}
static void lattice_at(const double *lo, const long idx[3], double dx, double x[SPH_DIM]) {
  for (int a = 0; a < SPH_DIM; a++)
    x[a] = lo[a] + ((double)idx[a] + 0.5) * dx;
}

/* The weight of the air over a block's surface (two phases, physics.air):
 * the air filling the tank up to its top, at rest; 0 without air. */
static double air_head(const sph_case *c, double surface) {
  return c->air ? c->air_material.rho0 * gravity_down(c) * (c->tank.hi[SPH_UP] - surface) : 0.0;
}

static int add_fluid(sph_sim *s, sph_error *err) {
  const sph_case *c = s->c;
  const double dx = c->dx, mass = sph_lattice_mass(c->rho0, dx);
  const double gmag = gravity_down(c);
  for (size_t b = 0; b < c->n_fluid; b++) {
    const sph_fluid_block *fb = &c->fluid[b];
    long n[3], off[3] = {0, 0, 0};
    const double *origin = fb->lo;
    lattice_size(fb->lo, fb->hi, dx, n);
    if (c->air) { /* the tank's lattice, which the air fills around the liquid (add_air): the
                   * points of it in the block's box and shape (a block whose box starts on it,
                   * the block's own lattice) */
      origin = c->tank.lo;
      for (int a = 0; a < SPH_DIM; a++) {
        off[a] = (long)ceil((fb->lo[a] - origin[a]) / dx - 0.5);
        n[a] = (long)floor((fb->hi[a] - origin[a]) / dx - 0.5) - off[a] + 1;
      }
    }
    for (long k = 0; k < n[2]; k++)
      for (long j = 0; j < n[1]; j++)
        for (long i = 0; i < n[0]; i++) {
          double x[SPH_DIM];
          lattice_at(origin, (const long[3]){off[0] + i, off[1] + j, off[2] + k}, dx, x);
          if (c->air && fb->shape.kind == SPH_SHAPE_BOX && !sph_shape_inside(fb, x)) continue;
          if (fb->shape.kind != SPH_SHAPE_BOX) {
            const int wn = sph_shape_winding_of(&fb->shape, x);
            if (wn == 0) continue;
            if (wn != 1)
              return sph_error_set(err,
                                   "%s:%zu: geometry.fluid[%zu].mesh: expected a surface that does "
                                   "not cross itself, got one that winds %d times around (%g, "
                                   "%g" SPH_IF3(", %g") ") (it crosses or overlaps itself there)",
                                   c->path ? c->path : "the case", fb->line, b, wn, x[0],
                                   x[1] SPH_IF3(, x[2]));
            if (shaped_overlap(c, b, x, err)) return -1;
          }
          fluid_jitter(fb, b, i, j, k, dx, x); /* perturbed start, if asked for */
          double rho = c->rho0;
          if (fb->hydrostatic) {
            double pw = c->rho0 * gmag * (fb->surface - x[SPH_UP]);
            if (c->air) pw += air_head(c, fb->surface);
            rho = sph_eos_density(&s->fp.eos, pw);
          }
          if (sph_particles_add_at(&s->p, x, fb->v, rho, mass, c->h, SPH_KIND_FLUID, err) < 0)
            return -1;
        }
  }
  return 0;
}

/* The air (two phases, physics.air; doc/case-files.md): a particle of
 * phase 1 at every point of the tank's lattice (lo + (i + 1/2) dx inside
 * the tank's inner box) that no fluid block holds (its box, or its shape),
 * at rest and hydrostatic under the air above it up to the tank's top;
 * the walls then clear it as they clear the liquid. */
static int add_air(sph_sim *s, sph_error *err) {
  const sph_case *c = s->c;
  if (!c->air) return 0;
  const sph_tank *t = &c->tank;
  const double dx = c->dx, mass = sph_lattice_mass(c->air_material.rho0, dx),
               gmag = gravity_down(c);
  const sph_eos *air = &s->fp.phase_eos[1];
  const double v[SPH_DIM] = {0.0};
  long n[3];
  lattice_size(t->lo, t->hi, dx, n);
  /* per lattice point: -1 where the liquid holds it, else how many of the liquid's points lie
   * above it in its column (the liquid's weight on the air there) */
  const size_t np = (size_t)n[0] * (size_t)n[1] * (size_t)n[2];
  long *above = malloc((np ? np : 1) * sizeof *above);
  if (!above) return sph_error_set(err, "out of memory: the air's lattice (%zu points)", np), -1;
#define AT(i, j, k) ((((size_t)(k) * (size_t)n[1]) + (size_t)(j)) * (size_t)n[0] + (size_t)(i))
  for (long k = 0; k < n[2]; k++)
    for (long j = 0; j < n[1]; j++)
      for (long i = 0; i < n[0]; i++) {
        double x[SPH_DIM];
        lattice_at(t->lo, (const long[3]){i, j, k}, dx, x);
        int liquid = 0;
        for (size_t b = 0; b < c->n_fluid && !liquid; b++)
          liquid = sph_shape_inside(&c->fluid[b], x);
        above[AT(i, j, k)] = liquid ? -1 : 0;
      }
  /* each column from the top down (up: the last axis), counting the liquid passed */
  const int up = SPH_UP;
  const long cols = n[0] * (up == 1 ? 1 : n[1]);
  for (long col = 0; col < cols; col++) {
    long held = 0;
    for (long q = n[up] - 1; q >= 0; q--) {
      const size_t a = up == 1 ? AT(col, q, 0) : AT(col % n[0], col / n[0], q);
      if (above[a] < 0)
        held++;
      else
        above[a] = held;
    }
  }
  /* hydrostatic: the air's own weight from the tank's top, and the liquid's where the column
   * above a point holds liquid (air under water: a Rayleigh-Taylor case, a bubble) */
  for (long k = 0; k < n[2]; k++)
    for (long j = 0; j < n[1]; j++)
      for (long i = 0; i < n[0]; i++) {
        const long held = above[AT(i, j, k)];
        if (held < 0) continue;
        double x[SPH_DIM];
        lattice_at(t->lo, (const long[3]){i, j, k}, dx, x);
        const double pw = (c->rho0 - c->air_material.rho0) * gmag * ((double)held * dx);
        const double pa = c->air_material.rho0 * gmag * (t->hi[SPH_UP] - x[SPH_UP]) + pw;
        const long at = sph_particles_add_at(&s->p, x, v, sph_eos_density(air, pa), mass, c->h,
                                             SPH_KIND_FLUID, err);
        if (at < 0) {
          free(above);
          return -1;
        }
        s->p.phase[at] = 1;
      }
#undef AT
  free(above);
  return 0;
}

/* Walls drawn through fluid (issue 21, D5), by a documented rule
 * (doc/case-files.md): a fluid particle closer than
 * SPH_WALL_CLEARANCE dx to a wall particle is not made. Wall particles are
 * binned in cells of dx, each fluid particle looks at its cell and the
 * eight around it. Ids are renumbered in order. Returns how many were
 * removed, or -1 out of memory. */
#define SPH_WALL_CLEARANCE 0.5

/* The wall particles binned in cells of dx from lo, n[d] cells along axis
 * d, cell c's at idx[start[c] .. start[c + 1] - 1]; and the test: fluid
 * particle i closer than sqrt(d2) to one in its cell or the 3^SPH_DIM - 1
 * around it. */
typedef struct wall_bins {
  double lo[SPH_DIM], dx, d2;
  size_t n[SPH_DIM];
  const size_t *start, *idx;
} wall_bins;
/* The cell coordinates of x (in cells of the bins, possibly outside them). */
static void cell_of(const wall_bins *b, const double x[SPH_DIM], double c[SPH_DIM]) {
  for (int d = 0; d < SPH_DIM; d++)
    c[d] = floor((x[d] - b->lo[d]) / b->dx);
}
/* The key of the cell c moved by off cells along each axis, or -1 outside the bins. */
static long bin_key(const wall_bins *b, const double c[SPH_DIM], const long off[SPH_DIM]) {
  size_t key = 0;
  for (int d = SPH_DIM - 1; d >= 0; d--) {
    const double cd = c[d] + (double)off[d];
    if (cd < 0 || cd >= (double)b->n[d]) return -1;
    key = key * b->n[d] + (size_t)cd;
  }
  return (long)key;
}
static int fluid_in_wall(const void *ctx, const sph_particles *p, size_t i) {
  const wall_bins *b = ctx;
  if (p->kind[i] != SPH_KIND_FLUID) return 0;
  const double x[SPH_DIM] = {SPH_XYZ(p->x[i], p->y[i], p->z[i])};
  double c[SPH_DIM];
  cell_of(b, x, c); /* once: the 3^SPH_DIM cells around are offsets from it */
  const long around = SPH_DIM == 2 ? 9 : 27;
  for (long o = 0; o < around; o++) {
    const long off[SPH_DIM] = {SPH_XYZ(o % 3 - 1, (o / 3) % 3 - 1, o / 9 - 1)};
    const long key = bin_key(b, c, off);
    for (size_t k = key < 0 ? 0 : b->start[key]; key >= 0 && k < b->start[key + 1]; k++) {
      const size_t j = b->idx[k];
      const double ex = x[0] - p->x[j], ey = x[1] - p->y[j];
      SPH_IF3(const double ez = x[2] - p->z[j];)
      const double r2 = SPH_NORM2(ex, ey, ez);
      if (r2 < b->d2) return 1;
    }
  }
  return 0;
}

/* The key of the cell holding x (a wall particle: inside the bins). */
static size_t bin_of(const wall_bins *b, const double x[SPH_DIM]) {
  double c[SPH_DIM];
  const long here[SPH_DIM] = {0};
  cell_of(b, x, c);
  return (size_t)bin_key(b, c, here);
}

/* Whether fluid particle i lies inside one of the case's obstacle boxes
 * (ctx: the case): a box's wall particles are layers behind its faces, its
 * inside is hollow, and a fluid block drawn through the box would fill it
 * (issue 61, E1). */
static int fluid_in_obstacle(const void *ctx, const sph_particles *p, size_t i) {
  const sph_case *c = ctx;
  if (p->kind[i] != SPH_KIND_FLUID) return 0;
  const double x[SPH_DIM] = {SPH_XYZ(p->x[i], p->y[i], p->z[i])};
  int held = c->n_vessels == 0; /* with vessels, a point inside none of them is not made */
  for (size_t k = 0; k < c->n_obstacles; k++) {
    const sph_obstacle *o = &c->obstacles[k];
    int in = 1;
    for (int d = 0; d < SPH_DIM && in; d++)
      in = x[d] > o->lo[d] && x[d] < o->hi[d];
    if (in && o->inside) in = o->inside(o->shape, x) == 1; /* a shape: inside it */
    if (o->vessel)
      held |= in;
    else if (in)
      return 1;
  }
  return !held;
}

static long remove_fluid_in_walls(sph_sim *s) {
  sph_particles *p = &s->p;
  const double dx = s->c->dx, d2 = (SPH_WALL_CLEARANCE * dx) * (SPH_WALL_CLEARANCE * dx);
  double lo[SPH_DIM], hi[SPH_DIM];
  for (int d = 0; d < SPH_DIM; d++)
    lo[d] = INFINITY, hi[d] = -INFINITY;
  size_t nw = 0;
  for (size_t i = 0; i < p->n; i++)
    if (p->kind[i] == SPH_KIND_WALL) {
      for (int d = 0; d < SPH_DIM; d++)
        lo[d] = fmin(lo[d], p->pos[d][i]), hi[d] = fmax(hi[d], p->pos[d][i]);
      nw++;
    }
  if (nw == 0) return 0;
  wall_bins b;
  memset(&b, 0, sizeof b);
  b.dx = dx;
  b.d2 = d2;
  double cells = 1.0;
  for (int d = 0; d < SPH_DIM; d++) {
    const double nd = floor((hi[d] - lo[d]) / dx) + 1.0;
    cells *= nd;
    b.lo[d] = lo[d];
    b.n[d] = (size_t)nd;
  }
  if (!(cells < 4.0 * (double)p->n + 1e6)) return 0; /* walls far apart: too sparse to bin */
  const size_t ncell = (size_t)cells;
  size_t *start = calloc(ncell + 1, sizeof *start), *idx = malloc(nw * sizeof *idx);
  size_t *fill = calloc(ncell, sizeof *fill);
  if (!start || !idx || !fill) {
    free(start);
    free(idx);
    free(fill);
    return -1;
  }
  for (size_t i = 0; i < p->n; i++)
    if (p->kind[i] == SPH_KIND_WALL) {
      const double x[SPH_DIM] = {SPH_XYZ(p->x[i], p->y[i], p->z[i])};
      start[bin_of(&b, x) + 1]++;
    }
  for (size_t c = 0; c < ncell; c++)
    start[c + 1] += start[c];
  for (size_t i = 0; i < p->n; i++)
    if (p->kind[i] == SPH_KIND_WALL) {
      const double x[SPH_DIM] = {SPH_XYZ(p->x[i], p->y[i], p->z[i])};
      const size_t c = bin_of(&b, x);
      idx[start[c] + fill[c]++] = i;
    }
  b.start = start;
  b.idx = idx;
  const long removed = (long)sph_particles_drop_if(p, 0, fluid_in_wall, &b);
  free(start);
  free(idx);
  free(fill);
  return removed;
}

/* Periodic: particles are wrapped into [x0, x1) along the periodic axis,
 * and a wall particle that then coincides with an earlier one (a staggered
 * layer that reaches both ends of a period) is dropped. Ids are renumbered
 * in order. */
static void dedupe_periodic(sph_sim *s) {
  sph_particles *p = &s->p;
  const double x0 = s->c->periodic_range[0], x1 = s->c->periodic_range[1], L = x1 - x0;
  const double tol = 1e-9 * L;
  const int a = s->c->periodic_axis;
  size_t kept = 0;
  for (size_t i = 0; i < p->n; i++) {
    double *restrict x = p->pos[a];
    if (x[i] >= x1) x[i] -= L;
    if (x[i] < x0) x[i] += L;
    int dup = 0;
    for (size_t j = 0; j < kept && !dup && p->kind[i] == SPH_KIND_WALL; j++) {
      if (p->kind[j] != SPH_KIND_WALL) continue;
      dup = 1;
      for (int d = 0; d < SPH_DIM; d++) {
        const double e = fabs(p->pos[d][j] - p->pos[d][i]);
        dup &= e < tol || (d == a && fabs(e - L) < tol);
      }
    }
    if (dup) continue;
    if (kept != i) sph_particles_move(p, kept, i);
    if (p->live & SPH_ARRAYS_REST) /* the rest position: wrapped */
      p->rest[a][kept] = p->pos[a][kept];
    p->id[kept] = (int64_t)kept;
    kept++;
  }
  p->n = kept;
}

/* Hydrostatic density of the wall particles beside or under a block. */
static void init_wall_density(sph_sim *s) {
  const sph_case *c = s->c;
  const double gmag = gravity_down(c);
  const double reach = SPH_CUBIC_SUPPORT * c->h;
  const double *up = s->p.pos[SPH_UP]; /* the vertical */
  for (size_t i = 0; i < s->p.n; i++) {
    if (s->p.kind[i] != SPH_KIND_WALL || (s->p.flags[i] & SPH_FLAG_REPULSIVE)) continue;
    double depth = 0.0;
    for (size_t b = 0; b < c->n_fluid; b++) {
      const sph_fluid_block *fb = &c->fluid[b];
      int beside = fb->hydrostatic; /* beside the block along every horizontal axis */
      for (int a = 0; a < SPH_UP; a++)
        beside &= s->p.pos[a][i] >= fb->lo[a] - reach && s->p.pos[a][i] <= fb->hi[a] + reach;
      if (!beside) continue;
      const double d = fb->surface - up[i];
      if (d > depth) depth = d;
    }
    if (depth > 0.0) s->p.rho[i] = sph_eos_density(&s->fp.eos, c->rho0 * gmag * depth);
  }
}

static void bounding_box(const sph_particles *p, double box[2 * SPH_DIM]) {
  for (int d = 0; d < SPH_DIM; d++) {
    box[2 * d] = INFINITY;
    box[2 * d + 1] = -INFINITY;
    for (size_t i = 0; i < p->n; i++) {
      if (p->pos[d][i] < box[2 * d]) box[2 * d] = p->pos[d][i];
      if (p->pos[d][i] > box[2 * d + 1]) box[2 * d + 1] = p->pos[d][i];
    }
  }
}

static void set_boxes(sph_sim *s) {
  const sph_case *c = s->c;
  enum { UP = 2 * SPH_UP }; /* the vertical's lower bound in a box */
  double bb[2 * SPH_DIM];
  bounding_box(&s->p, bb);
  if (c->tank.present) { /* a mirror tank has no wall particles: take its faces */
    const double face[2 * SPH_DIM] = {c->tank.x0, c->tank.x1, c->tank.y0,
                                      c->tank.y1 SPH_IF3(, c->tank.z0, c->tank.z1)};
    for (int k = 0; k < 2 * SPH_DIM; k += 2) {
      if (face[k] < bb[k]) bb[k] = face[k];
      if (face[k + 1] > bb[k + 1]) bb[k + 1] = face[k + 1];
    }
    const double wall = 0.5 * c->dx * (double)(c->tank.layers + 1);
    for (int k = 0; k < 2 * SPH_DIM; k += 2) {
      s->view[k] = face[k] - wall;
      s->view[k + 1] = face[k + 1] + wall;
    }
    if (!c->tank.lid) s->view[UP + 1] = face[UP + 1]; /* (open: the view ends at its top) */
    s->floor_y = face[UP];
  } else {
    memcpy(s->view, bb, sizeof bb);
    s->floor_y = INFINITY;
    for (size_t b = 0; b < c->n_fluid; b++) {
      const double bottom = c->fluid[b].lo[SPH_UP];
      if (bottom < s->floor_y) s->floor_y = bottom;
    }
  }
  sph_case_domain_around(c, bb, s->domain);
}

/* SPH_TEST_RANKS=R (doc/testing.md): every pass made as R ranks make it
 * (ranks.c); 1 when unset. */
static int test_ranks(void) {
  const char *e = getenv("SPH_TEST_RANKS");
  return e && *e ? atoi(e) : 1;
}

static int create(const sph_case *c, sph_sim **out, int ranks, int self, int rank_store,
                  sph_error *err);

/* Under an MPI launcher (procs.h) the passes are cut into one rank per
 * process, this process making its own. */
int sph_sim_create(const sph_case *c, sph_sim **out, sph_error *err) {
  const int procs = sph_procs_count();
  if (procs == 1) return create(c, out, test_ranks(), -1, 0, err);
  *out = NULL;
  if (test_ranks() > 1)
    return sph_error_set(err,
                         "SPH_TEST_RANKS emulates ranks in one process: unset it under "
                         "mpirun (%d processes)",
                         procs);
  return create(c, out, procs, sph_procs_rank(), 0, err);
}

int sph_sim_create_rank_store(const sph_case *c, sph_sim **out, sph_error *err) {
  return create(c, out, 1, -1, 1, err);
}

/* A sim of the case on `ranks` ranks, this process's `self` (-1: all of
 * them); a rank store (rank_store) makes no pass of its own: its owner's
 * passes fill it (ranks.c). */
/* The phases' laws and impedances (doc/method.md, Two phases): the liquid's (fp.eos), and with
 * physics.air the air's, of its own sound speed (by default the liquid's) and no floor: its gauge
 * pressure may fall below 0, about its ambient one, so that it fills the room a moving liquid
 * leaves, as a gas does. */
static void set_phases(sph_sim *s) {
  const sph_case *c = s->c;
  s->fp.phases = c->air ? 2 : 1;
  s->fp.phase_mat[0] = (sph_material){.rho0 = c->rho0,
                                      .exponent = 7,
                                      .c0 = c->sound_speed,
                                      .mu = c->mu,
                                      .density_limit = c->density_limit};
  if (c->air) s->fp.phase_mat[1] = c->air_material;
  s->fp.phase_eos[0] = s->fp.eos;
  for (int k = 0; k < s->fp.phases; k++) {
    const sph_material *m = &s->fp.phase_mat[k];
    if (k > 0)
      s->fp.phase_eos[k] =
          m->exponent == 1 ? sph_eos_linear(m->rho0, m->c0) : sph_eos_tait(m->rho0, m->c0);
    s->fp.phase_z[k] = s->fp.phase_eos[k].rho0 * s->fp.phase_eos[k].c0;
    s->fp.phase_mu[k] = m->mu;
  }
  s->fp.sigma = c->air ? c->air_material.sigma : 0.0;
}

/* The interaction passes' parameters from the case (force_pass.h), the phases' laws among them. */
static void force_params(sph_sim *s) {
  const sph_case *c = s->c;
  s->fp.eos = sph_eos_tait(c->rho0, c->sound_speed);
  if (!c->negative_pressure) s->fp.eos.rho_min = c->rho0; /* a fluid without tension */
  set_phases(s);
  s->fp.h = c->h;
  s->fp.alpha = c->alpha;
  s->fp.beta = c->beta;
  s->fp.eta = c->eta;
  s->fp.xsph = c->xsph;
  s->fp.riemann = c->riemann;
  s->fp.riemann_limiter = c->riemann_limiter;
  for (int d = 0; d < SPH_DIM; d++)
    s->fp.g[d] = c->gravity[d];
  s->fp.viscosity = c->viscosity;
  s->fp.mu = c->mu;
  s->fp.periodic = c->periodic;
  s->fp.period = c->periodic ? c->periodic_range[1] - c->periodic_range[0] : 0.0;
  s->fp.paxis = c->periodic ? c->periodic_axis : 0;
  s->fp.px0 = c->periodic ? c->periodic_range[0] : 0.0;
  s->fp.gradient_correction = c->gradient_correction;
  s->fp.corrected_gradient = c->corrected_gradient;
  s->fp.var_h = c->fs_h_factor > 0.0;
  s->fp.lj_d = c->repulsion;
  s->fp.lj_r0 = c->dx;
  s->fp.ledger = c->energy;
  s->fp.sps = c->sps;
  s->fp.sps_cs = c->sps_cs;
  s->fp.sps_ci = c->sps_ci;
  s->fp.sps_delta = c->dx;
  s->fp.kernel = c->kernel;
  s->fp.diffusion = c->diffusion;
  s->fp.diffusion_delta = c->diffusion_delta;
  if (c->variable_h) s->fp.var_h = 1;
  s->fp.loop = sph_test_loop();
  s->fp.runtime_terms = getenv("SPH_TEST_RUNTIME") != NULL; /* doc/testing.md */
  const char *nw = getenv("SPH_TEST_NWALL");
  s->fp.nwall_every = nw && strcmp(nw, "every") == 0;
}

static int create(const sph_case *c, sph_sim **out, int ranks, int self, int rank_store,
                  sph_error *err) {
  *out = NULL;
  /* resources bounded before any particle is made (issue 21, D3, D4) */
  if (sph_case_check_size(c, c->max_particles, err)) return -1;
  sph_sim *s = calloc(1, sizeof *s);
  if (!s) return sph_error_set(err, "out of memory");
  s->c = c;
  if (sph_sim_record_geometry(c, &s->geometry, err)) {
    free(s);
    return -1;
  }
  sph_grid_init(&s->grid);
  sph_nlist_init(&s->nl);
  force_params(s);
  s->first_step = 1;
  s->detect = sph_case_needs_free_surface(c);
  if (sph_particles_init(&s->p, 1024, err)) goto fail;
  /* the optional arrays the scheme needs from the start; the walls turn on
   * what theirs need (doc/memory.md) */
  const unsigned heat = c->energy ? SPH_ARRAYS_HEAT : 0u;
  const unsigned half = c->integrator == SPH_INTEGRATOR_LEAPFROG ? SPH_ARRAYS_HALF_STEP : 0u;
  /* the state at the start of a step: the predictor-corrector's X0; the
   * leap-frog's last good state is the pass's packed copy (sim.c), unless
   * the store is reordered between that pass and the blow-up check (the
   * density filter's grid; mirror particles, below) */
  const unsigned saved =
      !half || c->density_filter != SPH_FILTER_NONE ? (unsigned)SPH_ARRAYS_SAVED : 0u;
  sph_particles_limit(&s->p, heat | half | saved | (c->air ? (unsigned)SPH_ARRAYS_PHASE : 0u));
  if (add_fluid(s, err) || add_air(s, err)) goto fail;
  if (sph_walls_create(&s->walls, &s->p, &c->tank, c->walls, c->n_walls, c->obstacles,
                       c->n_obstacles, c->dx, c->rho0, c->h,
                       SPH_CUBIC_SUPPORT * c->h * (c->fs_h_factor > 1.0 ? c->fs_h_factor : 1.0),
                       err)) {
    sph_error ew = *err;
    sph_error_set(err, "case %s: %s", c->name, ew.msg);
    goto fail;
  }
  s->fp.no_slip = s->walls.no_slip;
  s->fp.free_slip = s->walls.free_slip;
  s->fp.mdbc = s->walls.mdbc;
  s->fp.adami = s->walls.adami;
  s->fp.moving_walls = s->walls.moving;
  s->fp.wall_diffusion = sph_diffusion_walls(&s->p, &s->fp);
  s->fp.mirror = s->walls.n_mirror > 0;
  if (s->fp.mirror) sph_particles_use(&s->p, SPH_ARRAYS_SAVED);
  s->fp.repulsive = s->walls.repulsive;
  s->ledger.repulsion = c->energy && s->walls.repulsive;
  if (c->periodic) dedupe_periodic(s);
  s->fluid_in_obstacles =
      s->c->n_obstacles ? sph_particles_drop_if(&s->p, 0, fluid_in_obstacle, s->c) : 0;
  const long removed = remove_fluid_in_walls(s);
  if (removed < 0) {
    sph_error_set(err, "out of memory");
    goto fail;
  }
  s->fluid_removed = (size_t)removed;
  /* a neighbour list kept across passes where nothing needs a fresh grid:
   * free-surface detection reads the list, and with h* = k h the list's
   * support is 2 k h whichever particles carry k h; only mirror particles
   * (made anew at every pass) and paper B's variable h (whose largest h
   * moves with the density) rebuild it at every pass */
  if (!s->walls.n_mirror && !c->variable_h)
    s->skin = sph_skin_fraction() * SPH_CUBIC_SUPPORT * c->h;
  s->nl.wall_fluid_only = wall_rows_fluid_only(s);
  if (s->p.n == 0) {
    sph_error_set(err, "case %s: no particles", c->name);
    goto fail;
  }
  if (c->shifting) { /* the store's size is fixed: shifting takes no mirror walls (case.c) */
    for (int a = 0; a < SPH_DIM; a++) {
      s->shift[a] = malloc(s->p.n * sizeof *s->shift[a]);
      if (!s->shift[a]) {
        sph_error_set(err, "out of memory");
        goto fail;
      }
    }
  }
  init_wall_density(s);
  sph_forces_pressure(&s->p, s->fp.phase_eos);
  set_boxes(s);
  s->parameters = sph_case_describe(c);
  if (!s->parameters) {
    sph_error_set(err, "out of memory");
    goto fail;
  }
  /* the grid's directions from the case's particles as set up: every later
   * sort (and a restart's) takes them (grid.h) */
  sph_grid_orient(&s->grid, &s->p);
  if (shuffle_store(&s->p, err)) goto fail;
  sph_sim_move_walls(s, 0.0);
  s->resort = 1;
  /* the ranks before the first pass, which they then make as every later
   * one (the processes agreeing that each could set them up) */
  int rc = rank_store ? 0 : sph_sim_ranks_init(s, ranks, self, err);
  if (self >= 0) rc = sph_procs_agree(rc, err);
  if (rc) goto fail;
  if (!rank_store) {
    if (sph_sim_pass(s, err)) goto fail; /* rates and flags of the initial state */
    /* the faster lane loop on this processor, timed on the store the
     * passes run on (a rank's: the process's own rows); the same bits;
     * mirror walls run the scalar loop, and their particles are gone after
     * the pass */
    sph_sim *on = s->sub ? s->sub : s;
    s->lane_ratio = 1.0;
    rc = s->walls.n_mirror ? 0
                           : sph_forces_fastest_loop(&on->p, &on->nl, &on->fp, &on->work,
                                                     &s->fp.loop, &s->lane_ratio, err);
    if (self >= 0) rc = sph_sim_ranks_agree_loop(s, rc, err); /* every process's choice */
    if (rc) goto fail;
  }
  if (c->energy) sph_sim_ledger_start(s);
  *out = s;
  return 0;
fail:
  sph_sim_free(s);
  return -1;
}

void sph_sim_free(sph_sim *s) {
  if (!s) return;
  sph_particles_free(&s->p);
  sph_outflow_free(&s->out);
  sph_grid_free(&s->grid);
  sph_nlist_free(&s->nl);
  sph_force_work_free(&s->work);
  sph_wall_velocity_work_free(&s->mdbc_work);
  for (int a = 0; a < SPH_DIM; a++)
    free(s->shift[a]);
  free(s->parameters);
  sph_snapshot_geometry_free(&s->geometry);
  sph_sim_ranks_free(s);
  free(s);
}
