/*
 * cli_run.c - `sph run CASE [-o DIR] [--threads N] [--set key=value]...
 *             [--restart SNAPSHOT]`, and `sph run --restart SNAPSHOT [...]`
 *             with the case taken from the snapshot
 *
 * Loads and validates the case (with overrides), prints the choices in
 * force, creates the output directory, and runs the case with a progress
 * bar on a terminal. With --restart the run continues from a snapshot of an
 * earlier run of the same case (sim.h, sph_sim_restore), bitwise as if it
 * had not stopped. SIGINT/SIGTERM end the run after the current step with
 * a final snapshot (exit status 4); a second signal of the same kind
 * during that wind-down ends the program at once, with the default
 * action. Messages go to stderr; the start-up listing and the summary to
 * stdout.
 */
#include "config.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "sph.h"
#include "cli/cli.h"
#include "cli/progress.h"

static volatile sig_atomic_t interrupted = 0;
static void on_signal(int sig) {
  if (interrupted) { /* asked twice: stop now (a snapshot being written stays a .tmp) */
    signal(sig, SIG_DFL);
    raise(sig);
    return;
  }
  interrupted = sig;
}

static void run_usage(FILE *f) {
  fprintf(f,
          "usage: sph run CASE [-o DIR] [--threads N] [--set key=value]... [--quiet]\n"
          "               [--restart SNAPSHOT]\n"
          "       sph run --restart SNAPSHOT [-o DIR] [--threads N] [--set time.end=T] [--quiet]\n"
          "\n"
          "Runs the case file CASE (YAML; see README.md for every key). Without CASE,\n"
          "--restart takes the case from SNAPSHOT (the case text and --set overrides it\n"
          "stores) and writes to SNAPSHOT's directory unless -o is given.\n"
          "\n"
          "  -o, --output DIR   output directory (default out/<case name>); created if needed\n"
          "  -r, --restart SNAPSHOT\n"
          "                     continue from SNAPSHOT (a snap_NNNN.h5 of an earlier run of\n"
          "                     CASE with the same --set overrides; only time.end may\n"
          "                     differ): writes snap_NNNN+1... bitwise equal to those of\n"
          "                     the uninterrupted run; diagnostics.csv and gauges.csv in\n"
          "                     DIR keep their rows up to the snapshot's time, then grow\n"
          "  -t, --threads N    OpenMP threads (default: all cores); results are bitwise\n"
          "                     identical for any N\n"
          "  -s, --set K=V      override a case key, e.g. --set numerics.dx=0.001\n"
          "                     (V is YAML: --set physics.gravity=[0,-9.81]); repeatable\n"
          "  -q, --quiet        no start-up listing and no progress bar\n"
          "  -h, --help         this help\n"
          "\n"
          "SIGINT or SIGTERM (Ctrl-C) ends the run after the current step: a final snapshot\n"
          "is written (restartable with --restart) and the exit status is 4; a second\n"
          "signal ends it at once. Exit status: 0 done, 1 bad input or I/O error, 2 usage\n"
          "error, 3 numerical blow-up (last good state in DIR/last_good.h5), 4 interrupted.\n");
}

typedef struct progress_ctx {
  sph_progress bar;
} progress_ctx;

static void on_progress(void *ctx, const sph_sim *s) {
  progress_ctx *pc = ctx;
  sph_progress_update(&pc->bar, sph_sim_time(s), sph_sim_steps(s));
}

int sph_cli_run(int argc, char **argv) {
  const char *case_path = NULL, *outdir = NULL, *restart = NULL;
  int threads = 0, quiet = 0;
  const char **sets = calloc((size_t)argc, sizeof *sets);
  size_t n_set = 0;
  if (!sets) return 1;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    const char *val = NULL;
    if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
      run_usage(stdout);
      free(sets);
      return 0;
    } else if (!strcmp(a, "-q") || !strcmp(a, "--quiet")) {
      quiet = 1;
    } else if (!strcmp(a, "-o") || !strcmp(a, "--output") || !strcmp(a, "-t") ||
               !strcmp(a, "--threads") || !strcmp(a, "-s") || !strcmp(a, "--set") ||
               !strcmp(a, "-r") || !strcmp(a, "--restart")) {
      if (i + 1 >= argc) {
        fprintf(stderr, "sph run: option %s needs a value\n", a);
        free(sets);
        return 2;
      }
      val = argv[++i];
      if (a[1] == 'o' || !strcmp(a, "--output")) {
        outdir = val;
      } else if (a[1] == 'r' || !strcmp(a, "--restart")) {
        restart = val;
      } else if (a[1] == 't' || !strcmp(a, "--threads")) {
        char *end;
        long t = strtol(val, &end, 10);
        if (*end || t < 1 || t > 4096) {
          fprintf(stderr, "sph run: --threads: expected a whole number >= 1, got '%s'\n", val);
          free(sets);
          return 2;
        }
        threads = (int)t;
      } else {
        if (!strchr(val, '=')) {
          fprintf(stderr, "sph run: --set: expected key=value, got '%s'\n", val);
          free(sets);
          return 2;
        }
        sets[n_set++] = val;
      }
    } else if (a[0] == '-' && a[1]) {
      fprintf(stderr, "sph run: unknown option '%s' (see sph run --help)\n", a);
      free(sets);
      return 2;
    } else if (!case_path) {
      case_path = a;
    } else {
      fprintf(stderr, "sph run: more than one case file given ('%s', '%s')\n", case_path, a);
      free(sets);
      return 2;
    }
  }
  if (!case_path && !restart) {
    run_usage(stderr);
    free(sets);
    return 2;
  }

  sph_error err = {{0}};
  sph_case c;
  char snapdir[4096];
  if (!case_path) { /* the case of the snapshot, and by default its directory */
    sph_snapshot *snap;
    int rc = sph_snapshot_open(restart, &snap, &err);
    if (rc == 0) {
      rc = sph_cli_snapshot_case_set(snap, sets, n_set, &c, &err);
      sph_snapshot_close(snap);
    }
    if (rc) {
      fprintf(stderr, "sph run: --restart: %s\n", err.msg);
      free(sets);
      return 1;
    }
    case_path = "the snapshot's case";
    if (!outdir) {
      snprintf(snapdir, sizeof snapdir, "%s", restart);
      char *slash = strrchr(snapdir, '/');
      if (slash)
        *slash = '\0';
      else
        snprintf(snapdir, sizeof snapdir, ".");
      outdir = snapdir;
    }
  } else if (sph_case_load(case_path, sets, n_set, &c, &err)) {
    fprintf(stderr, "sph run: %s\n", err.msg);
    sph_case_free(&c);
    free(sets);
    return 1;
  }
  free(sets);
#ifdef _OPENMP
  if (threads > 0) omp_set_num_threads(threads);
  const int nthreads = omp_get_max_threads();
#else
  const int nthreads = 1;
  if (threads > 1 && !quiet)
    fprintf(stderr, "sph run: built without OpenMP; running on 1 thread\n");
#endif
  char defdir[4096];
  if (!outdir) {
    snprintf(defdir, sizeof defdir, "out/%s", c.name);
    outdir = defdir;
  }
  if (sph_cli_make_dirs(outdir)) {
    fprintf(stderr, "sph run: cannot create output directory %s: %s\n", outdir, strerror(errno));
    sph_case_free(&c);
    return 1;
  }
  sph_sim *s;
  if (sph_sim_create(&c, &s, &err)) {
    fprintf(stderr, "sph run: %s\n", err.msg);
    sph_case_free(&c);
    return 1;
  }
  sph_snapshot_restart_data rd;
  if (restart && sph_sim_restore(s, restart, &rd, &err)) {
    fprintf(stderr, "sph run: --restart: %s\n", err.msg);
    sph_sim_free(s);
    sph_case_free(&c);
    return 1;
  }
  const sph_particles *p = sph_sim_particles(s);
  const size_t nf = sph_particles_count_kind(p, SPH_KIND_FLUID);
  if (!quiet) {
    printf("%s: case %s (%s)\n", sph_version(), c.name, case_path);
    printf("  particles %zu (fluid %zu, wall %zu), dx = %g m, h = %g m, c0 = %g m/s\n", p->n, nf,
           p->n - nf, c.dx, c.h, c.sound_speed);
    printf("  kernel %s, integrator %s, time step %s", sph_kernel_name(c.kernel),
           sph_integrator_name(c.integrator), sph_dt_rule_name(c.dt_rule));
    if (c.dt_rule == SPH_DT_FIXED)
      printf(" (dt %g s)\n", c.dt_fixed);
    else
      printf(" (factor %g)\n", c.dt_factor);
    printf("  walls:");
    if (c.tank.present)
      printf(" tank %s%s%s", sph_boundary_name(c.tank.boundary),
             c.tank.stagger ? "" : " unstaggered",
             c.tank.extrapolated ? " (extrapolated velocity)" : "");
    for (size_t w = 0; w < c.n_walls; w++)
      printf("%s wall %zu %s%s%s%s", c.tank.present || w ? "," : "", w,
             sph_boundary_name(c.walls[w].boundary), c.walls[w].stagger ? "" : " unstaggered",
             c.walls[w].extrapolated ? " (extrapolated velocity)" : "",
             c.walls[w].motion.kind != SPH_MOTION_NONE ? " (moving)" : "");
    if (!c.tank.present && c.n_walls == 0) printf(" none");
    if (c.periodic) printf("; periodic in x over [%g, %g]", c.periodic_x[0], c.periodic_x[1]);
    printf("\n  artificial viscosity alpha %g beta %g, laminar viscosity %s", c.alpha, c.beta,
           sph_viscosity_name(c.viscosity));
    if (c.viscosity != SPH_VISCOSITY_NONE)
      printf(" (mu %g Pa s%s)", c.mu, c.gradient_correction ? ", gradient correction" : "");
    printf(", XSPH %g, density filter %s", c.xsph, sph_filter_name(c.density_filter));
    if (c.density_filter != SPH_FILTER_NONE) printf(" every %d steps", c.filter_every);
    printf("\n  free surface %s, energy ledger %s; end %g s, output", 
           sph_case_needs_free_surface(&c) ? "detected" : "off", c.energy ? "on" : "off",
           c.t_end);
    if (c.output_interval > 0.0) printf(" every %g s", c.output_interval);
    if (c.n_output_times) printf("%s at %zu listed times", c.output_interval > 0.0 ? " and" : "",
                                 c.n_output_times);
    printf(", stop %s\n", sph_stop_name(c.stop));
    printf("  threads %d, output %s\n", nthreads, outdir);
    if (restart)
      printf("  restarting from %s at t = %.9g s, step %ld\n", restart, sph_sim_time(s),
             sph_sim_steps(s));
    fflush(stdout);
  }

  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);

  progress_ctx pc;
  sph_progress_init(&pc.bar, stderr, c.t_end, quiet);
  sph_run_options opt = {outdir, on_progress, &pc, &interrupted};
  sph_run_result r;
  const double w0 = sph_wall_seconds();
  int rc = sph_run_resume(s, &opt, restart ? &rd : NULL, &r, &err);
  if (restart) sph_snapshot_restart_free(&rd);
  const double wall = sph_wall_seconds() - w0;
  sph_progress_done(&pc.bar);
  int status = 0;
  switch (r.status) {
  case SPH_RUN_END:
  case SPH_RUN_STOPPED:
    status = 0;
    break;
  case SPH_RUN_INTERRUPTED:
    fprintf(stderr,
            "sph run: interrupted by %s at t = %.9g s (step %ld); final snapshot %s\n"
            "sph run: continue with: sph run --restart %s -o %s\n",
            interrupted == SIGTERM ? "SIGTERM" : "SIGINT", sph_sim_time(s), r.steps,
            r.last_snapshot[0] ? r.last_snapshot : "(none)",
            r.last_snapshot[0] ? r.last_snapshot : "SNAPSHOT", outdir);
    status = 4;
    break;
  case SPH_RUN_BLOWUP:
    fprintf(stderr, "sph run: %s\n", err.msg);
    fprintf(stderr, "sph run: last regular snapshot kept: %s\n",
            r.last_snapshot[0] ? r.last_snapshot : "(none)");
    status = 3;
    break;
  case SPH_RUN_ERROR:
    fprintf(stderr, "sph run: %s\n", err.msg);
    status = 1;
    break;
  }
  (void)rc;
  if (!quiet && status != 1) {
    const double ps = wall > 0 ? (double)p->n * (double)r.steps / wall : 0.0;
    printf("%s at t = %.9g s: %ld steps, %zu outputs, %.2f s wall, %.3g particle-steps/s\n",
           sph_run_status_name(r.status), sph_sim_time(s), r.steps, r.outputs, wall, ps);
  }
  sph_sim_free(s);
  sph_case_free(&c);
  return status;
}
