/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_outflow.c - fluid particles that leave the domain taken out of the run
 * (geometry.leaving: remove; src/solver/outflow.h, doc/case-files.md).
 *
 * 1. The removal on a hand-made store: only fluid outside the domain goes (a wall particle
 *    outside stays, a fluid particle with a NaN position stays for the blow-up check to
 *    name); the survivors keep their order in storage and in id, their ids become 0..n-1,
 *    origin[] gives each one's id at creation, also after a second removal; the mass,
 *    momentum and energy booked are the removed particles' own, to the last bit.
 * 2. The key: `stop` by default, listed in the run's parameters only as `remove`, any other
 *    value refused with the key's name and the choices.
 * 3. A run (tests/data/restart_outflow.yaml: water thrown at 2.5 m/s over a tank's 5 cm
 *    wall, the default scheme, the ledger on, 0.4 s): more than 20 particles leave and the
 *    run goes on; at every step mass + mass_removed is the initial mass (to 1e-12) and the
 *    diagnostics' n_fluid + n_removed the initial count; the energy balance, which books what
 *    left, closes to 1e-4 of E0 and the momentum balance to 1e-3 of the initial momentum (the
 *    same run's error before any particle leaves: measured 2.4e-5 and 4.8e-4); the XDMF index
 *    gives each snapshot its own particle count, and each snapshot's particles are its count.
 *    With `stop` the same case stops as a blow-up that names the particle and the domain.
 * Threads and restart: test_determinism and test_restart run the same fixture.
 */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/snapshot.h"
#include "solver/outflow.h"
#include "testsim.h"
#include "testutil.h"

/* A store of 6 particles: ids 5 4 3 2 1 0 in storage order. */
static void make_store(sph_particles *p) {
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(p, 8, &err) == 0);
  p->n = 6;
  /*                       0     1    2     3    4     5  (storage) */
  static const double x[] = {0.5, 2.0, 0.2, -1.0, 0.3, 3.0};
  static const double y[] = {0.5, 0.1, 0.2, 0.4, 0.3, 0.0};
  static const int32_t kind[] = {0, 0, 0, 1, 0, 0};
  for (size_t i = 0; i < 6; i++) {
    p->x[i] = x[i];
    p->y[i] = y[i];
    SPH_IF3(p->z[i] = 0.5;)
    p->vx[i] = 0.1 * (double)(i + 1);
    p->vy[i] = -0.3 * (double)i;
    SPH_IF3(p->vz[i] = 0.05;)
    p->mass[i] = 1.0 + 0.25 * (double)i;
    p->u[i] = 2.0 * (double)i;
    p->rho[i] = 1000.0 + (double)i;
    p->kind[i] = kind[i];
    p->id[i] = (int64_t)(5 - i);
  }
}

static void test_remove(void) {
  sph_particles p;
  make_store(&p);
  p.y[4] = NAN; /* id 1: not finite, left for the blow-up check */
  const double dom[2 * SPH_DIM] = {0.0, 1.0, 0.0, 1.0 SPH_IF3(, 0.0, 1.0)};
  const double grav[2] = {0.0, -9.81}; /* (a 2-D test) */
  sph_outflow o = {0};
  sph_error err;
  const uint64_t order = p.order;
  /* storage 1 (id 4, x = 2) and 5 (id 0, x = 3) are fluid outside; 3 (id 2) is a wall */
  CU_ASSERT_EQUAL(sph_outflow_remove(&o, &p, dom, grav, 0.0, &err), 2);
  CU_ASSERT_EQUAL(p.n, 4);
  CU_ASSERT(p.order != order);
  /* survivors in storage order: old storage 0, 2, 3, 4 (ids 5, 3, 2, 1) -> ids 3, 2, 1, 0 */
  static const int64_t ids[] = {3, 2, 1, 0};
  static const double xs[] = {0.5, 0.2, -1.0, 0.3};
  for (size_t i = 0; i < 4; i++) {
    CU_ASSERT_EQUAL(p.id[i], ids[i]);
    CU_ASSERT_EQUAL(p.x[i], xs[i]);
  }
  CU_ASSERT_EQUAL(p.kind[2], SPH_KIND_WALL);
  CU_ASSERT(isnan(p.y[3]));
  /* creation ids of ids 0..3: 1, 2, 3, 5 */
  CU_ASSERT_FATAL(o.origin != NULL && o.n_origin == 4);
  CU_ASSERT(o.origin[0] == 1 && o.origin[1] == 2 && o.origin[2] == 3 && o.origin[3] == 5);
  /* booked in storage order: old storage 1 then 5 */
  const double m1 = 1.25, m5 = 2.25;
  CU_ASSERT_EQUAL(o.count, 2);
  CU_ASSERT_EQUAL(o.mass, 0.0 + m1 + m5);
  const double vx1 = 0.1 * 2.0, vy1 = -0.3 * 1.0, vx5 = 0.1 * 6.0, vy5 = -0.3 * 5.0;
  CU_ASSERT_EQUAL(o.momentum[0], 0.0 + m1 * vx1 + m5 * vx5);
  CU_ASSERT_EQUAL(o.momentum[1], 0.0 + m1 * vy1 + m5 * vy5);
  const double e1 = 0.5 * m1 * (vx1 * vx1 + vy1 * vy1) + -m1 * (0.0 * 2.0 + -9.81 * 0.1) + m1 * 2.0;
  const double e5 =
      0.5 * m5 * (vx5 * vx5 + vy5 * vy5) + -m5 * (0.0 * 3.0 + -9.81 * 0.0) + m5 * 10.0;
  CU_ASSERT_EQUAL(o.energy, 0.0 + e1 + e5);
  /* a second removal: storage 1 (id 2, creation id 3) moved out */
  p.x[1] = 5.0;
  CU_ASSERT_EQUAL(sph_outflow_remove(&o, &p, dom, grav, 0.0, &err), 1);
  CU_ASSERT_EQUAL(p.n, 3);
  CU_ASSERT(p.id[0] == 2 && p.id[1] == 1 && p.id[2] == 0);
  CU_ASSERT_FATAL(o.n_origin == 3);
  CU_ASSERT(o.origin[0] == 1 && o.origin[1] == 2 && o.origin[2] == 5);
  CU_ASSERT_EQUAL(o.count, 3);
  /* nothing outside: nothing changes */
  const uint64_t before = p.order;
  CU_ASSERT_EQUAL(sph_outflow_remove(&o, &p, dom, grav, 0.0, &err), 0);
  CU_ASSERT(p.order == before && p.n == 3 && o.count == 3);
  /* a restart takes the same particles out of the store the case makes afresh */
  sph_particles q;
  make_store(&q);
  sph_outflow r = {0};
  double saved[SPH_OUTFLOW_SAVED];
  sph_outflow_save(&o, saved);
  CU_ASSERT_EQUAL(sph_outflow_restore(&r, &q, o.origin, o.n_origin, saved, "s.h5", &err), 0);
  CU_ASSERT_EQUAL(q.n, 3);
  for (size_t i = 0; i < 3; i++) {
    CU_ASSERT_EQUAL(q.id[i], p.id[i]);
    CU_ASSERT_EQUAL(q.x[i], p.x[i] == 5.0 ? q.x[i] : p.x[i]);
  }
  CU_ASSERT(r.count == 3 && r.mass == o.mass && r.energy == o.energy);
  /* a record that names a wall particle as gone, or ids out of order, is refused */
  sph_particles w;
  make_store(&w);
  const int64_t no_wall[] = {0, 1, 3, 4, 5}; /* leaves out id 2, a wall */
  saved[0] = 1.0;
  CU_ASSERT(sph_outflow_restore(&r, &w, no_wall, 5, saved, "s.h5", &err) != 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "a wall particle"));
  const int64_t unordered[] = {0, 3, 1};
  saved[0] = 3.0;
  CU_ASSERT(sph_outflow_restore(&r, &w, unordered, 3, saved, "s.h5", &err) != 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "s.h5: dataset /restart/origin holds 1 at row 2"));
  sph_outflow_free(&o);
  sph_outflow_free(&r);
  sph_particles_free(&p);
  sph_particles_free(&q);
  sph_particles_free(&w);
}

/* The fixture's geometry.leaving with the overrides set, and whether the run's parameters
 * list it. */
static int leaving_of(const char *const *set, size_t n, int *listed) {
  sph_case c;
  sph_sim *s;
  CU_ASSERT_FATAL(sph_test_open_sim("tests/data/restart_outflow.yaml", set, n, &c, &s) == 0);
  const int v = (int)c.leaving;
  char *d = sph_case_describe(&c);
  CU_ASSERT_FATAL(d != NULL);
  *listed = strstr(d, "geometry.leaving: remove\n") != NULL;
  CU_ASSERT(strstr(d, "geometry.leaving: stop") == NULL);
  free(d);
  sph_sim_free(s);
  sph_case_free(&c);
  return v;
}

static void test_key(void) {
  const char *stop[] = {"geometry.leaving=stop"};
  int listed;
  CU_ASSERT_EQUAL(leaving_of(NULL, 0, &listed), SPH_LEAVING_REMOVE);
  CU_ASSERT(listed);
  CU_ASSERT_EQUAL(leaving_of(stop, 1, &listed), SPH_LEAVING_STOP);
  CU_ASSERT(!listed);
  char *dir = sph_test_tmpdir(), args[8192], out[8192];
  snprintf(args, sizeof args, "run -q '%s' -o '%s/run' --set geometry.leaving=vanish",
           sph_test_src("tests/data/restart_outflow.yaml"), dir);
  CU_ASSERT_EQUAL(sph_test_sph(args, dir, out, sizeof out), 1);
  CU_ASSERT_PTR_NOT_NULL(strstr(out, "geometry.leaving"));
  CU_ASSERT_PTR_NOT_NULL(strstr(out, "stop, remove"));
  /* the default is to stop: a case without the key lists no geometry.leaving */
  sph_case c;
  sph_sim *s;
  CU_ASSERT_FATAL(sph_test_open_sim("tests/data/restart_no_tension.yaml", NULL, 0, &c, &s) == 0);
  CU_ASSERT_EQUAL(c.leaving, SPH_LEAVING_STOP);
  sph_sim_free(s);
  sph_case_free(&c);
  sph_test_rmtree(dir);
  free(dir);
}

/* The particle count of snapshot k of dir. */
static size_t snapshot_count(const char *dir, int k) {
  char path[4300];
  snprintf(path, sizeof path, "%s/snap_%04d.h5", dir, k);
  sph_snapshot *snap;
  sph_error err;
  if (sph_snapshot_open(path, &snap, &err)) return 0;
  sph_particles q;
  size_t n = 0;
  if (sph_snapshot_read_particles(snap, &q, &err) == 0) {
    n = q.n; /* the reader checks that the ids are 0..n-1 */
    sph_particles_free(&q);
  }
  sph_snapshot_close(snap);
  return n;
}

static void test_run(void) {
  /* step by step: mass and count add up at every step */
  sph_case c;
  sph_sim *s;
  sph_error err;
  CU_ASSERT_FATAL(sph_test_open_sim("tests/data/restart_outflow.yaml", NULL, 0, &c, &s) == 0);
  sph_diag_row row;
  sph_sim_diag(s, &row);
  const double m0 = row.mass;
  const size_t n0 = row.n_fluid;
  CU_ASSERT_EQUAL(row.n_removed, 0);
  double worst_mass = 0.0;
  long bad_count = 0, steps = 0;
  while (sph_sim_time(s) < c.t_end) {
    const int rc = sph_sim_step(s, c.t_end, &err);
    if (rc) printf("\n%s\n", err.msg);
    CU_ASSERT_FATAL(rc == 0);
    sph_sim_diag(s, &row);
    const double dm = fabs(row.mass + row.mass_removed - m0) / m0;
    if (dm > worst_mass) worst_mass = dm;
    double left = 0.0;
    bad_count += row.n_fluid + row.n_removed != n0 ||
                 sph_sim_fluid_left(s, &left) != row.n_removed || left != row.mass_removed;
    steps++;
  }
  printf("\n  %zu of %zu fluid particles left in %ld steps; mass balance %.1e", row.n_removed, n0,
         steps, worst_mass);
  CU_ASSERT(row.n_removed > 20);
  CU_ASSERT(row.n_fluid > 0);
  CU_ASSERT(worst_mass < 1e-12);
  CU_ASSERT_EQUAL(bad_count, 0);
  sph_sim_free(s);
  sph_case_free(&c);

  /* the command: the balances from the run's own diagnostics, the snapshots' counts */
  char *dir = sph_test_tmpdir(), args[8192], out[8192], path[4200];
  snprintf(args, sizeof args, "run '%s' -o '%s/run'",
           sph_test_src("tests/data/restart_outflow.yaml"), dir);
  CU_ASSERT_FATAL(sph_test_sph_ok(args, dir, out, sizeof out) == 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(out, "fluid particles left the domain and were taken out"));
  snprintf(path, sizeof path, "%s/run/diagnostics.csv", dir);
  double *col[5] = {NULL};
  const long n = sph_test_csv(path,
                              "energy_deviation,momentum_residual_x,momentum_residual_y,n_removed,"
                              "n_fluid",
                              col);
  CU_ASSERT_FATAL(n == 9); /* t = 0, 0.05, ..., 0.4 */
  double de = 0.0, dp = 0.0;
  for (long r = 0; r < n; r++) {
    if (fabs(col[0][r]) > de) de = fabs(col[0][r]);
    const double res = hypot(col[1][r], col[2][r]) / (row.mass + row.mass_removed) / 2.5;
    if (res > dp) dp = res;
  }
  printf("; energy balance %.2e of E0, momentum %.2e of M v0", de, dp);
  CU_ASSERT(de < 1e-4);
  CU_ASSERT(dp < 1e-3);
  CU_ASSERT(col[3][n - 1] > 20.0);
  /* each snapshot its own count, in the file and in the index */
  snprintf(path, sizeof path, "%s/run/snapshots.xmf", dir);
  char *xmf = sph_test_read_file(path, NULL);
  CU_ASSERT_FATAL(xmf != NULL);
  snprintf(path, sizeof path, "%s/run", dir);
  const size_t first = snapshot_count(path, 0), last = snapshot_count(path, 8);
  const size_t walls = first - (size_t)col[4][0];
  CU_ASSERT(first > last);
  CU_ASSERT_EQUAL(last, walls + (size_t)col[4][n - 1]);
  char a[64], b[64];
  snprintf(a, sizeof a, "NumberOfElements=\"%zu\"", first);
  snprintf(b, sizeof b, "NumberOfElements=\"%zu\"", last);
  CU_ASSERT_PTR_NOT_NULL(strstr(xmf, a));
  CU_ASSERT_PTR_NOT_NULL(strstr(xmf, b));
  free(xmf);
  for (int k = 0; k < 5; k++)
    free(col[k]);

  /* with stop, the same case is a blow-up that says where */
  snprintf(args, sizeof args, "run -q '%s' -o '%s/stop' --set geometry.leaving=stop",
           sph_test_src("tests/data/restart_outflow.yaml"), dir);
  CU_ASSERT_NOT_EQUAL(sph_test_sph(args, dir, out, sizeof out), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(out, "particle left the domain"));
  sph_test_rmtree(dir);
  free(dir);
}

int main(void) {
  CU_TestInfo tests[] = {{"the removal: order, ids, origin, what is booked", test_remove},
                         {"geometry.leaving: read, listed, refused", test_key},
                         {"a run: particles leave, the balances close, snapshots", test_run},
                         CU_TEST_INFO_NULL};
  return sph_test_main("outflow", tests);
}
