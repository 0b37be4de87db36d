/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_decomp.c - the domain decomposition (src/neighbours/decomp.h):
 *   - the Hilbert curve visits every cell of a cube once, each step to a
 *     face neighbour;
 *   - the cut balances the particles, and is the same for the keys in any
 *     order (a pure function of the state); the cut by weights is its
 *     definition's, made plainly (every particle sorted);
 *   - the halo holds every particle within `depth` cells of a rank's own;
 *   - the particles in the cells around each, which the cut's weights
 *     are made from, are counted right (a periodic axis too);
 *   - ranks emulated in one process: a rank that holds only its own
 *     particles and its ghosts computes its own particles' rates bit for bit
 *     as the whole set does, for 2, 3 and 7 ranks, on the schemes, walls and
 *     terms the solver has (the premise of running on many processes with
 *     the same bits: doc/method.md, Ranks).
 * Built for 2-D (test_decomp) and 3-D (test_decomp_3d).
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "neighbours/decomp.h"
#include "physics/kernel.h"
#include "solver/sim_internal.h"
#include "testsim.h"
#include "testutil.h"

static void test_hilbert_visits_every_cell_once(void) {
  const int bits = 3;
  const size_t side = (size_t)1 << bits;
  size_t n = 1;
  for (int a = 0; a < SPH_DIM; a++)
    n *= side;
  uint32_t(*at)[SPH_DIM] = calloc(n, sizeof *at);
  unsigned char *seen = calloc(n, 1);
  CU_ASSERT_FATAL(at && seen);
  for (size_t k = 0; k < n; k++) {
    uint32_t c[SPH_DIM];
    size_t rest = k;
    for (int a = 0; a < SPH_DIM; a++)
      c[a] = (uint32_t)(rest % side), rest /= side;
    const uint64_t key = sph_decomp_hilbert(c, bits);
    CU_ASSERT_FATAL(key < n);
    CU_ASSERT(!seen[key]);
    seen[key] = 1;
    memcpy(at[key], c, sizeof c);
  }
  int steps_ok = 1;
  for (size_t k = 1; k < n; k++) {
    long dist = 0;
    for (int a = 0; a < SPH_DIM; a++)
      dist += labs((long)at[k][a] - (long)at[k - 1][a]);
    steps_ok &= dist == 1;
  }
  CU_ASSERT(steps_ok);
  free(at);
  free(seen);
}

static void test_cut_is_balanced_and_pure(void) {
  enum { N = 10007 };
  uint64_t *keys = malloc(N * sizeof *keys), first[7], again[7];
  CU_ASSERT_FATAL(keys != NULL);
  unsigned long long seed = 12345;
  for (int i = 0; i < N; i++) /* about 3 particles a key */
    keys[i] = (uint64_t)(sph_test_uniform(&seed) * 3300.0);
  for (int ranks = 1; ranks <= 7; ranks++) {
    sph_error err;
    CU_ASSERT_FATAL(sph_decomp_cut(keys, N, ranks, first, &err) == 0);
    long count[7] = {0};
    for (int i = 0; i < N; i++)
      count[sph_decomp_owner(first, ranks, keys[i])]++;
    for (int r = 0; r < ranks; r++) /* within the largest key's share of N / ranks */
      CU_ASSERT(labs(count[r] - N / ranks) <= 16);
    for (int i = N - 1; i > 0; i--) { /* shuffled: the same cut */
      const int j = (int)(sph_test_uniform(&seed) * (i + 1));
      const uint64_t t = keys[i];
      keys[i] = keys[j], keys[j] = t;
    }
    CU_ASSERT_FATAL(sph_decomp_cut(keys, N, ranks, again, &err) == 0);
    CU_ASSERT(memcmp(first, again, (size_t)ranks * sizeof *first) == 0);
  }
  free(keys);
}

/* The weighted cut (sph_decomp_cut_weighted) against its definition made
 * plainly: every particle sorted by key, then weight, and rank r from the
 * key of the first particle before which the weights reach r / ranks of
 * the whole; on keys in runs (as a store sorted by cells gives them: a key
 * merges several runs) and shuffled, with weights from 1 to 1000, for 1
 * to 7 ranks; then the same cut for the particles in any order. The cut
 * with uneven shares (sph_decomp_cut_shares) the same way: rank r from
 * where the weights reach the shares of the ranks before it; shares of
 * 0.1 and 0.9 leave the first rank a tenth of the weights. */
typedef struct key_weight {
  uint64_t key;
  uint32_t w;
} key_weight;

static int cmp_key_weight(const void *a, const void *b) {
  const key_weight *x = a, *y = b;
  if (x->key != y->key) return (x->key > y->key) - (x->key < y->key);
  return (x->w > y->w) - (x->w < y->w);
}

static void plain_cut(const uint64_t *keys, const uint32_t *w, size_t n, int ranks,
                      const double *share, uint64_t *first) {
  key_weight *s = malloc(n * sizeof *s);
  uint64_t total = 0, sum = 0;
  for (size_t i = 0; i < n; i++)
    s[i] = (key_weight){keys[i], w[i]}, total += w[i];
  qsort(s, n, sizeof *s, cmp_key_weight);
  size_t p = 0;
  first[0] = 0;
  double below = 0.0;
  for (int r = 1; r < ranks; r++) {
    if (share) below += share[r - 1];
    while (p < n && (share ? (double)sum < below * (double)total
                           : sum * (uint64_t)ranks < (uint64_t)r * total))
      sum += s[p++].w;
    first[r] = p < n ? s[p].key : s[n - 1].key + 1;
    if (first[r] < first[r - 1]) first[r] = first[r - 1];
  }
  free(s);
}

static void test_weighted_cut(void) {
  enum { N = 5003 };
  uint64_t *keys = malloc(N * sizeof *keys), first[7], plain[7];
  uint32_t *w = malloc(N * sizeof *w);
  CU_ASSERT_FATAL(keys && w);
  unsigned long long seed = 4242;
  for (int trial = 0; trial < 40; trial++) {
    const double spread = trial % 2 ? 40.0 : 900.0; /* few keys (long runs) or many */
    for (int i = 0; i < N;) {                       /* a run of 1 to 8 particles of one key */
      const uint64_t k = (uint64_t)(sph_test_uniform(&seed) * spread);
      const int run = 1 + (int)(sph_test_uniform(&seed) * 8.0);
      for (int j = 0; j < run && i < N; j++, i++)
        keys[i] = k, w[i] = 1 + (uint32_t)(sph_test_uniform(&seed) * (trial % 4 < 2 ? 999.0 : 2.0));
    }
    for (int ranks = 1; ranks <= 7; ranks++) {
      sph_error err;
      CU_ASSERT_FATAL(sph_decomp_cut_weighted(keys, w, N, ranks, first, &err) == 0);
      plain_cut(keys, w, N, ranks, NULL, plain);
      CU_ASSERT(memcmp(first, plain, (size_t)ranks * sizeof *first) == 0);
      /* uneven shares (the cut by measured work, solver/ranks.c) */
      double share[7], all = 0.0;
      for (int r = 0; r < ranks; r++)
        all += share[r] = 0.2 + sph_test_uniform(&seed);
      for (int r = 0; r < ranks; r++)
        share[r] /= all;
      CU_ASSERT_FATAL(sph_decomp_cut_shares(keys, w, N, ranks, share, first, &err) == 0);
      plain_cut(keys, w, N, ranks, share, plain);
      CU_ASSERT(memcmp(first, plain, (size_t)ranks * sizeof *first) == 0);
    }
    for (int i = N - 1; i > 0; i--) { /* shuffled: the same cut */
      const int j = (int)(sph_test_uniform(&seed) * (i + 1));
      const uint64_t t = keys[i];
      const uint32_t tw = w[i];
      keys[i] = keys[j], keys[j] = t, w[i] = w[j], w[j] = tw;
    }
    sph_error err;
    CU_ASSERT_FATAL(sph_decomp_cut_weighted(keys, w, N, 5, first, &err) == 0);
    plain_cut(keys, w, N, 5, NULL, plain);
    CU_ASSERT(memcmp(first, plain, 5 * sizeof *first) == 0);
    /* shares of 0.1 and 0.9: the first rank's keys weigh a tenth of the whole, to within the
     * weight of the keys at the cut (pure: the same cut shuffled) */
    const double tenth[2] = {0.1, 0.9};
    CU_ASSERT_FATAL(sph_decomp_cut_shares(keys, w, N, 2, tenth, first, &err) == 0);
    plain_cut(keys, w, N, 2, tenth, plain);
    CU_ASSERT(memcmp(first, plain, 2 * sizeof *first) == 0);
    uint64_t below = 0, total = 0, last = 0, at_first = 0, at_last = 0; /* the keys either side */
    for (int i = 0; i < N; i++)
      if (keys[i] < first[1] && keys[i] >= last) last = keys[i];
    for (int i = 0; i < N; i++) {
      total += w[i];
      if (keys[i] < first[1]) below += w[i];
      if (keys[i] == first[1]) at_first += w[i];
      if (keys[i] == last) at_last += w[i];
    }
    CU_ASSERT(below > 0 && fabs((double)below - 0.1 * (double)total) <=
                               (double)(at_first > at_last ? at_first : at_last));
  }
  free(keys);
  free(w);
}

/* The counts the cut's weights are made from (sph_decomp_block_counts):
 * the particles in the 3^D cells around each, of every kind and of one,
 * against counting them pair by pair: 400 particles at random (seeded),
 * fluid and walls, in a box of cells and with a periodic axis of 1, 2 and
 * 5 cells (each cell of the period counted once). */
static void test_block_counts(void) {
  const long periods[] = {0, 1, 2, 5};
  for (int c = 0; c < 4; c++) {
    const double side = 0.2;
    const sph_decomp_grid g = {side, periods[c] ? 1 : 0, 0.0, periods[c] ? periods[c] : 1};
    sph_particles p;
    sph_error err;
    CU_ASSERT_FATAL(sph_particles_init(&p, 400, &err) == 0);
    unsigned long long r = 12345u + (unsigned)c;
    const double v[SPH_DIM] = {0.0};
    for (int k = 0; k < 400; k++) {
      double x[SPH_DIM];
      for (int a = 0; a < SPH_DIM; a++) {
        r = r * 6364136223846793005ull + 1442695040888963407ull;
        const double span = a == 0 && periods[c] ? side * (double)periods[c] : 1.3;
        x[a] = (double)(r >> 11) / 9007199254740992.0 * span;
      }
      const int32_t kind = (r >> 7 & 3) ? SPH_KIND_FLUID : SPH_KIND_WALL;
      CU_ASSERT_FATAL(sph_particles_add_at(&p, x, v, 1000.0, 1.0, 0.1, kind, &err) >= 0);
    }
    uint32_t *all = malloc(p.n * sizeof *all), *fluid = malloc(p.n * sizeof *fluid);
    uint32_t(*cell)[SPH_DIM] = malloc(p.n * sizeof *cell);
    CU_ASSERT_FATAL(all && fluid && cell);
    CU_ASSERT_FATAL(sph_decomp_block_counts(&g, &p, SPH_KIND_FLUID, all, fluid, &err) == 0);
    for (size_t i = 0; i < p.n; i++) {
      double x[SPH_DIM];
      for (int a = 0; a < SPH_DIM; a++)
        x[a] = p.pos[a][i];
      CU_ASSERT_FATAL(sph_decomp_cell(&g, x, cell[i]) == 0);
    }
    int bad = 0;
    for (size_t i = 0; i < p.n; i++) {
      uint32_t n_all = 0, n_fluid = 0;
      for (size_t j = 0; j < p.n; j++) {
        int near = 1;
        for (int a = 0; a < SPH_DIM; a++) {
          long d = labs((long)cell[i][a] - (long)cell[j][a]);
          if (a == 0 && periods[c] && periods[c] - d < d)
            d = periods[c] - d; /* around the period */
          near = near && d <= 1;
        }
        n_all += (uint32_t)near;
        n_fluid += (uint32_t)(near && p.kind[j] == SPH_KIND_FLUID);
      }
      bad += all[i] != n_all || fluid[i] != n_fluid;
    }
    if (bad) printf("\n  period of %ld cells: %d particles' counts wrong", periods[c], bad);
    CU_ASSERT_EQUAL(bad, 0);
    free(all);
    free(fluid);
    free(cell);
    sph_particles_free(&p);
  }
}

/* ---- ranks emulated in one process ----------------------------------------- */

static const char *const ranks_cases[][2] = {
#if SPH_DIM == 2
    {"cases/martin_moyce_coarse.yaml", ""}, /* paper B's scheme, dynamic walls, fourtakas */
    {"cases/lobovsky_h300.yaml", "numerics.dx=0.015"},     /* the default scheme: adami walls */
    {"cases/wet_bed_dam_break.yaml", "numerics.dx=0.012"}, /* stress tensor, ledger, a gate */
    {"cases/inclined_plane.yaml", ""},                     /* periodic, free surface */
    {"cases/hydrostatic_tank.yaml", "geometry.tank.boundary=mirror"}, /* mirror walls */
    {"cases/sps_dam_break_coarse.yaml", ""},                          /* SPS turbulence */
#else
    {"cases/hydrostatic_3d.yaml", ""},
    {"cases/lobovsky_h300_3d.yaml", "numerics.dx=0.02"},
#endif
};

/* Opens the case and runs `steps` steps (the last pass sorts the store when
 * steps is a multiple of the resort interval). */
static sph_sim *run_to(const char *rel, const char *set, long steps, sph_case *c) {
  const char *sets[1] = {set};
  sph_sim *s;
  if (sph_test_open_sim(rel, sets, *set ? 1 : 0, c, &s)) return NULL;
  sph_error err;
  while (sph_sim_steps(s) < steps)
    if (sph_sim_step(s, INFINITY, &err)) {
      printf("\n  %s: %s", rel, err.msg);
      sph_sim_free(s);
      sph_case_free(c);
      return NULL;
    }
  return s;
}

static int same_double(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* Whether particle i of q has the rates of particle j of p, bit for bit. */
static int same_rates(const sph_particles *p, size_t j, const sph_particles *q, size_t i, int xsph,
                      const char **what) {
  for (int a = 0; a < SPH_DIM; a++) {
    if (!same_double(p->acc[a][j], q->acc[a][i])) return *what = "acceleration", 0;
    if (xsph && !same_double(p->xsph[a][j], q->xsph[a][i])) return *what = "XSPH velocity", 0;
  }
  if (!same_double(p->drho[j], q->drho[i])) return *what = "drho/dt", 0;
  if ((p->live & SPH_ARRAYS_HEAT) && !same_double(p->du[j], q->du[i])) return *what = "du/dt", 0;
  if (!same_double(p->rho[j], q->rho[i])) return *what = "density", 0;
  if (!same_double(p->p[j], q->p[i])) return *what = "pressure", 0;
  return 1;
}

/* Runs the case to a sorting step, then emulates each rank count with
 * ghosts `depth` cells deep, those within `rows` cells of the rank's own
 * and of a kind in `kinds` (bit 1 << SPH_KIND_*) with rows of their own in
 * the neighbour list, the others with empty rows (grid.h, no_row); returns
 * the number of particles whose rates differ from the whole set's
 * (printing the first). */
#define ALL_KINDS (1u << SPH_KIND_FLUID | 1u << SPH_KIND_WALL | 1u << SPH_KIND_MIRROR)
static long emulate(const char *rel, const char *set, int depth, int rows, unsigned kinds,
                    int quiet) {
  const long steps = 40; /* a step whose end-of-step pass sorts the store */
  sph_case cf;
  sph_sim *full = run_to(rel, set, steps, &cf);
  CU_ASSERT_FATAL(full != NULL);
  const sph_particles *pf = sph_sim_particles(full);
  const size_t n = pf->n;
  const double side = (SPH_CUBIC_SUPPORT * cf.h) * 1.25;
  const sph_decomp_grid g = {
      side, cf.periodic ? 1 + cf.periodic_axis : 0, cf.periodic ? cf.periodic_range[0] : 0.0,
      cf.periodic ? (long)floor((cf.periodic_range[1] - cf.periodic_range[0]) / side + 1e-9) : 0};
  uint64_t *keys = malloc(n * sizeof *keys);
  unsigned char *mark = malloc(n);
  long max_id = 0;
  for (size_t i = 0; i < n; i++)
    if (pf->id[i] > max_id) max_id = (long)pf->id[i];
  long *where = malloc(((size_t)max_id + 1) * sizeof *where);
  unsigned char *no_row = malloc((size_t)max_id + 1);
  CU_ASSERT_FATAL(keys && mark && where && no_row);
  for (size_t i = 0; i < n; i++)
    where[pf->id[i]] = (long)i;
  sph_error err;
  CU_ASSERT_FATAL(sph_decomp_keys(&g, pf, keys, &err) == 0);
  static const int rank_counts[] = {2, 3, 7};
  long differ = 0;
  for (size_t rc = 0; rc < sizeof rank_counts / sizeof *rank_counts; rc++) {
    const int ranks = rank_counts[rc];
    uint64_t first[8];
    CU_ASSERT_FATAL(sph_decomp_cut(keys, n, ranks, first, &err) == 0);
    long owned_all = 0, ghosts_all = 0, bad = 0;
    for (int r = 0; r < ranks; r++) {
      const long ghosts =
          sph_decomp_halo(&g, pf, keys, first, ranks, r, depth, rows, kinds, mark, &err);
      CU_ASSERT_FATAL(ghosts >= 0);
      sph_case cr;
      sph_sim *s = run_to(rel, set, steps, &cr);
      CU_ASSERT_FATAL(s != NULL);
      sph_particles *q = sph_sim_particles(s);
      CU_ASSERT_FATAL(q->n == n);
      size_t k = 0;
      long owned = 0;
      for (size_t i = 0; i < n; i++) {
        CU_ASSERT_FATAL(q->id[i] == pf->id[i]); /* the same run: the same store */
        no_row[pf->id[i]] = mark[i] == 3;
        if (!mark[i]) continue;
        owned += mark[i] == 1;
        sph_particles_move(q, k++, i);
      }
      s->nl.no_row = no_row, s->nl.no_row_n = (size_t)max_id + 1;
      q->n = k;
      s->resort = 1; /* the pass of the full run sorted the store */
      CU_ASSERT_FATAL(sph_sim_pass(s, &err) == 0);
      for (size_t i = 0; i < q->n; i++) {
        const size_t j = (size_t)where[q->id[i]];
        const char *what = "";
        if (mark[j] != 1 || same_rates(pf, j, q, i, cf.xsph != 0.0, &what)) continue;
        if (!bad && !quiet)
          printf("\n  %s, %d ranks, rank %d: particle %lld's %s differs", rel, ranks, r,
                 (long long)q->id[i], what);
        bad++;
      }
      owned_all += owned;
      ghosts_all += ghosts;
      sph_sim_free(s);
      sph_case_free(&cr);
    }
    if (!quiet)
      printf("\n  %s, %d ranks, ghosts %d cells deep (rows %d%s): %ld owned, %ld ghosts (%.2f "
             "a particle), %s",
             rel, ranks, depth, rows, kinds == ALL_KINDS ? "" : ", some kinds", owned_all,
             ghosts_all, (double)ghosts_all / (double)n,
             bad ? "DIFFERENT" : "every rate identical");
    CU_ASSERT(owned_all == (long)n);
    differ += bad;
  }
  free(keys);
  free(mark);
  free(where);
  free(no_row);
  sph_sim_free(full);
  sph_case_free(&cf);
  return differ;
}

/* Ghosts SPH_HALO_DEPTH cells deep (cells 1.25 supports wide), rows for
 * those within the cells the solver gives them (sph_sim_ranks_row_depth:
 * one, or all of them where a chain of passes is a support longer) and of
 * the kinds it gives them to (sph_sim_ranks_row_kinds): every rate the same
 * bits. The least depth that does it with rows for every ghost, and the
 * least row depth, are printed for each case; a rank without ghosts, one
 * with rows for its own particles only, and where the solver gives rows to
 * the walls alone, one with rows for every kind but the walls, must differ
 * (the comparison can fail). */
#define SPH_HALO_DEPTH 3
static void test_emulated_ranks(void) {
  int need_rows = 0, walls_only = 0; /* cases whose ghosts need rows; the walls' alone */
  for (size_t k = 0; k < sizeof ranks_cases / sizeof *ranks_cases; k++) {
    const char *rel = ranks_cases[k][0], *set = ranks_cases[k][1];
    sph_case c;
    sph_sim *s = run_to(rel, set, 0, &c);
    CU_ASSERT_FATAL(s != NULL);
    const int given = sph_sim_ranks_row_depth(s, SPH_HALO_DEPTH);
    const unsigned kinds = sph_sim_ranks_row_kinds(s);
    sph_sim_free(s);
    sph_case_free(&c);
    CU_ASSERT(emulate(rel, set, SPH_HALO_DEPTH, given, kinds, 0) == 0);
    if (SPH_DIM == 3 && k > 0) continue; /* (the searches on the first 3-D case: time) */
    int least = SPH_HALO_DEPTH;
    while (least > 0 && emulate(rel, set, least - 1, least - 1, ALL_KINDS, 1) == 0)
      least--;
    printf("\n  %s: the least depth with the same bits: %d cell(s)", rel, least);
    CU_ASSERT(least > 0);
    if (SPH_DIM == 3) continue; /* (the rows' search in 2-D: in 3-D it would take a minute) */
    int rows = given;
    while (rows > 0 && emulate(rel, set, SPH_HALO_DEPTH, rows - 1, kinds, 1) == 0)
      rows--;
    printf("; rows %d cell(s) deep (the solver's: %d)", rows, given);
    need_rows += rows > 0;
    if (kinds == 1u << SPH_KIND_WALL) { /* the walls' rows are what the fluid reads */
      const long d =
          emulate(rel, set, SPH_HALO_DEPTH, given, ALL_KINDS & ~(1u << SPH_KIND_WALL), 1);
      printf("; rows for the walls alone (with every kind but the walls': %ld differ)", d);
      CU_ASSERT(d > 0);
      walls_only++;
    }
  }
  CU_ASSERT(SPH_DIM == 3 || (need_rows > 0 && walls_only > 0));
}

int main(void) {
  CU_TestInfo tests[] = {
      {"the Hilbert curve visits every cell once", test_hilbert_visits_every_cell_once},
      {"the cut is balanced and pure", test_cut_is_balanced_and_pure},
      {"the weighted cut is its definition's", test_weighted_cut},
      {"the particles around each are counted", test_block_counts},
      {"ranks emulated in one process compute the same bits", test_emulated_ranks},
      CU_TEST_INFO_NULL};
  return sph_test_main(SPH_DIM == 2 ? "decomp" : "decomp_3d", tests);
}
