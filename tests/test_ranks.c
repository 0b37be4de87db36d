/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_ranks.c - whole runs with every pass made as ranks make it
 * (SPH_TEST_RANKS, src/solver/ranks.c): each rank holds its own particles
 * and its ghosts (src/neighbours/decomp.h), and every output file (the
 * snapshots, the XDMF index, diagnostics.csv, gauges.csv, probes.csv) must
 * be the bytes of the run on one rank, for 2 and 3 ranks (and 7 on the
 * first case), on 1 and 2 threads, on:
 *   - paper B's dam break (dynamic walls, fourtakas diffusion, XSPH);
 *   - the default scheme on Lobovsky's tank (Adami walls, the Riemann
 *     pressure, the leap-frog, pressure sensors);
 *   - the wet bed (the stress tensor, the energy ledger, a moving gate,
 *     output times);
 *   - the periodic film (leap-frog, free-surface flags with h* = 2h, a
 *     period shorter than the ghosts' reach);
 *   - a still tank with mirror walls (mirror particles, the MLS filter);
 *   - the SPS dam break; the flap wavemaker (paddle, gauges, variable h);
 *   - in 3-D the Lobovsky tank and SPHERIC Test 2 (its box obstacle);
 *   - free-slip mdbc walls with particle shifting and the ledger;
 *   - a run stopped and restarted on another rank count.
 */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>

#include "testutil.h"

/* Runs the case with `env` before the command into a new directory. */
static char *run(const char *prog, const char *case_rel, const char *sets, const char *env,
                 int threads) {
  char *d = sph_test_tmpdir(), cmd[8192];
  snprintf(cmd, sizeof cmd, "%s SPH_TEST_OMP_MIN=0 '%s' run --quiet --threads %d '%s' -o '%s' %s",
           env, sph_test_build(prog), threads, sph_test_src(case_rel), d, sets);
  const int rc = sph_test_system(cmd);
  if (rc) printf("\n  %s %s: exit %d", env, case_rel, rc);
  CU_ASSERT_FATAL(rc == 0);
  return d;
}

static void same_on_ranks(const char *prog, const char *case_rel, const char *sets,
                          const int *ranks, int n_ranks) {
  char *one = run(prog, case_rel, sets, "", 1);
  for (int k = 0; k < n_ranks; k++) {
    char env[64];
    snprintf(env, sizeof env, "SPH_TEST_RANKS=%d", ranks[k]);
    const int threads = 1 + k % 2; /* 1 and 2 threads in turn */
    char *d = run(prog, case_rel, sets, env, threads);
    const int same = sph_test_same_dirs(one, d);
    printf("\n  %s, %d ranks, %d thread(s): %s", case_rel, ranks[k], threads,
           same ? "identical" : "DIFFERENT");
    CU_ASSERT(same);
    sph_test_rmtree(d);
    free(d);
  }
  sph_test_rmtree(one);
  free(one);
}

static const int two_three_seven[] = {2, 3, 7};
static const int two_three[] = {2, 3};

static void test_paper_b(void) {
  same_on_ranks("src/sph", "cases/martin_moyce_coarse.yaml", "--set time.end=0.05", two_three_seven,
                3);
}

static void test_default_scheme(void) {
  same_on_ranks("src/sph", "cases/lobovsky_h300.yaml", "--set numerics.dx=0.02 --set time.end=0.2",
                two_three, 2);
}

static void test_stress_and_gate(void) {
  same_on_ranks("src/sph", "cases/wet_bed_dam_break.yaml",
                "--set numerics.dx=0.015 --set time.end=0.1", two_three, 2);
}

static void test_periodic_film(void) {
  same_on_ranks("src/sph", "cases/inclined_plane.yaml",
                "--set time.end=0.1 --set time.output_interval=0.05", two_three, 2);
}

static void test_mirror_walls(void) {
  same_on_ranks("src/sph", "cases/hydrostatic_tank.yaml",
                "--set geometry.tank.boundary=mirror --set time.end=0.05 "
                "--set numerics.density_filter.kind=mls --set numerics.density_filter.every=5",
                two_three + 1, 1);
}

/* variable h with mdbc no-slip walls (their density written by the pass,
 * read by the other ranks' ghosts) under the stress tensor and SPS; the
 * free-surface smoothing lengths with mdbc walls */
static void test_variable_h_mdbc(void) {
  same_on_ranks("src/sph", "cases/sps_dam_break_coarse.yaml",
                "--set time.end=0.05 --set numerics.smoothing_length=variable --set "
                "geometry.tank.boundary=mdbc",
                two_three, 2);
  /* free-surface smoothing lengths with mdbc walls: the fluid a wall
   * particle's mirror point fits over is flagged by its own neighbours
   * (needs ghosts 3 cells deep here, where 2 were taken) */
  same_on_ranks("src/sph", "cases/sps_dam_break.yaml",
                "--set numerics.dx=0.02 --set time.end=0.03 --set time.output_interval=0.01 "
                "--set geometry.tank.boundary=mdbc --set 'free_surface={h_factor: 1.3}'",
                two_three + 1, 1);
  /* variable h with no-slip (extrapolated) mdbc walls: the velocity fit's
   * cells fit the whole store's 2 max h, not a rank's own (4 ranks at
   * t = 0.2 s differed when they fitted a rank's) */
  static const int four[] = {4};
  same_on_ranks("src/sph", "cases/sps_dam_break.yaml",
                "--set numerics.dx=0.01 --set time.end=0.2 --set time.output_interval=0.2 "
                "--set numerics.smoothing_length=variable --set geometry.tank.boundary=mdbc "
                "--set geometry.tank.extrapolated_velocity=true",
                four, 1);
}

static void test_sps_and_wavemaker(void) {
  same_on_ranks("src/sph", "cases/sps_dam_break_coarse.yaml", "--set time.end=0.05", two_three, 1);
  same_on_ranks("src/sph", "cases/linear_wave_coarse.yaml", "--set time.end=0.3", two_three + 1, 1);
}

static void test_3d(void) {
  same_on_ranks("src/sph-3d", "cases/lobovsky_h300_3d.yaml",
                "--set numerics.dx=0.03 --set time.end=0.1", two_three + 1, 1);
  same_on_ranks("src/sph-3d", "cases/spheric_test2.yaml",
                "--set numerics.dx=0.06 --set time.end=0.1", two_three, 1);
}

/* Periods of two cells of the neighbour grid, the shortest it takes (every
 * row walked whole; the decomposition's cells wrap onto themselves within
 * a ghost layer): the film 6 dx wide with particle shifting and
 * free-surface flags, 12 dx with h* = 2h (cells twice as wide), and the
 * 3-D flap flume 6 dx (2.4 m) wide with its snapshots. */
static const int three[] = {3};

static void test_two_cell_periods(void) {
  same_on_ranks("src/sph", "cases/inclined_plane.yaml",
                "--set time.end=0.05 --set time.output_interval=0.01 " SPH_TEST_FILM_6DX
                "--set output.free_surface=true --set 'numerics.shifting={coefficient: 2}'",
                two_three, 2);
  same_on_ranks(
      "src/sph", "cases/inclined_plane.yaml",
      "--set time.end=0.05 --set time.output_interval=0.01 "
      "--set 'geometry.periodic_x=[0.0, 6.0e-4]' "
      "--set 'geometry.fluid=[{x: [0.0, 6.0e-4], y: [0.0, 1.0e-3], hydrostatic: false}]' "
      "--set 'geometry.walls=[{from: [5.75e-4, -2.5e-5], to: [2.5e-5, -2.5e-5], layers: 4, "
      "stagger: false, extrapolated_velocity: true, boundary: fixed_layers}]' "
      "--set output.free_surface=true --set 'free_surface={h_factor: 2}'",
      three, 1);
  same_on_ranks("src/sph-3d", "cases/linear_wave_flume_3d.yaml",
                "--set time.end=0.3 --set time.output_interval=0.1 --set "
                "output.snapshots=true " SPH_TEST_FLUME_6DX,
                three, 1);
}

/* A run to t = 0.04 s on 3 ranks, restarted from its snapshot at 0.02 s
 * on 2 ranks into a new directory: the snapshot at 0.04 s is the one-rank
 * run's, byte for byte. */
static void test_restart_on_other_ranks(void) {
  const char *c = "cases/martin_moyce_coarse.yaml";
  const char *sets = "--set time.end=0.04 --set time.output_interval=0.02 --set time.stop=none";
  char *whole = run("src/sph", c, sets, "", 1);
  char *part = run("src/sph", c, sets, "SPH_TEST_RANKS=3", 1), *again = sph_test_tmpdir();
  char cmd[16384];
  snprintf(cmd, sizeof cmd,
           "SPH_TEST_RANKS=2 '%s' run --quiet --restart '%s/snap_0001.h5' '%s' -o '%s' %s",
           sph_test_build("src/sph"), part, sph_test_src(c), again, sets);
  CU_ASSERT(sph_test_restart_same(cmd, whole, again,
                                  "restarted on 2 ranks from a 3-rank run's snapshot"));
  sph_test_rmtree(whole);
  sph_test_rmtree(part);
  sph_test_rmtree(again);
  free(whole);
  free(part);
  free(again);
}

/* mdbc walls (free-slip) with particle shifting (its own pass over the
 * whole store's list) and the energy ledger. */
static void test_shifting_and_ledger(void) {
  same_on_ranks("src/sph", "cases/martin_moyce_coarse.yaml",
                "--set time.end=0.05 --set time.stop=none --set 'geometry.tank={x: [0.0, "
                "0.2286], y: [0.0, 0.17145], boundary: mdbc, free_slip: true}' "
                "--set 'numerics.shifting={coefficient: 2}' --set output.energy=true",
                two_three, 2);
}

int main(void) {
  CU_TestInfo tests[] = {{"paper B's scheme", test_paper_b},
                         {"the default scheme", test_default_scheme},
                         {"the stress tensor and a gate", test_stress_and_gate},
                         {"the periodic film with free-surface flags", test_periodic_film},
                         {"mirror walls and the MLS filter", test_mirror_walls},
                         {"SPS and the flap wavemaker", test_sps_and_wavemaker},
                         {"variable and free-surface h with mdbc walls", test_variable_h_mdbc},
                         {"3-D", test_3d},
                         {"periods of two cells", test_two_cell_periods},
                         {"a restart on another rank count", test_restart_on_other_ranks},
                         {"mdbc walls, particle shifting and the ledger", test_shifting_and_ledger},
                         CU_TEST_INFO_NULL};
  return sph_test_main("ranks", tests);
}
