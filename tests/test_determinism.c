/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_determinism.c - same case, same build: byte-identical output on 1
 * and on 2 threads, for every kind of loop the solver has (DESIGN rule 1),
 * and on 3 for the plain scheme (slices of unequal size).
 * test_dam_break covers the plain scheme; here short runs switch on the
 * other terms, each run with SPH_TEST_OMP_MIN=0 so that even these small cases
 * take the parallel paths:
 *   - wet-bed dam break: stress-tensor viscosity, artificial viscosity,
 *     XSPH, the energy ledger, a moving gate, output_times;
 *   - coarse SPS dam break: SPS turbulence with Morris viscosity;
 *   - hydrostatic tank with mirror walls, MLS filter every 5 steps;
 *   - inclined plane: periodic x, leap-frog, free surface with h* = 2h;
 *   - free-surface flags on the kept neighbour list (coarse dam break on
 *     1-3 threads, the inclined plane without h*);
 *   - coarse flap wavemaker: paddle motion, wave gauges, variable h,
 *     Shepard filter;
 *   - coarse dam break with the Wendland kernel, the stress tensor, the
 *     MLS filter and a pressure probe;
 *   - density diffusion: antuono (its gradient pass) on the coarse dam
 *     break, fourtakas with the energy ledger on the wet bed;
 *   - particle shifting with the ledger on free-slip mdbc walls, and on
 *     the periodic inclined plane;
 *   - the Riemann-solver pressure on mdbc walls with the ledger and a
 *     low-pass probe;
 *   - adami walls with Morris viscosity and the ledger, a probe with its
 *     own interpolation, on 1-3 threads;
 *   - a fluid without tension (the density floor) in the default scheme
 *     with the ledger and a probe, on 1-3 threads;
 *   - two phases (physics.air) with surface tension and the corrected
 *     kernel gradient, on 1-3 threads, and in 3-D on 1-2;
 *   - the store shuffled before the first sort (SPH_TEST_SHUFFLE): the
 *     same bits, the summation order independent of the storage order.
 * Every file of the two output directories (snapshots, XDMF index,
 * diagnostics.csv, gauges.csv, probes.csv) must be identical.
 */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>

#include "testutil.h"

/* Runs the case on 1 .. max_threads threads and compares every output
 * directory with the 1-thread one. */
static void same_on_threads(const char *case_rel, const char *sets, int max_threads) {
  char *d[4], cmd[8192];
  for (int t = 1; t <= max_threads; t++) {
    d[t - 1] = sph_test_tmpdir();
    snprintf(cmd, sizeof cmd, "SPH_TEST_OMP_MIN=0 '%s' run --quiet --threads %d '%s' -o '%s' %s",
             sph_test_build("src/sph"), t, sph_test_src(case_rel), d[t - 1], sets);
    const int rc = sph_test_system(cmd);
    if (rc) printf("\n  %s: exit %d", case_rel, rc);
    CU_ASSERT_FATAL(rc == 0);
  }
  for (int t = 2; t <= max_threads; t++) {
    snprintf(cmd, sizeof cmd, "diff -r '%s' '%s' >/dev/null", d[0], d[t - 1]);
    const int same = sph_test_system(cmd) == 0;
    printf("\n  %s, %d threads: %s", case_rel, t, same ? "identical" : "DIFFERENT");
    CU_ASSERT(same);
  }
  for (int t = 1; t <= max_threads; t++) {
    sph_test_rmtree(d[t - 1]);
    free(d[t - 1]);
  }
}

static void same_on_1_and_2_threads(const char *case_rel, const char *sets) {
  same_on_threads(case_rel, sets, 2);
}

/* Three threads on the plain scheme: uneven cost-balanced slices
 * (src/core/parallel.h) in every loop of the step, and the kept neighbour list. */
static void test_three_threads(void) {
  same_on_threads("cases/martin_moyce_coarse.yaml",
                  "--set time.end=0.1 --set numerics.integrator=leapfrog", 3);
}

static void test_wet_bed(void) {
  same_on_1_and_2_threads("cases/wet_bed_dam_break.yaml",
                          "--set numerics.dx=0.012 --set time.end=0.16");
}

static void test_sps(void) {
  same_on_1_and_2_threads("cases/sps_dam_break_coarse.yaml", "--set time.end=0.2");
}

static void test_mirror_filter(void) {
  same_on_1_and_2_threads("tests/data/still_tank.yaml",
                          "--set time.end=0.05 --set time.output_interval=0.01 "
                          "--set 'geometry.tank={x: [0.0, 0.2], y: [0.0, 0.15], boundary: mirror}' "
                          "--set 'numerics.density_filter={kind: mls, every: 5}'");
}

static void test_periodic_free_surface(void) {
  same_on_1_and_2_threads("cases/inclined_plane.yaml",
                          "--set time.end=0.05 --set time.output_interval=0.01 "
                          "--set 'free_surface={h_factor: 2}' --set output.free_surface=true");
}

/* free-surface flags from the rows of the neighbour list kept across
 * steps (no h*, so the list keeps its skin), on a plain grid and periodic */
static void test_free_surface_kept_list(void) {
  same_on_threads("cases/martin_moyce_coarse.yaml",
                  "--set time.end=0.1 --set output.free_surface=true", 3);
  same_on_1_and_2_threads("cases/inclined_plane.yaml",
                          "--set time.end=0.05 --set time.output_interval=0.01 "
                          "--set output.free_surface=true");
}

static void test_paddle(void) {
  same_on_1_and_2_threads("cases/linear_wave_coarse.yaml",
                          "--set time.end=1.0 --set numerics.smoothing_length=variable "
                          "--set 'numerics.density_filter={kind: shepard, every: 10}'");
}

/* mdbc walls: the wall density from the fluid's fit at the mirror points,
 * through the impact on the right wall (and restart-safe: the pass that a
 * restore reruns recomputes it) */
static void test_mdbc(void) {
  same_on_1_and_2_threads("cases/martin_moyce_coarse.yaml",
                          "--set time.end=0.2 --set time.stop=none --set 'geometry.tank={x: [0.0, "
                          "0.2286], y: [0.0, 0.17145], boundary: mdbc}'");
}

/* density diffusion: the antuono model's gradient pass and the pair term
 * (lane loop), and fourtakas with the energy ledger (scalar loop, the
 * diffusion_energy column) on the wet bed, whose fixed_layers walls and
 * gate diffuse with the fluid (solver/diffusion.h; the dynamic walls' rows
 * in the lane loop: test_three_threads, test_wendland and the coarse dam
 * break of the other tests, whose case runs fourtakas) */
static void test_density_diffusion(void) {
  same_on_1_and_2_threads("cases/martin_moyce_coarse.yaml",
                          "--set time.end=0.2 --set time.stop=none "
                          "--set 'numerics.density_diffusion={model: antuono}'");
  same_on_1_and_2_threads("cases/wet_bed_dam_break.yaml",
                          "--set numerics.dx=0.012 --set time.end=0.1 "
                          "--set 'numerics.density_diffusion={model: fourtakas, delta: 0.1}'");
}

/* particle shifting (physics/shifting.h): its pass over the kept list, the
 * walls' keep-off after it and the ledger's shifting_drift, through the
 * impact on a free-slip mdbc wall; and on a periodic grid (the minimum
 * image in its sums) with the leap-frog */
static void test_shifting(void) {
  same_on_1_and_2_threads("cases/martin_moyce_coarse.yaml",
                          "--set time.end=0.2 --set time.stop=none --set 'geometry.tank={x: [0.0, "
                          "0.2286], y: [0.0, 0.17145], boundary: mdbc, free_slip: true}' "
                          "--set 'numerics.shifting={coefficient: 2}' --set output.energy=true");
  same_on_1_and_2_threads("cases/inclined_plane.yaml",
                          "--set time.end=0.05 --set time.output_interval=0.01 "
                          "--set 'numerics.shifting={coefficient: 2}'");
}

/* the Riemann-solver pressure (physics.riemann): its own lane loop, the walls'
 * normal closing speed in the rows that meet an mdbc wall (w->nwall), its
 * continuity term with the ledger, a probe's low-pass filter, through the
 * impact on the right wall */
static void test_riemann(void) {
  same_on_1_and_2_threads("cases/martin_moyce_coarse.yaml",
                          "--set time.end=0.2 --set time.stop=none --set 'geometry.tank={x: [0.0, "
                          "0.2286], y: [0.0, 0.17145], boundary: mdbc}' "
                          "--set physics.artificial_viscosity.alpha=0 --set physics.xsph=0 "
                          "--set 'numerics.density_diffusion={model: none}' "
                          "--set physics.riemann.limiter=3 --set output.energy=true "
                          "--set 'output.probes=[{name: P, kind: pressure, at: [0.2286, 0.005], "
                          "low_pass: 500}]'");
}

/* adami walls (walls/adami.h): their pass over the walls' rows, the rows
 * skipped in the main pass, their no-slip velocity gathered in the lanes
 * (artificial and Morris viscosity), the ledger's passive pairs, through
 * the impact on the right wall, on 1-3 threads; and a probe with its own
 * interpolation (points, smoothing, clip_negative, hydrostatic) */
static void test_adami(void) {
  same_on_threads("cases/martin_moyce_coarse.yaml",
                  "--set time.end=0.2 --set time.stop=none --set 'geometry.tank={x: [0.0, "
                  "0.2286], y: [0.0, 0.17145], boundary: adami}' "
                  "--set 'physics.viscosity={model: morris, mu: 0.001}' --set output.energy=true "
                  "--set 'output.probes=[{name: P, kind: pressure, at: [0.2286, 0.005], diameter: "
                  "0.004, points: 7, smoothing: 2, clip_negative: true, hydrostatic: false}]'",
                  3);
}

/* a fluid that holds no tension (physics.negative_pressure: false): the density floor in
 * the leap-frog's slices, with the default scheme, the ledger and a probe */
static void test_no_tension(void) {
  same_on_threads("tests/data/restart_no_tension.yaml", "--set time.end=0.1", 3);
}

/* fluid that leaves the domain taken out (geometry.leaving: remove): the count's reduction,
 * the store's compaction and the booking, with the default scheme and the ledger */
static void test_outflow(void) { same_on_threads("tests/data/restart_outflow.yaml", "", 3); }

/* two phases (physics.air): the phases' laws, the impedance-weighted pairs and the walls'
 * pressure for each phase, with the ledger, a probe and a gauge; and in 3-D */
static void test_air(void) {
  same_on_threads("tests/data/restart_air.yaml", "--set time.end=0.1", 3);
  same_on_threads("tests/data/air_3d.yaml", "", 2);
}

/* the Wendland kernel in the pair loop, the strain-rate pass, the MLS
 * filter and the probes */
static void test_wendland(void) {
  same_on_1_and_2_threads("cases/martin_moyce_coarse.yaml",
                          "--set time.end=0.1 --set numerics.kernel=wendland_c2 "
                          "--set 'physics.viscosity={model: stress_tensor, mu: 0.001}' "
                          "--set 'numerics.density_filter={kind: mls, every: 10}' "
                          "--set 'output.probes=[{name: P, kind: pressure, at: [0.0, 0.01]}]'");
}

/* Runs the case on 2 threads with the environment `base` and with `hook`
 * (test hooks, doc/testing.md) and compares every output byte for byte;
 * `what` names the hook in the report. */
static void same_with(const char *base, const char *hook, const char *what, const char *case_rel,
                      const char *sets) {
  char *d[2], cmd[8192];
  const char *env[2] = {base, hook};
  for (int k = 0; k < 2; k++) {
    d[k] = sph_test_tmpdir();
    snprintf(cmd, sizeof cmd, "%s SPH_TEST_OMP_MIN=0 '%s' run --quiet --threads 2 '%s' -o '%s' %s",
             env[k], sph_test_build("src/sph"), sph_test_src(case_rel), d[k], sets);
    const int rc = sph_test_system(cmd);
    if (rc) printf("\n  %s: exit %d", case_rel, rc);
    CU_ASSERT_FATAL(rc == 0);
  }
  for (int k = 1; k < 2; k++) {
    snprintf(cmd, sizeof cmd, "diff -r '%s' '%s' >/dev/null", d[0], d[k]);
    const int same = sph_test_system(cmd) == 0;
    printf("\n  %s, %s (%s): %s", case_rel, what, env[k], same ? "identical" : "DIFFERENT");
    CU_ASSERT(same);
  }
  for (int k = 0; k < 2; k++) {
    sph_test_rmtree(d[k]);
    free(d[k]);
  }
}

/* The summation order does not depend on the storage order: the store
 * shuffled before the first sort (SPH_TEST_SHUFFLE) gives every
 * output of the unshuffled run, byte for byte, on 2 threads. The first sort
 * puts each particle where its global cell and its id say (grid.h); a sort
 * that kept the old order within a cell would not. The default scheme's
 * walls and leap-frog, the ledger and a moving gate, a periodic axis with
 * the free surface, fluid leaving the domain, mirror walls, and 3-D. */
static void same_shuffled(const char *case_rel, const char *sets) {
  same_with("", "SPH_TEST_SHUFFLE=20261203", "store shuffled", case_rel, sets);
}

static void test_storage_order(void) {
  same_shuffled("cases/lobovsky_h300.yaml",
                "--set numerics.dx=0.015 --set time.end=0.15 --set time.output_interval=0.05 "
                "--set output.energy=true");
  same_shuffled("cases/wet_bed_dam_break.yaml", "--set numerics.dx=0.012 --set time.end=0.1");
  same_shuffled("cases/inclined_plane.yaml", "--set time.end=0.05 --set time.output_interval=0.01 "
                                             "--set output.free_surface=true");
  same_shuffled("tests/data/restart_outflow.yaml", "");
  same_shuffled("tests/data/still_tank.yaml",
                "--set time.end=0.03 --set time.output_interval=0.01 "
                "--set 'geometry.tank={x: [0.0, 0.2], y: [0.0, 0.15], boundary: mirror}'");
  same_shuffled("cases/hydrostatic_3d.yaml", "--set time.end=0.02 --set time.output_interval=0.01");
}

/* The Riemann pressure's rows that meet a wall with a normal (forces.c,
 * nwall), found once a list build: the same bits as found at every pass
 * (SPH_TEST_NWALL=every) as the surge runs along the floor to the far wall
 * and fluid comes within reach of more wall particles, with a skin so thin
 * (SPH_TEST_SKIN) that lists are built again every few steps between the
 * sorts; adami walls (the default scheme) and mdbc. */
static void test_nwall_kept(void) {
  const char *sets = "--set numerics.dx=0.015 --set time.end=0.45 --set time.output_interval=0.15";
  char mdbc[512];
  snprintf(mdbc, sizeof mdbc, "%s --set geometry.tank.boundary=mdbc", sets);
  const char *each[2] = {sets, mdbc};
  for (int k = 0; k < 2; k++)
    same_with("SPH_TEST_SKIN=0.02", "SPH_TEST_SKIN=0.02 SPH_TEST_NWALL=every",
              "the walls' rows read at every pass", "cases/lobovsky_h300.yaml", each[k]);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"the walls' rows met, found once a list build: the same bits", test_nwall_kept},
      {"the storage order shuffled: the same bits", test_storage_order},
      {"Wendland kernel, stress tensor, MLS filter, probes", test_wendland},
      {"density diffusion: antuono, fourtakas with the ledger", test_density_diffusion},
      {"mdbc walls through an impact", test_mdbc},
      {"adami walls through an impact, 1-3 threads", test_adami},
      {"the Riemann pressure through an impact, with the ledger", test_riemann},
      {"particle shifting, also periodic", test_shifting},
      {"wet bed: viscosity, ledger, moving gate", test_wet_bed},
      {"SPS turbulence", test_sps},
      {"mirror walls and the MLS filter", test_mirror_filter},
      {"periodic x, leap-frog, free surface with h*", test_periodic_free_surface},
      {"free surface on the kept neighbour list, 1-3 threads", test_free_surface_kept_list},
      {"paddle, gauges, variable h, Shepard filter", test_paddle},
      {"leap-frog dam break on 1, 2 and 3 threads", test_three_threads},
      {"a fluid without tension, 1-3 threads", test_no_tension},
      {"fluid that leaves the domain taken out, 1-3 threads", test_outflow},
      {"two phases (water under air), 1-3 threads; in 3-D 1-2", test_air},
      CU_TEST_INFO_NULL};
  return sph_test_main("determinism", tests);
}
