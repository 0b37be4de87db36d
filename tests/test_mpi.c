/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_mpi.c - `sph run` under mpirun (solver/procs.h, doc/parallel.md):
 * every output file of a run on 1, 2, 3, 4 and 7 processes, each of 1 and
 * 2 threads, is byte for byte the file of the same program run as one
 * process without mpirun (the serial path: no MPI at all, the bytes the
 * golden files hold):
 *   - 2-D, the default scheme with its walls, pressure and level probes and
 *     the energy ledger (every count and thread number), and with a
 *     variable h;
 *   - 2-D, a moving gate; a periodic axis; mdbc walls with particle shifting
 *     and the ledger;
 *   - 3-D, the default scheme with probes and the ledger (every count and
 *     thread number), through `sph`'s hand-over to `sph-3d`;
 *   - snapshots of two HDF5 chunks, written by the processes together
 *     (parallel HDF5), and of a case text too long for that (its first
 *     process writes alone); a snapshot that cannot be created stops every
 *     process with HDF5's reason;
 *   - an initial state out of its band on 3 processes: the serial run's message;
 *   - a step that collapses (a fixed step of 1e-300 s) on 3 processes: the
 *     serial run's message, naming a particle of the second process's share;
 *   - a run that stops on its condition (the surge front at the wall) on 3
 *     processes, each looking at its share: every file the serial run's;
 *   - a blow-up (leap-frog, a step ten times too long) in 2-D and 3-D on 2
 *     and 3 processes: exit status 3, last_good.h5 and every other file
 *     the serial run's, and the message naming the same particle;
 *   - one process's pass failing (SPH_TEST_FAIL_PASS) stops every process
 *     with its message, none left waiting, in 2-D and 3-D on 2 and 3;
 *   - a run on 4 processes restarted from its snapshot on 3;
 *   - the comparison sees a reduction summed in rank order
 *     (SPH_TEST_RANK_ORDER_SUMS=1 rounds each rank's ledger sums and adds
 *     them in rank order, =2 each process's share of the diagnostics' sums:
 *     the files must then differ);
 *   - one process killed with SIGKILL ends the job (mpirun's report, well
 *     within 30 s), and a restart from the last snapshot left gives the
 *     uninterrupted run's bytes;
 *   - SIGTERM to mpirun: rank 0's message and a complete final snapshot,
 *     from which a restart on 3 processes reaches the uninterrupted run's
 *     state;
 *   - how the processes wait, in the summary: blocking where the machine
 *     has a core for each thread the run sets (--threads, not the
 *     environment's count), napping where it has fewer.
 * Without --with-mpi the test says so and is skipped (exit 77).
 */
#include "config.h"

#include <dirent.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>
#include <unistd.h>

#include "snapcmp.h"
#include "testutil.h"

/* Seconds any one launch may take (the longest takes about 40 s): a run
 * that hangs in a collective step fails the test (exit 124) instead of
 * holding make check (a resumed run's probes row once did). */
#define SPH_MPIRUN_BOUND 300

/* mpirun with the flags a test machine needs: more processes than cores,
 * and root (a container's CI) allowed, under that bound; Open MPI's
 * point-to-point layer for shared memory named (pml ob1), so that no start
 * waits for its probe of fast-network libraries (doc/parallel.md). */
static const char *mpirun(void) {
  static char cmd[1024];
  const char *m = getenv("SPH_MPIRUN");
  snprintf(cmd, sizeof cmd,
           "timeout -k 10 %d '%s' --oversubscribe --bind-to none --mca pml ob1 --mca "
           "mpi_yield_when_idle 1%s -x "
           "SPH_TEST_OMP_MIN -x OMP_WAIT_POLICY",
           SPH_MPIRUN_BOUND, m && *m ? m : "mpirun", geteuid() == 0 ? " --allow-run-as-root" : "");
  return cmd;
}

static double now(void) {
  struct timeval tv;
  gettimeofday(&tv, NULL);
  return (double)tv.tv_sec + 1e-6 * (double)tv.tv_usec;
}

/* Runs the case (case_rel: in the source tree, or an absolute path) on
 * `procs` processes (0: without mpirun) of `threads` threads, with `env`
 * before the command, into a new directory; the run must exit with
 * `status`. */
static char *run_to(const char *prog, const char *case_rel, const char *sets, const char *env,
                    int procs, int threads, int status, int keep_err) {
  char *d = sph_test_tmpdir(), cmd[8400], launch[1100] = "", err[4200] = "";
  if (procs > 0) snprintf(launch, sizeof launch, "%s -n %d", mpirun(), procs);
  if (keep_err) snprintf(err, sizeof err, " 2>'%s.err'", d); /* (err_line) */
  snprintf(cmd, sizeof cmd,
           "SPH_TEST_OMP_MIN=0 %s %s '%s' run --quiet --threads %d '%s' -o '%s' %s%s", env, launch,
           sph_test_build(prog), threads, case_rel[0] == '/' ? case_rel : sph_test_src(case_rel), d,
           sets, err);
  const int rc = sph_test_system(cmd);
  if (rc != status) printf("\n  %s on %d processes: exit %d, not %d", case_rel, procs, rc, status);
  CU_ASSERT_FATAL(rc == status);
  return d;
}

static char *run(const char *prog, const char *case_rel, const char *sets, const char *env,
                 int procs, int threads) {
  return run_to(prog, case_rel, sets, env, procs, threads, 0, 0);
}

/* The line of run_to's kept standard error (then removed) that holds
 * `what`, from `what` up to `until` (or its end), into line; 1 if found. */
static int err_line(const char *d, const char *what, const char *until, char *line, size_t n) {
  char path[4200], buf[8192];
  snprintf(path, sizeof path, "%s.err", d);
  FILE *f = fopen(path, "r");
  int found = 0;
  while (f && !found && fgets(buf, sizeof buf, f)) {
    char *at = strstr(buf, what);
    if (!at) continue;
    char *end = strstr(at, until);
    if (end) *end = '\0';
    at[strcspn(at, "\n")] = '\0';
    snprintf(line, n, "%s", at);
    found = 1;
  }
  if (f) fclose(f);
  remove(path);
  return found;
}

/* The case on each process count of procs[], with 1 and 2 threads (both,
 * or in turn when `both` is 0), against the run without mpirun; env (a
 * test hook) for the runs under mpirun. */
static void same_on_processes_env(const char *prog, const char *case_rel, const char *sets,
                                  const char *env, const int *procs, int n_procs, int both) {
  char *one = run(prog, case_rel, sets, "", 0, 1);
  for (int k = 0; k < n_procs; k++)
    for (int threads = 1; threads <= 2; threads++) {
      if (!both && threads != 1 + k % 2) continue;
      const double t0 = now();
      char *d = run(prog, case_rel, sets, env, procs[k], threads);
      const int same = sph_test_same_dirs(one, d);
      printf("\n  %s, %d processes of %d thread(s): %s (%.1f s)", case_rel, procs[k], threads,
             same ? "identical" : "DIFFERENT", now() - t0);
      CU_ASSERT(same);
      sph_test_rmtree(d);
      free(d);
    }
  sph_test_rmtree(one);
  free(one);
}

static void same_on_processes(const char *prog, const char *case_rel, const char *sets,
                              const int *procs, int n_procs, int both) {
  same_on_processes_env(prog, case_rel, sets, "", procs, n_procs, both);
}

static const int all_counts[] = {1, 2, 3, 4, 7};
static const int two_three[] = {2, 3};

static void test_default_scheme_2d(void) {
  same_on_processes("src/sph", "cases/lobovsky_h300.yaml",
                    "--set numerics.dx=0.02 --set time.end=0.1 --set output.energy=true",
                    all_counts, 5, 1);
  /* with paper B's variable h: the walls in stages and the late rows with a list made at every
   * pass and smoothing lengths made from the walls' densities; the probes' records sized for one
   * term (SPH_TEST_PROBE_SLOT=1), so that the first row's terms follow in a second step and
   * the slot grows (run.c, read_probes_shared) */
  same_on_processes_env("src/sph", "cases/lobovsky_h300.yaml",
                        "--set numerics.dx=0.02 --set time.end=0.1 "
                        "--set numerics.smoothing_length=variable",
                        "SPH_TEST_PROBE_SLOT=1", two_three, 2, 0);
}

/* The stop condition (time.stop: front_at_wall), each process looking at its share of the
 * store and all agreeing in the step's collective: the run stops at the serial run's step. */
static const int three[] = {3};

static void test_stop_condition(void) {
  /* (a tank half as long: the front at its wall after 1 250 steps, not 2 521) */
  same_on_processes("src/sph", "cases/martin_moyce_coarse.yaml",
                    "--set 'geometry.tank={x: [0.0, 0.1143], y: [0.0, 0.17145], layers: 2, "
                    "boundary: dynamic}' --set time.output_interval=0.01",
                    three, 1, 0);
}

static void test_gate_periodic_mdbc(void) {
  same_on_processes("src/sph", "cases/wet_bed_dam_break.yaml",
                    "--set numerics.dx=0.015 --set time.end=0.1", two_three, 2, 0);
  /* the film 6 dx wide, its period two cells of the neighbour grid (the least: rows walked
   * whole), with particle shifting and free-surface flags */
  same_on_processes("src/sph", "cases/inclined_plane.yaml",
                    "--set time.end=0.1 --set time.output_interval=0.05 " SPH_TEST_FILM_6DX
                    "--set output.free_surface=true --set 'numerics.shifting={coefficient: 2}'",
                    two_three, 2, 0);
  same_on_processes("src/sph", "cases/martin_moyce_coarse.yaml",
                    "--set time.end=0.05 --set time.stop=none --set 'geometry.tank={x: [0.0, "
                    "0.2286], y: [0.0, 0.17145], boundary: mdbc, free_slip: true}' "
                    "--set 'numerics.shifting={coefficient: 2}' --set output.energy=true",
                    two_three, 2, 0);
}

/* Probe rows on an interval (output.probe_interval > 0: the row at the start time is the
 * writer's to count, and every process lands on the row times), and two phases (physics.air:
 * the phase and the walls' air pressure in the exchange): a process that counted the rows
 * alone skipped the start's row and left the writer waiting in its gather. */
static void test_probe_interval_air(void) {
  same_on_processes("src/sph", "tests/data/restart_air.yaml", "--set time.end=0.05", two_three, 2,
                    0);
}

/* Fluid taken out of the run (geometry.leaving: remove; from t = 0.1-0.15 s on) reorders the
 * store between two cuts: the walls' values that each process's passes keep to it between
 * outputs (the default scheme's walls in stages: ranks.c, lazy_walls) are shared first, and the
 * outputs are the serial run's (3 processes of one thread: the middle one has two neighbours). */
static void test_outflow(void) {
  same_on_processes("src/sph", "tests/data/restart_outflow.yaml",
                    "--set time.end=0.2 --set time.output_interval=0.05", three, 1, 0);
}

static void test_default_scheme_3d(void) {
  same_on_processes("src/sph", "cases/lobovsky_h300_3d.yaml",
                    "--set numerics.dx=0.04 --set time.end=0.06 --set time.output_interval=0.02 "
                    "--set output.energy=true",
                    all_counts, 5, 1);
}

/* The processes write each snapshot together through parallel HDF5, each
 * its share of whole chunks of 65 536 rows (io/snapshot.c): with 87 524
 * particles, two chunks, so on 2 processes each writes one and on 3 the
 * first writes none; the files are the lone writer's bytes. A case text
 * longer than an attribute in the root's header (here a 70 000-byte
 * comment) has the first process write alone: the same bytes again. */
static void test_snapshots_together(void) {
  same_on_processes("src/sph", "cases/lobovsky_h300.yaml",
                    "--set numerics.dx=0.0015 --set time.end=0.0004 "
                    "--set time.output_interval=0.0002",
                    two_three, 2, 0);
  char *d = sph_test_tmpdir(), path[4200];
  snprintf(path, sizeof path, "%s/long_text.yaml", d);
  FILE *in = fopen(sph_test_src("cases/martin_moyce_coarse.yaml"), "r"), *out = fopen(path, "w");
  CU_ASSERT_FATAL(in && out);
  int ch;
  while ((ch = fgetc(in)) != EOF)
    fputc(ch, out);
  fputs("# ", out);
  for (int k = 0; k < 70000; k++)
    fputc('x', out);
  fputc('\n', out);
  fclose(in);
  CU_ASSERT_FATAL(fclose(out) == 0);
  same_on_processes("src/sph", path, "--set time.end=0.02", two_three, 2, 0);
  sph_test_rmtree(d);
  free(d);
}

/* A snapshot the processes cannot create (its temporary name taken by a
 * directory) stops all of them together after the earlier snapshots:
 * exit 1 (not the bound's 124), HDF5's reason in the message, the
 * earlier snapshots kept, on 2 and 3 processes. */
static void test_failed_snapshot(void) {
  for (int procs = 2; procs <= 3; procs++) {
    char *d = sph_test_tmpdir(), cmd[8192], log[4200], path[4200];
    snprintf(cmd, sizeof cmd, "mkdir -p '%s/out/snap_0002.h5.tmp'", d);
    CU_ASSERT_FATAL(sph_test_system(cmd) == 0);
    snprintf(log, sizeof log, "%s/log", d);
    snprintf(cmd, sizeof cmd,
             "%s -n %d '%s' run --quiet --threads 1 '%s' -o '%s/out' --set time.end=0.1 > '%s' "
             "2>&1",
             mpirun(), procs, sph_test_build("src/sph"),
             sph_test_src("cases/martin_moyce_coarse.yaml"), d, log);
    const int rc = sph_test_system(cmd);
    char *out = sph_test_read_file(log, NULL);
    const int told = out && strstr(out, "snap_0002.h5: cannot create") && strstr(out, "(HDF5: ");
    free(out);
    snprintf(path, sizeof path, "%s/out/snap_0001.h5", d);
    const int kept = access(path, R_OK) == 0;
    printf("\n  snap_0002.h5.tmp a directory, %d processes: exit %d, %s, snap_0001.h5 %s", procs,
           rc, told ? "HDF5's reason" : "NO MESSAGE", kept ? "kept" : "MISSING");
    CU_ASSERT(rc == 1);
    CU_ASSERT(told);
    CU_ASSERT(kept);
    sph_test_rmtree(d);
    free(d);
  }
}

/* A blow-up (a fixed step some ten times the stable one) with the
 * leap-frog, whose last good state each process keeps for its own
 * particles in its rank store (solver/ranks.c) and gathers only then, in
 * 2-D and 3-D on 2 and 3 processes: the exit status 3 and every file,
 * last_good.h5 included, the run's on one process. */
static void test_blow_up(void) {
#define BLOW_UP_SETS                                                                               \
  "--set numerics.integrator=leapfrog --set time.output_interval=0.02 --set "                      \
  "'numerics.time_step={rule: fixed, dt: 0.004}'"
  const char *sets = BLOW_UP_SETS, *sets3 = BLOW_UP_SETS " --set numerics.dx=0.04";
  char *one[2] = {run_to("src/sph", "tests/data/stability_impact.yaml", sets, "", 0, 1, 3, 1),
                  run_to("src/sph", "cases/lobovsky_h300_3d.yaml", sets3, "", 0, 1, 3, 1)};
  /* the message, up to where the last good state went: the first offender
   * in id order, its state, the stable step (each process checks a share
   * of the store: sim.c) */
  char msg[2][2048], got[2048];
  for (int k = 0; k < 2; k++)
    CU_ASSERT(err_line(one[k], "blow-up at step", "; last good state", msg[k], sizeof msg[k]));
  char good[4200]; /* (this program reads 2-D snapshots) */
  snprintf(good, sizeof good, "%s/last_good.h5", one[0]);
  CU_ASSERT(snapcmp_complete(good, NULL, NULL));
  for (int procs = 2; procs <= 3; procs++) {
    char *d = run_to("src/sph", "tests/data/stability_impact.yaml", sets, "", procs, procs - 1, 3,
                     1),
         *e = run_to("src/sph", "cases/lobovsky_h300_3d.yaml", sets3, "", procs, 1, 3, 1);
    int same = sph_test_same_dirs(one[0], d), same3 = sph_test_same_dirs(one[1], e);
    same = err_line(d, "blow-up at step", "; last good state", got, sizeof got) &&
           strcmp(got, msg[0]) == 0 && same;
    same3 = err_line(e, "blow-up at step", "; last good state", got, sizeof got) &&
            strcmp(got, msg[1]) == 0 && same3;
    printf("\n  a blow-up on %d processes: 2-D %s, 3-D %s", procs, same ? "identical" : "DIFFERENT",
           same3 ? "identical" : "DIFFERENT");
    CU_ASSERT(same && same3);
    sph_test_rmtree(d);
    sph_test_rmtree(e);
    free(d);
    free(e);
  }
  for (int k = 0; k < 2; k++) {
    sph_test_rmtree(one[k]);
    free(one[k]);
  }
  /* the initial state out of its band (the hydrostatic start against a band of 1e-5): each
   * process checks its share before the first step, and the process whose share holds the
   * first offender makes the message for all: the serial run's. The first fluid block stands at
   * the tank's right end, so that its first particle, the offender, lies in the second of 3
   * processes' shares (seen when this test was written), not the first's */
  const char *tight = "--set numerics.dx=0.02 --set numerics.density_limit=0.00001 --set "
                      "'geometry.fluid=[{x: [1.0, 1.6], y: [0.0, 0.3], hydrostatic: true}, "
                      "{x: [0.0, 0.6], y: [0.0, 0.1], hydrostatic: true}]'";
  char *a = run_to("src/sph", "cases/lobovsky_h300.yaml", tight, "", 0, 1, 3, 1),
       *b = run_to("src/sph", "cases/lobovsky_h300.yaml", tight, "", 3, 1, 3, 1);
  const int start = err_line(a, "blow-up at step 0", "; last", msg[0], sizeof msg[0]) &&
                    err_line(b, "blow-up at step 0", "; last", got, sizeof got) &&
                    strcmp(got, msg[0]) == 0;
  printf("\n  the initial state out of its band on 3 processes: %s",
         start ? "the same message" : "DIFFERENT");
  CU_ASSERT(start);
  sph_test_rmtree(a);
  sph_test_rmtree(b);
  free(a);
  free(b);
}

/* A step that stays below its floor (a fixed step of 1e-300 s) stops the run with the fastest
 * particle named: the wet bed's gate (a wall moving from the start), in the second of 3
 * processes' shares (seen when this test was written), whose process makes the message for
 * all: the serial run's message and files, last_good.h5 included. */
static void test_collapse(void) {
  const char *sets = "--set numerics.dx=0.015 --set time.end=1 "
                     "--set 'numerics.time_step={rule: fixed, dt: 1e-300}'";
  char *a = run_to("src/sph", "cases/wet_bed_dam_break.yaml", sets, "", 0, 1, 3, 1),
       *b = run_to("src/sph", "cases/wet_bed_dam_break.yaml", sets, "", 3, 1, 3, 1);
  char want[2048], got[2048];
  int same = sph_test_same_dirs(a, b);
  same = err_line(a, "time step collapse", "; last good state", want, sizeof want) &&
         err_line(b, "time step collapse", "; last good state", got, sizeof got) &&
         strcmp(got, want) == 0 && same;
  printf("\n  a collapsed step on 3 processes: %s", same ? "identical" : "DIFFERENT");
  CU_ASSERT(same);
  sph_test_rmtree(a);
  sph_test_rmtree(b);
  free(a);
  free(b);
}

/* One process's pass fails (SPH_TEST_FAIL_PASS: process 1's fifth pass,
 * before its walls' first stage on the default scheme): every process
 * stops with that process's message, none left waiting in a collective
 * step (the launch's bound would end it with 124), in 2-D and 3-D. */
static void test_failed_pass(void) {
  const char *cases[2][2] = {{"cases/lobovsky_h300.yaml", "--set numerics.dx=0.02"},
                             {"cases/lobovsky_h300_3d.yaml", "--set numerics.dx=0.04"}};
  for (int k = 0; k < 2; k++)
    for (int procs = 2; procs <= 3; procs++) {
      char *d = sph_test_tmpdir(), cmd[8192], log[4200];
      snprintf(log, sizeof log, "%s/log", d);
      snprintf(cmd, sizeof cmd,
               "SPH_TEST_FAIL_PASS=1:5 %s -n %d '%s' run --quiet --threads 1 '%s' -o '%s/out' %s "
               "--set time.end=0.1 > '%s' 2>&1",
               mpirun(), procs, sph_test_build("src/sph"), sph_test_src(cases[k][0]), d,
               cases[k][1], log);
      const double t0 = now();
      const int rc = sph_test_system(cmd);
      char *out = sph_test_read_file(log, NULL);
      const int told = out && strstr(out, "SPH_TEST_FAIL_PASS: pass 5 fails") != NULL;
      free(out);
      printf("\n  %s, process 1 of %d fails its fifth pass: exit %d, %s (%.1f s)", cases[k][0],
             procs, rc, told ? "its message" : "NO MESSAGE", now() - t0);
      CU_ASSERT(rc != 0 && rc != 124);
      CU_ASSERT(told);
      sph_test_rmtree(d);
      free(d);
    }
}

/* A run to t = 0.04 s on 4 processes, restarted from its snapshot at
 * 0.02 s on 3 into a new directory: the snapshot at 0.04 s is the serial
 * run's, byte for byte. */
static void test_restart_on_other_count(void) {
  const char *c = "cases/martin_moyce_coarse.yaml";
  const char *sets = "--set time.end=0.04 --set time.output_interval=0.02 --set time.stop=none "
                     "--set output.energy=true";
  char *whole = run("src/sph", c, sets, "", 0, 1);
  char *part = run("src/sph", c, sets, "", 4, 1), *again = sph_test_tmpdir();
  char cmd[16384];
  snprintf(
      cmd, sizeof cmd,
      "SPH_TEST_OMP_MIN=0 %s -n 3 '%s' run --quiet --restart '%s/snap_0001.h5' '%s' -o '%s' %s",
      mpirun(), sph_test_build("src/sph"), part, sph_test_src(c), again, sets);
  CU_ASSERT(sph_test_restart_same(cmd, whole, again,
                                  "restarted on 3 processes from a 4-process run's snapshot"));
  sph_test_rmtree(whole);
  sph_test_rmtree(part);
  sph_test_rmtree(again);
  free(whole);
  free(part);
  free(again);
}

/* The ledger's sums (hook 1), or the diagnostics' (hook 2), rounded per
 * process and added in rank order: the files differ from the serial run's
 * (the comparison above would fail). */
static void rank_order_seen(const char *hook, const char *what) {
  const char *c = "cases/lobovsky_h300.yaml";
  const char *sets = "--set numerics.dx=0.02 --set time.end=0.2 --set output.energy=true";
  char *one = run("src/sph", c, sets, "", 0, 1);
  char env[64];
  snprintf(env, sizeof env, "SPH_TEST_RANK_ORDER_SUMS=%s", hook);
  char *d = run("src/sph", c, sets, env, 3, 1);
  char a[4096], b[4096];
  snprintf(a, sizeof a, "%s/diagnostics.csv", one);
  snprintf(b, sizeof b, "%s/diagnostics.csv", d);
  char cmd[9000];
  snprintf(cmd, sizeof cmd, "cmp -s '%s' '%s'", a, b);
  const int differ = sph_test_system(cmd) != 0;
  printf("\n  %s summed in rank order on 3 processes: %s", what,
         differ ? "seen (diagnostics.csv differs)" : "NOT SEEN");
  CU_ASSERT(differ);
  sph_test_rmtree(one);
  sph_test_rmtree(d);
  free(one);
  free(d);
}

static void test_rank_order_sums_are_seen(void) {
  rank_order_seen("1", "the ledger's rates");
  rank_order_seen("2", "the diagnostics' sums");
}

/* The pid of a process whose command line holds `a` and `b`: mpirun itself
 * when `launcher` is 1, else one of the processes it started (not the
 * shell that started it); 0 if none (read from /proc). */
static long find_process(const char *a, const char *b, int launcher) {
  long found = 0;
  DIR *proc = opendir("/proc");
  if (!proc) return 0;
  struct dirent *e;
  while (!found && (e = readdir(proc))) {
    char *end;
    const long pid = strtol(e->d_name, &end, 10);
    if (*end || pid <= 0) continue;
    char path[300], line[8192];
    snprintf(path, sizeof path, "/proc/%ld/cmdline", pid);
    FILE *f = fopen(path, "rb");
    if (!f) continue;
    const size_t n = fread(line, 1, sizeof line - 1, f);
    fclose(f);
    line[n] = 0;
    const int is_mpirun = strstr(line, "mpirun") != NULL; /* the program: the first string */
    const int is_bound = strstr(line, "timeout") != NULL; /* (mpirun's bound, SPH_MPIRUN_BOUND) */
    for (size_t k = 0; k < n; k++)
      if (!line[k]) line[k] = ' ';
    if (strstr(line, a) && strstr(line, b) && is_mpirun == launcher && !is_bound &&
        !strstr(line, "sh -c"))
      found = pid;
  }
  closedir(proc);
  return found;
}

/* The long 2-D job of the signal tests, started on 2 processes in the
 * background in d (its output in d/out, mpirun's in d/job.txt, its exit
 * status in d/status.txt once it ends) with `quiet` flags; returns when its
 * third snapshot exists: the pid of mpirun (launcher 1) or of one of its
 * processes; 0 (mpirun's last lines shown) if the job ended before. */
static const char *long_case = "cases/lobovsky_h300.yaml";
static const char *long_sets = "--set numerics.dx=0.0075 --set time.output_interval=0.05";

static long start_long_job(const char *d, const char *quiet, int launcher) {
  char cmd[16384], path[4200], out[4200], what[64];
  snprintf(cmd, sizeof cmd,
           "cd '%s' && (%s -n 2 '%s' run %s--threads 1 '%s' -o '%s/out' %s "
           "--set time.end=1.5 > job.txt 2>&1; echo $? > status.txt) &",
           d, mpirun(), sph_test_build("src/sph"), quiet, sph_test_src(long_case), d, long_sets);
  if (sph_test_system(cmd) != 0) return 0;
  char status[4200];
  snprintf(path, sizeof path, "%s/out/snap_0002.h5", d);
  snprintf(status, sizeof status, "%s/status.txt", d);
  for (int i = 0; i < 1200 && access(path, F_OK) != 0; i++) {
    if (access(status, F_OK) == 0) { /* the job ended before its third snapshot */
      snprintf(cmd, sizeof cmd, "tail -12 '%s/job.txt'", d);
      sph_test_system(cmd);
      return 0;
    }
    usleep(100000);
  }
  snprintf(out, sizeof out, "%s/out", d);
  snprintf(what, sizeof what, "run %s--threads 1", quiet);
  return find_process(what, out, launcher);
}

/* Seconds from t0 until the job of start_long_job ended (at most 60). */
static double wait_job(const char *d, double t0) {
  char path[4200];
  snprintf(path, sizeof path, "%s/status.txt", d);
  double waited = 0.0;
  while (access(path, F_OK) != 0 && waited < 60.0) {
    usleep(100000);
    waited = now() - t0;
  }
  return waited;
}

/* The last snapshot the job left in d/out; -1 if none. */
static int last_snapshot(const char *d) {
  char path[4200];
  int last = -1;
  for (int k = 0; k < 10000; k++) {
    snprintf(path, sizeof path, "%s/out/snap_%04d.h5", d, k);
    if (access(path, F_OK) != 0) break;
    last = k;
  }
  return last;
}

/* One of 2 processes killed (SIGKILL) while the job runs: mpirun ends the
 * job with its report within 30 s; the snapshots written are whole, and a
 * restart from the last one (on 2 processes) gives the bytes of the
 * uninterrupted serial run's next snapshot. */
static void test_killed_process(void) {
  const double every = 0.05;
  char *d = sph_test_tmpdir(), cmd[16384];
  const long pid = start_long_job(d, "--quiet ", 0);
  printf("\n  killing process %ld of the job", pid);
  CU_ASSERT_FATAL(pid > 0);
  const double t0 = now();
  CU_ASSERT_FATAL(kill((pid_t)pid, SIGKILL) == 0);
  const double waited = wait_job(d, t0);
  printf("\n  a process killed: the job ended after %.1f s", waited);
  CU_ASSERT(waited < 30.0);
  snprintf(cmd, sizeof cmd, "grep -q 'exited on signal 9' '%s/job.txt'", d);
  CU_ASSERT(sph_test_system(cmd) == 0);
  /* the last whole snapshot, and the one after it from a restart */
  const int last = last_snapshot(d);
  CU_ASSERT_FATAL(last >= 2);
  const double end = (double)(last + 1) * every;
  snprintf(cmd, sizeof cmd,
           "cd '%s' && SPH_TEST_OMP_MIN=0 %s -n 2 '%s' run --quiet --restart out/snap_%04d.h5 '%s' "
           "-o again %s "
           "--set time.end=%.17g && "
           "SPH_TEST_OMP_MIN=0 '%s' run --quiet '%s' -o whole %s --set time.end=%.17g && "
           "cmp -s again/snap_%04d.h5 whole/snap_%04d.h5",
           d, mpirun(), sph_test_build("src/sph"), last, sph_test_src(long_case), long_sets, end,
           sph_test_build("src/sph"), sph_test_src(long_case), long_sets, end, last + 1, last + 1);
  const int same = sph_test_system(cmd) == 0;
  printf("\n  restarted on 2 processes from snap_%04d.h5, the last left: %s", last,
         same ? "identical" : "DIFFERENT");
  CU_ASSERT(same);
  sph_test_rmtree(d);
  free(d);
}

/* SIGTERM to mpirun while 2 processes run (a batch system's time limit):
 * Open MPI passes it on, the processes stop after the same step, rank 0
 * says so and writes the final snapshot, complete; a restart from it on 3
 * processes reaches an output time past it in the state of the
 * uninterrupted serial run (compared field by field: the resumed run's
 * snapshot has another index). */
static void test_terminated_job(void) {
  char *d = sph_test_tmpdir(), cmd[16384], path[4200];
  const long pid = start_long_job(d, "", 1);
  printf("\n  SIGTERM to mpirun (%ld)", pid);
  CU_ASSERT_FATAL(pid > 0);
  CU_ASSERT_FATAL(kill((pid_t)pid, SIGTERM) == 0);
  const double waited = wait_job(d, now());
  printf(": the job ended after %.1f s", waited);
  CU_ASSERT_FATAL(waited < 60.0);
  snprintf(cmd, sizeof cmd, "grep -q 'interrupted by SIGTERM' '%s/job.txt'", d);
  const int said = sph_test_system(cmd) == 0;
  if (!said) {
    snprintf(cmd, sizeof cmd, "tail -5 '%s/job.txt'", d);
    sph_test_system(cmd);
  }
  CU_ASSERT(said);
  const int last = last_snapshot(d);
  CU_ASSERT_FATAL(last >= 3);
  snprintf(path, sizeof path, "%s/out/snap_%04d.h5", d, last);
  size_t n = 0;
  double ti = 0.0;
  CU_ASSERT_FATAL(snapcmp_complete(path, &n, &ti));
  /* the final snapshot is the interruption's: off the output grid */
  CU_ASSERT(ti > 0.05 * (last - 1) && ti < 0.05 * last);
  const double t2 = 0.05 * (last + 1);
  snprintf(cmd, sizeof cmd,
           "cd '%s' && SPH_TEST_OMP_MIN=0 %s -n 3 '%s' run --quiet --restart out/snap_%04d.h5 '%s' "
           "-o again %s --set time.end=%.17g && "
           "SPH_TEST_OMP_MIN=0 '%s' run --quiet '%s' -o whole %s --set time.end=%.17g",
           d, mpirun(), sph_test_build("src/sph"), last, sph_test_src(long_case), long_sets, t2,
           sph_test_build("src/sph"), sph_test_src(long_case), long_sets, t2);
  CU_ASSERT_FATAL(sph_test_system(cmd) == 0);
  char a[4300], b[4300];
  snprintf(a, sizeof a, "%s/again/snap_%04d.h5", d, last + 2);
  snprintf(b, sizeof b, "%s/whole/snap_%04d.h5", d, last + 1);
  const int same = snapcmp("restart after SIGTERM", a, b, 1) == 0;
  printf("\n  restarted on 3 processes from the final snapshot (t = %.4f s) to t = %.2f s: %s", ti,
         t2, same ? "the uninterrupted run's state" : "DIFFERENT");
  CU_ASSERT(same);
  sph_test_rmtree(d);
  free(d);
}

/* How the processes wait (procs.c, the summary's line): blocking where this
 * machine has a core for every process's threads as --threads sets them,
 * napping where it has fewer; the environment's thread count
 * (OMP_NUM_THREADS=4 here) is not the run's. */
static void test_waits(void) {
  const long cores = sysconf(_SC_NPROCESSORS_ONLN);
  const int runs[2][2] = {{2, 1}, {3, 2}};
  for (int k = 0; k < 2; k++) {
    const int procs = runs[k][0], threads = runs[k][1];
    char *d = sph_test_tmpdir(), cmd[8192], log[4200];
    snprintf(log, sizeof log, "%s/log", d);
    snprintf(cmd, sizeof cmd,
             "OMP_NUM_THREADS=4 %s -x OMP_NUM_THREADS -n %d '%s' run --threads %d '%s' -o '%s/out' "
             "--set numerics.dx=0.02 --set time.end=0.025 > '%s' 2>&1",
             mpirun(), procs, sph_test_build("src/sph"), threads,
             sph_test_src("cases/lobovsky_h300.yaml"), d, log);
    const int rc = sph_test_system(cmd);
    char *out = sph_test_read_file(log, NULL);
    const int crowded = (long)procs * threads > cores;
    const char *want = crowded ? "; waits napping (more threads than cores)"
                               : "; waits blocking (a core for every thread)";
    const int told = out && strstr(out, want) != NULL;
    printf("\n  %d processes of %d thread(s) on %ld cores: exit %d, %s", procs, threads, cores, rc,
           told ? want + 2 : "NOT TOLD");
    CU_ASSERT(rc == 0);
    CU_ASSERT(told);
    free(out);
    sph_test_rmtree(d);
    free(d);
  }
}

/* The cut by measured work (solver/ranks.c, balance): with process 1 made three times slower
 * (SPH_TEST_SLOW_PROCESS=1:2, a nap of twice its pass's time after each pass), 2 processes of
 * one thread move their shares at the cuts (every 40 steps; 212 steps here), process 1's below
 * 0.45 of the weight, and write the one-process run's bytes; with --balance weights the shares
 * stay even (the cut a pure function of the state) and the bytes are the same too. */
static void test_balance(void) {
  const char *sets = "--set numerics.dx=0.02 --set time.end=0.1";
  char *one = run("src/sph", "cases/lobovsky_h300.yaml", sets, "", 0, 1);
  for (int weights = 0; weights < 2; weights++) {
    char *d = sph_test_tmpdir(), cmd[8192], log[4200];
    snprintf(log, sizeof log, "%s.log", d);
    snprintf(cmd, sizeof cmd,
             "SPH_TEST_SLOW_PROCESS=1:2 %s -x SPH_TEST_SLOW_PROCESS -n 2 '%s' run --threads 1 "
             "'%s' -o '%s' %s%s > '%s' 2>&1",
             mpirun(), sph_test_build("src/sph"), sph_test_src("cases/lobovsky_h300.yaml"), d, sets,
             weights ? " --balance weights" : "", log);
    const int rc = sph_test_system(cmd);
    char *out = sph_test_read_file(log, NULL);
    const char *at = out ? strstr(out, "the processes' shares of its weight ") : NULL;
    double lo = -1.0, hi = -1.0;
    long moved = -1;
    if (at)
      sscanf(at, "the processes' shares of its weight %lf to %lf (moved at %ld", &lo, &hi, &moved);
    /* the waits: "; each waited A to B s for the others", the run's "outputs, W s wall" */
    const char *wat = out ? strstr(out, "; each waited ") : NULL;
    const char *wall_at = out ? strstr(out, " outputs, ") : NULL;
    double wlo = -1.0, whi = -1.0, wall = -1.0;
    if (wat) sscanf(wat, "; each waited %lf to %lf s for the others", &wlo, &whi);
    if (wall_at) sscanf(wall_at, " outputs, %lf s wall", &wall);
    const int same = rc == 0 && sph_test_same_dirs(one, d);
    printf("\n  --balance %s, process 1 three times slower: exit %d, shares %.3f to %.3f, moved at "
           "%ld cuts, waits %.3g to %.3g s of %.3g s, %s",
           weights ? "weights" : "work", rc, lo, hi, moved, wlo, whi, wall,
           same ? "identical" : "DIFFERENT");
    CU_ASSERT(rc == 0);
    CU_ASSERT(same);
    CU_ASSERT(wlo >= 0.0 && wlo <= whi && whi <= wall);
    if (weights) {
      CU_ASSERT(lo == 0.5 && hi == 0.5 && moved == 0);
      /* the other process waits out the slow one's naps (two thirds of each pass's time) */
      CU_ASSERT(whi > 0.3 * wall);
    } else {
      CU_ASSERT(lo > 0.0 && lo < 0.45 && hi > 0.55 && moved >= 1);
    }
    free(out);
    remove(log);
    sph_test_rmtree(d);
    free(d);
  }
  sph_test_rmtree(one);
  free(one);
}

int main(void) {
  CU_TestInfo tests[] = {{"2-D, the default scheme, 1-7 processes", test_default_scheme_2d},
                         {"2-D, a gate, a periodic axis, mdbc", test_gate_periodic_mdbc},
                         {"3-D, the default scheme, 1-7 processes", test_default_scheme_3d},
                         {"probe rows on an interval, two phases", test_probe_interval_air},
                         {"fluid taken out of the run", test_outflow},
                         {"snapshots written together", test_snapshots_together},
                         {"a snapshot that cannot be made", test_failed_snapshot},
                         {"a blow-up's last good state", test_blow_up},
                         {"the stop condition", test_stop_condition},
                         {"a collapsed step", test_collapse},
                         {"a failed pass stops every process", test_failed_pass},
                         {"a restart on another process count", test_restart_on_other_count},
                         {"a reduction in rank order is seen", test_rank_order_sums_are_seen},
                         {"a killed process", test_killed_process},
                         {"SIGTERM to mpirun", test_terminated_job},
                         {"how the processes wait", test_waits},
                         {"the cut follows a slower process", test_balance},
                         CU_TEST_INFO_NULL};
#ifndef SPH_MPI
  (void)tests; /* (named, so that a build without MPI compiles them all) */
  printf("test_mpi: this build has no MPI; ./configure --with-mpi (Debian: apt-get install "
         "libopenmpi-dev openmpi-bin libhdf5-openmpi-dev) runs these tests\n");
  return 77;
#else
  return sph_test_main("mpi", tests);
#endif
}
