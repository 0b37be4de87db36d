/*
 * sim.c - the simulation object (see sim.h).
 *
 * Set-up: fluid blocks are filled on the lattice x0 + (i + 1/2) dx; walls
 * come from boundary.c. With a hydrostatic start the density of a fluid
 * particle is the Tait density of p = rho0 |g| (surface - y), and a wall
 * particle within 2h of a block's x-range gets the same law for that
 * block's surface, so walls hold the column up from the first step. Every
 * particle has mass rho0 dx^2 and smoothing length h = h_factor dx.
 *
 * One step is paper B's predictor-corrector (integrate.h) with an
 * interaction pass at the mid-step state and one at the new state. The
 * passes walk a neighbour list (grid.h) that is kept, with a skin, for as
 * long as it provably holds every pair within the support (see
 * neighbours()), so the grid is not rebuilt at every pass; every pair
 * inside the support is evaluated at every pass, exactly as with a fresh
 * grid. The time step comes from the first pass (the state
 * at t^n). After the step every particle is checked: finite state, density
 * within density_limit of rho0, inside the domain. The first offender in id
 * order is reported, so the message is the same for any thread count.
 */
#include "config.h"

#include "core/parallel.h"

#include "solver/sim.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "walls/boundary.h"
#include "walls/motion.h"
#include "physics/filter.h"
#include "physics/freesurface.h"
#include "physics/eos.h"
#include "solver/forces.h"
#include "neighbours/grid.h"
#include "solver/integrate.h"
#include "physics/kernel.h"
#include "io/snapshot.h"

struct sph_sim {
  const sph_case *c;
  sph_mirror_line mirror[SPH_MIRROR_MAX_LINES]; /* mirror walls */
  size_t n_mirror;
  double mirror_reach;
  int first_step;             /* leap-frog: the special first half step */
  int detect;                 /* free-surface detection runs at every pass */
  size_t n_surface;           /* particles flagged at the last pass */
  int moving;                 /* some walls have a prescribed motion */
  /* energy ledger (output.energy) */
  double power_wall, power_xsph; /* at the last pass: sum_i m_i wpow_i, -sum_i m_i g.xs_i */
  double work_wall, drift_xsph;  /* their time integrals */
  double force_x, force_y;       /* at the last pass: external force on the fluid
                                    (walls, mirror particles, body force) */
  double impulse_x, impulse_y;   /* its time integral */
  double p0x, p0y;               /* initial fluid momentum */
  double dt_paper_b;             /* paper B §2.6 step from the last pass */
  double e0, e0_fluid;           /* initial totals */
  sph_particles p;
  sph_grid grid;
  sph_nlist nl;               /* neighbour list of the interaction passes */
  double skin;                /* its skin; 0 = rebuilt at every pass */
  int resort;                 /* the next pass sorts the store by cell */
  sph_force_work work;
  sph_force_params fp;
  double t, last_dt;
  double t_saved; /* time of the state saved at the start of the last step */
  long steps;
  double floor_y;
  double domain[4];
  double view[4];
  char *parameters; /* sph_case_describe */
};

/* The neighbour list's skin as a fraction of the support 2h: the default,
 * and the one in effect (SPH_TEST_SKIN overrides it, for benchmarks; 0 rebuilds
 * at every pass). */
#define SPH_SKIN_DEFAULT 0.15
static double sph_skin_fraction(void) {
  const char *e = getenv("SPH_TEST_SKIN");
  if (e && *e) return atof(e);
  return SPH_SKIN_DEFAULT;
}

/* The interaction loop: the default, or the one the test hook
 * SPH_TEST_LANES names (portable, avx or scalar; doc/testing.md), for the
 * tests that compare the loops through whole runs. */
static sph_force_loop sph_test_loop(void) {
  const char *e = getenv("SPH_TEST_LANES");
  if (!e) return SPH_LOOP_AUTO;
  if (strcmp(e, "portable") == 0) return SPH_LOOP_LANES;
  if (strcmp(e, "avx") == 0) return SPH_LOOP_LANES_AVX;
  if (strcmp(e, "scalar") == 0) return SPH_LOOP_SCALAR;
  return SPH_LOOP_AUTO;
}

/* Cells of the grid are a hair larger than the support, so rounding in the
 * cell index can never separate a pair closer than 2h by a whole cell. */
#define SPH_CELL_MARGIN (1.0 + 1e-9)

static int add_fluid(sph_sim *s, sph_error *err) {
  const sph_case *c = s->c;
  const double dx = c->dx, mass = c->rho0 * dx * dx;
  const double gmag = -c->gravity[1] > 0.0 ? -c->gravity[1] : 0.0;
  for (size_t b = 0; b < c->n_fluid; b++) {
    const sph_fluid_block *fb = &c->fluid[b];
    const long nx = (long)floor((fb->x1 - fb->x0) / dx + 1e-9);
    const long ny = (long)floor((fb->y1 - fb->y0) / dx + 1e-9);
    for (long j = 0; j < ny; j++)
      for (long i = 0; i < nx; i++) {
        double x = fb->x0 + ((double)i + 0.5) * dx;
        double y = fb->y0 + ((double)j + 0.5) * dx;
        sph_fluid_jitter(fb, b, i, j, dx, &x, &y); /* perturbed start, if asked for */
        double rho = c->rho0;
        if (fb->hydrostatic) rho = sph_eos_density(&s->fp.eos, c->rho0 * gmag * (fb->surface - y));
        if (sph_particles_add(&s->p, x, y, fb->vx, fb->vy, rho, mass, c->h, SPH_KIND_FLUID, err) <
            0)
          return -1;
      }
  }
  return 0;
}

static int pass(sph_sim *s, sph_error *err);
static double fluid_internal(const sph_sim *s);

static uint8_t wall_flags(sph_boundary_kind b, int extrapolated) {
  return (uint8_t)((b == SPH_BOUNDARY_REPULSIVE ? SPH_FLAG_REPULSIVE : 0) |
                   (extrapolated ? SPH_FLAG_NO_SLIP : 0));
}

/* Wall particles of the tank and segments; mirror walls become lines. */
static int add_walls(sph_sim *s, sph_error *err) {
  const sph_case *c = s->c;
  const double wall_mass = c->rho0 * c->dx * c->dx;
  s->mirror_reach = SPH_CUBIC_SUPPORT * c->h * (c->fs_h_factor > 1.0 ? c->fs_h_factor : 1.0);
  s->fp.no_slip = c->tank.present && c->tank.extrapolated;
  for (size_t w = 0; w < c->n_walls; w++) s->fp.no_slip |= c->walls[w].extrapolated;
  if (c->tank.present) {
    if (c->tank.boundary == SPH_BOUNDARY_MIRROR) {
      s->n_mirror += sph_mirror_tank_lines(&c->tank, s->mirror_reach, s->mirror);
    } else if (sph_boundary_add_tank(&s->p, &c->tank, c->dx, c->rho0, wall_mass, c->h,
                                     wall_flags(c->tank.boundary, c->tank.extrapolated), err)) {
      return -1;
    }
    if (c->tank.boundary == SPH_BOUNDARY_REPULSIVE) s->fp.repulsive = 1;
  }
  for (size_t w = 0; w < c->n_walls; w++) {
    const sph_wall_segment *ws = &c->walls[w];
    if (ws->boundary == SPH_BOUNDARY_MIRROR) {
      if (s->n_mirror == sizeof s->mirror / sizeof s->mirror[0])
        return sph_error_set(err, "case %s: more than %zu mirror walls", c->name, s->n_mirror);
      s->mirror[s->n_mirror++] = sph_mirror_segment_line(ws->x0, ws->y0, ws->x1, ws->y1);
      continue;
    }
    if (ws->boundary == SPH_BOUNDARY_REPULSIVE) s->fp.repulsive = 1;
    const size_t first = s->p.n;
    if (sph_boundary_add_segment(&s->p, ws->x0, ws->y0, ws->x1, ws->y1, ws->layers, ws->stagger, 0,
                                 c->dx, c->rho0, wall_mass, c->h,
                                 wall_flags(ws->boundary, ws->extrapolated), err))
      return -1;
    if (ws->motion.kind != SPH_MOTION_NONE) {
      s->moving = 1;
      for (size_t i = first; i < s->p.n; i++) s->p.body[i] = (int32_t)w;
    }
  }
  return 0;
}

/* Periodic in x: wall particles are wrapped into [x0, x1), and a wall
 * particle that then coincides with an earlier one (a staggered layer that
 * reaches both ends of a period) is dropped. Ids are renumbered in order. */
static void dedupe_periodic(sph_sim *s) {
  sph_particles *p = &s->p;
  const double x0 = s->c->periodic_x[0], x1 = s->c->periodic_x[1], L = x1 - x0;
  const double tol = 1e-9 * L;
  size_t kept = 0;
  for (size_t i = 0; i < p->n; i++) {
    if (p->x[i] >= x1) p->x[i] -= L;
    if (p->x[i] < x0) p->x[i] += L;
    int dup = 0;
    for (size_t j = 0; j < kept && !dup && p->kind[i] == SPH_KIND_WALL; j++)
      dup = p->kind[j] == SPH_KIND_WALL && fabs(p->y[j] - p->y[i]) < tol &&
            (fabs(p->x[j] - p->x[i]) < tol || fabs(fabs(p->x[j] - p->x[i]) - L) < tol);
    if (dup) continue;
    if (kept != i) {
      p->x[kept] = p->x[i];
      p->y[kept] = p->y[i];
      p->vx[kept] = p->vx[i];
      p->vy[kept] = p->vy[i];
      p->rho[kept] = p->rho[i];
      p->mass[kept] = p->mass[i];
      p->h[kept] = p->h[i];
      p->kind[kept] = p->kind[i];
      p->flags[kept] = p->flags[i];
      p->body[kept] = p->body[i];
      p->yr[kept] = p->yr[i];
      p->mx[kept] = p->mx[i];
      p->my[kept] = p->my[i];
    }
    p->xr[kept] = p->x[kept]; /* the rest position is the wrapped one */
    p->id[kept] = (int64_t)kept;
    kept++;
  }
  p->n = kept;
}

/* Positions and velocities of the moving wall particles at time t: rest
 * position plus the prescribed displacement (never accumulated, so a wall
 * is exactly where its law puts it). */
static void move_walls(sph_sim *s, double t) {
  if (!s->moving) return;
  sph_particles *p = &s->p;
  for (size_t i = 0; i < p->n; i++) {
    if (p->body[i] < 0) continue;
    sph_motion_point(&s->c->walls[p->body[i]].motion, t, p->xr[i], p->yr[i], &p->x[i], &p->y[i],
                     &p->vx[i], &p->vy[i]);
  }
}

/* Hydrostatic density of the wall particles beside or under a block. */
static void init_wall_density(sph_sim *s) {
  const sph_case *c = s->c;
  const double gmag = -c->gravity[1] > 0.0 ? -c->gravity[1] : 0.0;
  const double reach = SPH_CUBIC_SUPPORT * c->h;
  for (size_t i = 0; i < s->p.n; i++) {
    if (s->p.kind[i] != SPH_KIND_WALL || (s->p.flags[i] & SPH_FLAG_REPULSIVE)) continue;
    double depth = 0.0;
    for (size_t b = 0; b < c->n_fluid; b++) {
      const sph_fluid_block *fb = &c->fluid[b];
      if (!fb->hydrostatic || s->p.x[i] < fb->x0 - reach || s->p.x[i] > fb->x1 + reach) continue;
      const double d = fb->surface - s->p.y[i];
      if (d > depth) depth = d;
    }
    if (depth > 0.0) s->p.rho[i] = sph_eos_density(&s->fp.eos, c->rho0 * gmag * depth);
  }
}

static void bounding_box(const sph_particles *p, double box[4]) {
  box[0] = box[2] = INFINITY;
  box[1] = box[3] = -INFINITY;
  for (size_t i = 0; i < p->n; i++) {
    if (p->x[i] < box[0]) box[0] = p->x[i];
    if (p->x[i] > box[1]) box[1] = p->x[i];
    if (p->y[i] < box[2]) box[2] = p->y[i];
    if (p->y[i] > box[3]) box[3] = p->y[i];
  }
}

static void set_boxes(sph_sim *s) {
  const sph_case *c = s->c;
  double bb[4];
  bounding_box(&s->p, bb);
  if (c->tank.present) { /* a mirror tank has no wall particles: take its faces */
    if (c->tank.x0 < bb[0]) bb[0] = c->tank.x0;
    if (c->tank.x1 > bb[1]) bb[1] = c->tank.x1;
    if (c->tank.y0 < bb[2]) bb[2] = c->tank.y0;
    if (c->tank.y1 > bb[3]) bb[3] = c->tank.y1;
  }
  if (c->periodic) {
    s->view[0] = c->periodic_x[0];
    s->view[1] = c->periodic_x[1];
    s->view[2] = bb[2];
    s->view[3] = bb[3];
  }
  if (c->tank.present) {
    const double wall = 0.5 * c->dx * (double)(c->tank.layers + 1);
    s->view[0] = c->tank.x0 - wall;
    s->view[1] = c->tank.x1 + wall;
    s->view[2] = c->tank.y0 - wall;
    s->view[3] = c->tank.y1;
    s->floor_y = c->tank.y0;
  } else {
    memcpy(s->view, bb, sizeof bb);
    s->floor_y = INFINITY;
    for (size_t b = 0; b < c->n_fluid; b++)
      if (c->fluid[b].y0 < s->floor_y) s->floor_y = c->fluid[b].y0;
  }
  if (c->domain_set) {
    memcpy(s->domain, c->domain, sizeof s->domain);
  } else if (c->periodic) { /* x wraps: only a runaway beyond a period is an error */
    const double L = c->periodic_x[1] - c->periodic_x[0], hgt = bb[3] - bb[2];
    s->domain[0] = c->periodic_x[0] - L;
    s->domain[1] = c->periodic_x[1] + L;
    s->domain[2] = bb[2] - hgt - 4.0 * c->h;
    s->domain[3] = bb[3] + 2.0 * hgt + 4.0 * c->h;
  } else {
    /* the particles' box, widened by half its size sideways and below, and
     * by twice its height above (splashes rise, nothing should fall far) */
    const double w = bb[1] - bb[0], hgt = bb[3] - bb[2];
    const double m = 0.5 * (w > hgt ? w : hgt) + 4.0 * c->h;
    s->domain[0] = bb[0] - m;
    s->domain[1] = bb[1] + m;
    s->domain[2] = bb[2] - m;
    s->domain[3] = bb[3] + 2.0 * hgt + m;
  }
}

int sph_sim_create(const sph_case *c, sph_sim **out, sph_error *err) {
  *out = NULL;
  sph_sim *s = calloc(1, sizeof *s);
  if (!s) return sph_error_set(err, "out of memory");
  s->c = c;
  sph_grid_init(&s->grid);
  sph_nlist_init(&s->nl);
  s->fp.eos = sph_eos_tait(c->rho0, c->sound_speed);
  s->fp.h = c->h;
  s->fp.alpha = c->alpha;
  s->fp.beta = c->beta;
  s->fp.eta = c->eta;
  s->fp.xsph = c->xsph;
  s->fp.gx = c->gravity[0];
  s->fp.gy = c->gravity[1];
  s->fp.viscosity = c->viscosity;
  s->fp.mu = c->mu;
  s->fp.periodic = c->periodic;
  s->fp.period = c->periodic ? c->periodic_x[1] - c->periodic_x[0] : 0.0;
  s->fp.px0 = c->periodic ? c->periodic_x[0] : 0.0;
  s->fp.gradient_correction = c->gradient_correction;
  s->fp.var_h = c->fs_h_factor > 0.0;
  s->fp.lj_d = c->repulsion;
  s->fp.lj_r0 = c->dx;
  s->first_step = 1;
  s->detect = sph_case_needs_free_surface(c);
  s->fp.ledger = c->energy;
  s->fp.sps = c->sps;
  s->fp.sps_cs = c->sps_cs;
  s->fp.sps_ci = c->sps_ci;
  s->fp.sps_delta = c->dx;
  if (c->variable_h) s->fp.var_h = 1;
  s->fp.loop = sph_test_loop();
  if (sph_particles_init(&s->p, 1024, err)) goto fail;
  if (add_fluid(s, err)) goto fail;
  if (add_walls(s, err)) goto fail;
  if (c->periodic) dedupe_periodic(s);
  /* a neighbour list kept across passes where nothing needs a fresh grid */
  if (!s->n_mirror && !s->detect && !s->fp.var_h) s->skin = sph_skin_fraction() * SPH_CUBIC_SUPPORT * c->h;
  if (s->p.n == 0) {
    sph_error_set(err, "case %s: no particles", c->name);
    goto fail;
  }
  init_wall_density(s);
  sph_forces_pressure(&s->p, &s->fp.eos);
  set_boxes(s);
  s->parameters = sph_case_describe(c);
  if (!s->parameters) {
    sph_error_set(err, "out of memory");
    goto fail;
  }
  move_walls(s, 0.0);
  s->resort = 1;
  if (pass(s, err)) goto fail; /* rates and flags of the initial state */
  if (c->energy) {
    sph_diag_row row;
    sph_sim_diag(s, &row);
    s->e0 = row.total;
    s->e0_fluid = row.kinetic + row.potential + fluid_internal(s);
    s->p0x = row.momentum_x;
    s->p0y = row.momentum_y;
  }
  *out = s;
  return 0;
fail:
  sph_sim_free(s);
  return -1;
}

void sph_sim_free(sph_sim *s) {
  if (!s) return;
  sph_particles_free(&s->p);
  sph_grid_free(&s->grid);
  sph_nlist_free(&s->nl);
  sph_force_work_free(&s->work);
  free(s->parameters);
  free(s);
}

/* The largest smoothing length: k h with h* = k h on the free surface. */
static double h_max(const sph_sim *s) {
  if (!s->c->variable_h) return s->fp.var_h ? s->c->fs_h_factor * s->c->h : s->c->h;
  double h = 0.0;
  for (size_t i = 0; i < s->p.n; i++)
    if (s->p.h[i] > h) h = s->p.h[i];
  return h;
}

/* Paper B §2.1: h = h0 (rho0/rho)^(1/d), d = 2, at every particle. */
static void update_h(sph_sim *s) {
  if (!s->c->variable_h) return;
  const double h0 = s->c->h, rho0 = s->c->rho0;
  for (size_t i = 0; i < s->p.n; i++) s->p.h[i] = h0 * sqrt(rho0 / s->p.rho[i]);
}

/* The ledger's rates at the state of the last pass, summed serially in
 * storage order: the power of the walls on the fluid, and the rate at which
 * the XSPH correction (a displacement no force pays for) changes the
 * potential energy. */
static void ledger_powers(sph_sim *s) {
  const sph_particles *p = &s->p;
  const double *g = s->c->gravity;
  const int xsph = s->c->xsph != 0.0;
  double pw = 0.0, px = 0.0, fx = 0.0, fy = 0.0;
  for (size_t i = 0; i < p->n; i++) {
    if (p->kind[i] != SPH_KIND_FLUID) continue;
    const double m = p->mass[i];
    pw += m * s->work.wpow[i];
    if (xsph) px -= m * (g[0] * p->xsx[i] + g[1] * p->xsy[i]);
    fx += m * (s->work.wfx[i] + g[0]);
    fy += m * (s->work.wfy[i] + g[1]);
  }
  s->power_wall = pw;
  s->power_xsph = px;
  s->force_x = fx;
  s->force_y = fy;
}

static double fluid_internal(const sph_sim *s) {
  double u = 0.0;
  for (size_t i = 0; i < s->p.n; i++)
    if (s->p.kind[i] == SPH_KIND_FLUID) u += s->p.mass[i] * s->p.u[i];
  return u;
}

/* Paper A §7: flag the free surface (circles of radius factor * h_i), then
 * with h* = k h give surface particles the smoothing length k h0. Without
 * h* the smoothing lengths are left alone (constant, or paper B's
 * variable h). */
static int free_surface(sph_sim *s, sph_error *err) {
  const sph_case *c = s->c;
  sph_freesurface_params fp = {c->fs_radius_factor,
                               c->periodic ? c->periodic_x[1] - c->periodic_x[0] : 0.0};
  const int hstar = c->fs_h_factor > 0.0;
  if (hstar) sph_freesurface_apply_h(&s->p, c->h, 1.0);
  if (sph_freesurface_detect(&s->p, &s->grid, &fp, &s->n_surface, err)) return -1;
  if (hstar) sph_freesurface_apply_h(&s->p, c->h, c->fs_h_factor);
  return 0;
}

/* The interaction support: 2 max h, and the Lennard-Jones range if larger. */
static double support(const sph_sim *s) {
  double r = SPH_CUBIC_SUPPORT * h_max(s);
  if (s->fp.repulsive && s->fp.lj_r0 > r) r = s->fp.lj_r0;
  return r * SPH_CELL_MARGIN;
}

/* The cell list of the current positions (periodic in x when the case
 * is), cells fitting the support plus the list's skin. At most ~64 cells
 * per particle: far more than any sane domain needs. */
static int build_grid(sph_sim *s, double cell, sph_error *err) {
  const sph_case *c = s->c;
  const size_t max_cells = 64 * s->p.n + 1024 * 1024;
  return c->periodic ? sph_grid_build_periodic(&s->grid, &s->p, cell, c->periodic_x[0],
                                               c->periodic_x[1], max_cells, err)
                     : sph_grid_build(&s->grid, &s->p, cell, max_cells, err);
}

/* Steps between sorts of the store when the neighbour list is kept. */
#define SPH_RESORT_EVERY 40

/* The neighbour list of the current state.
 *
 * Without a skin (cases whose passes need a fresh grid or change the
 * store: mirror particles, free-surface detection, variable h) the store is
 * sorted by cell and the list rebuilt at every pass.
 *
 * With a skin, a list built earlier is kept while sph_nlist_fresh proves it
 * complete (no particle moved more than skin/2 since); otherwise the
 * particles are binned without reordering the store and the list rebuilt.
 * The store is sorted (for memory locality) only at the end-of-step pass
 * of every SPH_RESORT_EVERY-th step: a function of the step count, not of
 * when lists happened to be rebuilt. Since the rows of a list are in
 * storage order, every sum of a pass then depends only on the state, the
 * storage order and the step count, so a run restarted from any snapshot
 * (which records the storage order) repeats the uninterrupted run bit for
 * bit, whatever the skin. */
static int neighbours(sph_sim *s, sph_error *err) {
  const sph_case *c = s->c;
  const int resort = s->resort;
  s->resort = 0;
  if (s->skin > 0.0 && !resort && sph_nlist_fresh(&s->nl, &s->p)) return 0;
  const double cell = (support(s) + s->skin) * SPH_CELL_MARGIN;
  const double px0 = c->periodic ? c->periodic_x[0] : 0.0;
  const double px1 = c->periodic ? c->periodic_x[1] : 0.0;
  /* Without a skin the cells fit the support. With one, the store is
   * sorted by cells that fit the support plus the default skin, whatever
   * the skin in effect: the storage order (and with it every result) does
   * not depend on the skin, and with the default skin the list's cells are
   * the sort's. A particle then stays in the cell it was sorted by until
   * it crosses a cell edge, so the cells' contents, walked in the grid's
   * order, come out nearly in storage order and the rows' insertion sort
   * (sph_nlist_build) has little to do; with smaller sort cells every row
   * interleaves several cells' runs of indices. */
  const double sort_cell =
      (support(s) + (s->skin > 0.0 ? SPH_SKIN_DEFAULT * SPH_CUBIC_SUPPORT * c->h : 0.0)) *
      SPH_CELL_MARGIN;
  if ((s->skin == 0.0 || resort) && build_grid(s, sort_cell, err)) return -1;
  if (s->skin > 0.0 && sph_grid_bin(&s->grid, &s->p, cell, c->periodic, px0, px1,
                                    64 * s->p.n + 1024 * 1024, err))
    return -1;
  return sph_nlist_build(&s->nl, &s->grid, &s->p, support(s), s->skin, px1 - px0, err);
}

/* Mirror particles, grid build, free-surface flags and one interaction
 * pass on the current state; the mirror particles are gone again when it
 * returns. */
static int pass(sph_sim *s, sph_error *err) {
  const sph_case *c = s->c;
  update_h(s);
  if (s->n_mirror && sph_mirror_add(&s->p, s->mirror, s->n_mirror, s->mirror_reach, err) < 0)
    return -1;
  int rc = neighbours(s, err);
  if (rc == 0 && s->detect) rc = free_surface(s, err);
  if (rc == 0) rc = sph_forces_evaluate(&s->p, &s->nl, &s->fp, &s->work, err);
  /* everything that reads the pass's per-particle work arrays, before
   * removing the mirror particles reorders the store under them */
  if (rc == 0) {
    s->dt_paper_b = sph_dt_paper_b(&s->work, c->h, c->dt_factor);
    if (s->fp.ledger) ledger_powers(s);
  }
  if (s->n_mirror) sph_mirror_remove(&s->p, s->grid.perm, s->grid.work);
  return rc;
}

/* Density re-initialisation (paper B §2.8) on a grid of the new positions;
 * with the leap-frog the half-step density is reset to the filtered one. */
static int apply_filter(sph_sim *s, sph_error *err) {
  const sph_case *c = s->c;
  sph_nlist_invalidate(&s->nl); /* the grid build reorders the store */
  if (build_grid(s, SPH_CUBIC_SUPPORT * h_max(s) * SPH_CELL_MARGIN, err)) return -1;
  sph_filter_params fp;
  sph_filter_params_default(&fp, s->fp.var_h ? 0.0 : c->h);
  if (sph_filter_apply(c->density_filter, &s->p, &s->grid, &fp, s->work.sigma, NULL, err))
    return -1;
  if (c->integrator == SPH_INTEGRATOR_LEAPFROG)
    for (size_t i = 0; i < s->p.n; i++) s->p.rhoh[i] = s->p.rho[i];
  sph_forces_pressure(&s->p, &s->fp.eos);
  return 0;
}

/* Periodic in x: particles that crossed a side re-enter at the other. */
static void wrap_periodic(sph_sim *s) {
  if (!s->c->periodic) return;
  const double x0 = s->c->periodic_x[0], x1 = s->c->periodic_x[1], L = x1 - x0;
  for (size_t i = 0; i < s->p.n; i++) {
    if (s->p.x[i] >= x1)
      s->p.x[i] -= L;
    else if (s->p.x[i] < x0)
      s->p.x[i] += L;
  }
}

/* How the loops over the store split it among threads: by the neighbour
 * list's rows while the list covers the store (parallel.h). */
static const size_t *slices(const sph_sim *s) {
  return s->nl.cost && s->nl.n == s->p.n ? s->nl.cost : NULL;
}

/* Why particle i fails the blow-up check, or NULL. */
static inline const char *bad_particle(const sph_particles *p, size_t i, double lim, double rho0,
                                       const double *d) {
  if (!isfinite(p->x[i]) || !isfinite(p->y[i]) || !isfinite(p->vx[i]) || !isfinite(p->vy[i]) ||
      !isfinite(p->rho[i]) || !isfinite(p->p[i]))
    return "state is not finite (NaN or Inf)";
  if (fabs(p->rho[i] / rho0 - 1.0) > lim) return "density outside the allowed band";
  if (p->kind[i] == SPH_KIND_FLUID &&
      (p->x[i] < d[0] || p->x[i] > d[1] || p->y[i] < d[2] || p->y[i] > d[3]))
    return "particle left the domain";
  return NULL;
}

/* Whether particle i surely passes the blow-up check, without a division:
 * v - v is 0 for every finite v and NaN otherwise; the density band is
 * narrowed by a relative 1e-9, far more than the rounding of
 * |rho / rho0 - 1| (bad_particle decides every particle this does not
 * pass, so the check names the same particles). */
static inline int surely_good(const sph_particles *p, size_t i, double rlo, double rhi,
                              const double *d) {
  const double x = p->x[i], y = p->y[i], rho = p->rho[i];
  const double z = (x - x) + (y - y) + (p->vx[i] - p->vx[i]) + (p->vy[i] - p->vy[i]) +
                   (rho - rho) + (p->p[i] - p->p[i]);
  return z == 0.0 && rho > rlo && rho < rhi &&
         (p->kind[i] != SPH_KIND_FLUID || !(x < d[0] || x > d[1] || y < d[2] || y > d[3]));
}

/* The blow-up check; the first offender in id order is named (a min
 * reduction over ids, exact in any order, then a serial look-up). */
static int check_state(sph_sim *s, sph_error *err) {
  const sph_particles *p = &s->p;
  const double lim = s->c->density_limit, rho0 = s->c->rho0;
  const double rlo = rho0 * (1.0 - lim) * (1.0 + 1e-9), rhi = rho0 * (1.0 + lim) * (1.0 - 1e-9);
  const double *d = s->domain;
  const long n = (long)p->n;
  int64_t first = INT64_MAX;
#pragma omp parallel if (n > SPH_OMP_MIN) reduction(min : first)
  {
    size_t lo, hi;
    sph_slice(slices(s), p->n, &lo, &hi);
    for (size_t i = lo; i < hi; i++)
      if (!surely_good(p, i, rlo, rhi, d) && p->id[i] < first && bad_particle(p, i, lim, rho0, d))
        first = p->id[i];
  }
  if (first == INT64_MAX) return 0;
  long worst = -1;
  for (long i = 0; i < n && worst < 0; i++)
    if (p->id[i] == first) worst = i;
  if (worst < 0) return 0;
  const size_t i = (size_t)worst;
  const char *why = bad_particle(p, i, lim, rho0, d);
  sph_error_set(err,
                "blow-up at step %ld, t = %.9g s: %s particle %lld: %s "
                "(x = %.6g, y = %.6g, vx = %.6g, vy = %.6g, rho = %.6g; allowed rho in "
                "[%.6g, %.6g], domain x [%.6g, %.6g] y [%.6g, %.6g])",
                s->steps, s->t, p->kind[i] == SPH_KIND_FLUID ? "fluid" : "wall",
                (long long)p->id[i], why, p->x[i], p->y[i], p->vx[i], p->vy[i], p->rho[i],
                rho0 * (1.0 - lim), rho0 * (1.0 + lim), d[0], d[1], d[2], d[3]);
  return SPH_BLOWUP;
}

int sph_sim_step(sph_sim *s, double t_target, sph_error *err) {
  const sph_case *c = s->c;
  const int xsph = c->xsph != 0.0;
  double dt; /* from the rates of the current state, computed by the last pass */
  switch (c->dt_rule) {
  case SPH_DT_FIXED:
    dt = c->dt_fixed;
    break;
  case SPH_DT_CFL:
    dt = sph_dt_cfl(&s->p, &s->fp.eos, c->h, c->dt_factor);
    break;
  case SPH_DT_PAPER_B:
  default:
    dt = s->dt_paper_b;
    break;
  }
  if (!(dt > 0.0) || !isfinite(dt))
    return sph_error_set(err, "blow-up at step %ld, t = %.9g s: time step is %g", s->steps, s->t,
                         dt),
           SPH_BLOWUP;
  int land = 0;
  if (s->t + dt >= t_target) {
    dt = t_target - s->t;
    land = 1;
  }
  s->t_saved = s->t; /* the stage (or the leap-frog) saves X^n in X0 */
  const double t_new = land ? t_target : s->t + dt;
  if (c->integrator == SPH_INTEGRATOR_LEAPFROG) {
    /* the rates of t^n drive the whole step: so do the ledger's powers */
    s->work_wall += dt * s->power_wall;
    s->drift_xsph += dt * s->power_xsph;
    s->impulse_x += dt * s->force_x;
    s->impulse_y += dt * s->force_y;
    sph_leapfrog_step(&s->p, dt, s->first_step, xsph, &s->fp.eos, slices(s));
    s->first_step = 0;
    move_walls(s, t_new);
  } else {
    sph_pc_half(&s->p, dt, xsph, &s->fp.eos, slices(s));
    move_walls(s, s->t + 0.5 * dt);
    if (pass(s, err)) return -1;
    /* X^{n+1} = X^n + dt F(X^{n+1/2}): the mid-step powers drive the step */
    s->work_wall += dt * s->power_wall;
    s->drift_xsph += dt * s->power_xsph;
    s->impulse_x += dt * s->force_x;
    s->impulse_y += dt * s->force_y;
    sph_pc_finish(&s->p, dt, xsph, &s->fp.eos, slices(s));
    move_walls(s, t_new);
  }
  wrap_periodic(s);
  s->t = t_new;
  s->last_dt = dt;
  s->steps++;
  if (c->density_filter != SPH_FILTER_NONE && s->steps % c->filter_every == 0 &&
      apply_filter(s, err))
    return -1;
  const int st = check_state(s, err);
  if (st) return st;
  /* rates (and flags) of the new state: the next step starts from them,
   * and a snapshot of this state carries flags that belong to it */
  s->resort = s->steps % SPH_RESORT_EVERY == 0;
  return pass(s, err);
}

double sph_sim_time(const sph_sim *s) { return s->t; }
long sph_sim_steps(const sph_sim *s) { return s->steps; }
double sph_sim_last_dt(const sph_sim *s) { return s->last_dt; }
const sph_case *sph_sim_case(const sph_sim *s) { return s->c; }
sph_particles *sph_sim_particles(sph_sim *s) { return &s->p; }
double sph_sim_floor(const sph_sim *s) { return s->floor_y; }
void sph_sim_domain(const sph_sim *s, double box[4]) { memcpy(box, s->domain, 4 * sizeof *box); }
void sph_sim_view(const sph_sim *s, double box[4]) { memcpy(box, s->view, 4 * sizeof *box); }

void sph_sim_diag(const sph_sim *s, sph_diag_row *row) {
  sph_diag_compute(&s->p, s->floor_y, 2.0 * s->c->dx, s->c->gravity, row);
  row->n_surface = s->detect ? (long)s->n_surface : -1;
  if (s->c->energy) {
    double u = 0.0;
    for (size_t i = 0; i < s->p.n; i++) u += s->p.mass[i] * s->p.u[i];
    row->ledger = 1;
    row->internal = u;
    row->boundary_work = s->work_wall;
    row->xsph_drift = s->drift_xsph;
    row->total = row->kinetic + row->potential + u - s->work_wall - s->drift_xsph;
    row->deviation = s->e0 != 0.0 ? (row->total - s->e0) / s->e0 : 0.0;
    const double ef = row->kinetic + row->potential + fluid_internal(s);
    row->fluid_deviation = s->e0_fluid != 0.0 ? (ef - s->e0_fluid) / s->e0_fluid : 0.0;
    row->momentum_residual_x = row->momentum_x - s->p0x - s->impulse_x;
    row->momentum_residual_y = row->momentum_y - s->p0y - s->impulse_y;
  }
  row->time = s->t;
  row->step = s->steps;
  row->dt = s->last_dt;
}

static void fill_meta(const sph_sim *s, sph_snapshot_meta *m, double t, long step) {
  memset(m, 0, sizeof *m);
  m->time = t;
  m->dt = s->last_dt;
  m->step = step;
  m->case_name = s->c->name;
  m->case_text = s->c->text;
  m->overrides = s->c->overrides;
  m->parameters = s->parameters;
  m->dx = s->c->dx;
  m->h = s->c->h;
  m->rho0 = s->c->rho0;
  memcpy(m->view, s->view, sizeof m->view);
  m->free_surface = s->detect;
}

int sph_sim_write_snapshot(const sph_sim *s, const char *path, sph_error *err) {
  sph_snapshot_meta m;
  fill_meta(s, &m, s->t, s->steps);
  return sph_snapshot_write(path, &m, &s->p, err);
}

int sph_sim_write_saved_snapshot(sph_sim *s, const char *path, sph_error *err) {
  /* a view of the store whose state arrays are the saved ones */
  sph_particles v = s->p;
  v.x = s->p.x0;
  v.y = s->p.y0;
  v.vx = s->p.vx0;
  v.vy = s->p.vy0;
  v.rho = s->p.rho0;
  v.u = s->p.u0;
  v.p = s->work.prho2; /* scratch: pressure of the saved state */
  for (size_t i = 0; i < v.n; i++) v.p[i] = sph_eos_pressure(&s->fp.eos, v.rho[i]);
  sph_snapshot_meta m;
  fill_meta(s, &m, s->t_saved, s->steps - 1);
  return sph_snapshot_write(path, &m, &v, err);
}

/* ---- restart (sph run --restart) -------------------------------------------
 * A snapshot written by sph_sim_write_run_snapshot carries, besides the
 * fields, what the next step reads that the fields do not hold: the
 * storage order (the grid's sort is stable, so the order within a cell,
 * and with it the order of every neighbour sum, depends on the history),
 * the leap-frog's half-step values and first-step flag, and the ledger's
 * time integrals. Everything else the step uses is either a function of
 * the case (set-up, rest positions and motion of walls, domain, initial
 * energies and momentum, all remade by sph_sim_create) or of the state in
 * that order (the rates, flags and step-rule inputs of the pass, which
 * sph_sim_restore reruns). So a restored sim steps bit for bit as the one
 * that wrote the snapshot. */

int sph_sim_write_run_snapshot(const sph_sim *s, const char *path, int64_t output_index,
                               const double *levels, size_t n_levels, sph_error *err) {
  sph_snapshot_meta m;
  fill_meta(s, &m, s->t, s->steps);
  sph_snapshot_restart r;
  memset(&r, 0, sizeof r);
  r.output_index = output_index;
  r.first_step = s->first_step;
  r.ledger[0] = s->work_wall;
  r.ledger[1] = s->drift_xsph;
  r.ledger[2] = s->impulse_x;
  r.ledger[3] = s->impulse_y;
  r.n_levels = n_levels;
  r.levels = levels;
  r.order = s->p.id;
  if (s->c->integrator == SPH_INTEGRATOR_LEAPFROG) {
    r.vxh = s->p.vxh;
    r.vyh = s->p.vyh;
    r.rhoh = s->p.rhoh;
    r.uh = s->p.uh;
  }
  m.restart = &r;
  return sph_snapshot_write(path, &m, &s->p, err);
}

/* The first line of a that differs from b, ignoring time.end (a restart
 * may run further); NULL if none. Lines are "key: value". */
static const char *first_difference(const char *a, const char *b, size_t *len) {
  for (;;) {
    while (!strncmp(a, "time.end:", 9)) a += strcspn(a, "\n") + (a[strcspn(a, "\n")] != 0);
    while (!strncmp(b, "time.end:", 9)) b += strcspn(b, "\n") + (b[strcspn(b, "\n")] != 0);
    if (!*a && !*b) return NULL;
    const size_t la = strcspn(a, "\n"), lb = strcspn(b, "\n");
    if (la != lb || memcmp(a, b, la)) {
      *len = la ? la : lb;
      return la ? a : b;
    }
    a += la + (a[la] != 0);
    b += lb + (b[lb] != 0);
  }
}

static int restore_state(sph_sim *s, const sph_snapshot *snap, const sph_particles *q,
                         const sph_snapshot_restart_data *rd, sph_error *err) {
  const char *path = sph_snapshot_path(snap);
  const size_t n = s->p.n;
  if (q->n != n)
    return sph_error_set(err, "%s: holds %zu particles, the case makes %zu: not a snapshot of "
                              "this case",
                         path, q->n, n);
  const char *params = sph_snapshot_text(snap, "parameters");
  size_t dlen = 0;
  const char *diff = params ? first_difference(params, s->parameters, &dlen) : NULL;
  if (!params || diff)
    return sph_error_set(err, "%s: written with other parameters than the case (%s%.*s); "
                              "only time.end may change on a restart",
                         path, params ? "first difference: " : "no parameters attribute",
                         (int)dlen, diff ? diff : "");
  const int leapfrog = s->c->integrator == SPH_INTEGRATOR_LEAPFROG;
  if (leapfrog && !rd->first_step && !rd->vxh)
    return sph_error_set(err, "%s: a leap-frog run's snapshot without the half-step values "
                              "(/restart/vxh, vyh, rhoh, uh)",
                         path);
  size_t *pos = malloc(n * sizeof *pos), *perm = malloc(n * sizeof *perm);
  void *work = malloc(n * sizeof(double));
  if (!pos || !perm || !work) {
    free(pos);
    free(perm);
    free(work);
    return sph_error_set(err, "out of memory");
  }
  for (size_t i = 0; i < n; i++) pos[s->p.id[i]] = i;
  for (size_t k = 0; k < n; k++) perm[k] = pos[rd->order[k]];
  sph_particles_permute(&s->p, perm, work);
  free(pos);
  free(perm);
  free(work);
  sph_particles *p = &s->p;
  for (size_t k = 0; k < n; k++) {
    const size_t i = (size_t)p->id[k]; /* row of the snapshot */
    if (q->kind[i] != p->kind[k] || q->mass[i] != p->mass[k])
      return sph_error_set(err, "%s: particle %zu is a %s of mass %g, the case makes a %s of "
                                "mass %g: not a snapshot of this case",
                           path, i, q->kind[i] == SPH_KIND_FLUID ? "fluid particle" : "wall particle",
                           q->mass[i], p->kind[k] == SPH_KIND_FLUID ? "fluid particle" : "wall particle",
                           p->mass[k]);
    p->x[k] = q->x[i];
    p->y[k] = q->y[i];
    p->vx[k] = q->vx[i];
    p->vy[k] = q->vy[i];
    p->rho[k] = q->rho[i];
    p->p[k] = q->p[i];
    p->h[k] = q->h[i];
    p->u[k] = q->u[i];
    p->flags[k] = (uint8_t)((p->flags[k] & ~SPH_FLAG_FREE_SURFACE) | (q->flags[i] & 1u));
    if (rd->vxh) {
      p->vxh[k] = rd->vxh[k];
      p->vyh[k] = rd->vyh[k];
      p->rhoh[k] = rd->rhoh[k];
      p->uh[k] = rd->uh[k];
    }
  }
  s->t = sph_snapshot_time(snap);
  s->steps = (long)sph_snapshot_step(snap);
  s->last_dt = sph_snapshot_dt(snap);
  s->first_step = (int)rd->first_step;
  s->work_wall = rd->ledger[0];
  s->drift_xsph = rd->ledger[1];
  s->impulse_x = rd->ledger[2];
  s->impulse_y = rd->ledger[3];
  const int st = check_state(s, err);
  if (st) return st;
  return pass(s, err); /* the rates, flags and step-rule inputs of this state */
}

int sph_sim_restore(sph_sim *s, const char *path, sph_snapshot_restart_data *rd,
                    sph_error *err) {
  memset(rd, 0, sizeof *rd);
  sph_snapshot *snap;
  if (sph_snapshot_open(path, &snap, err)) return -1;
  sph_particles q;
  int rc = sph_snapshot_read_particles(snap, &q, err);
  if (rc == 0) {
    rc = sph_snapshot_read_restart(snap, rd, err);
    if (rc == 0) rc = restore_state(s, snap, &q, rd, err);
    sph_particles_free(&q);
  }
  sph_snapshot_close(snap);
  if (rc) sph_snapshot_restart_free(rd);
  return rc;
}
