/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * cli_run.c - `sph run CASE [-o DIR] [--threads N] [--set key=value]...
 *             [--restart SNAPSHOT]`, and `sph run --restart SNAPSHOT [...]`
 *             with the case taken from the snapshot
 *
 * Loads and validates the case (with overrides), prints the case as it
 * will run (sph_case_describe, the same listing the snapshots store),
 * creates the output directory, and runs the case with a progress
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
#include <time.h>

#include "cli/cli.h"
#include "cli/progress.h"
#include "sph.h"

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
          "               [--restart SNAPSHOT] [--progress S] [--balance MODE]\n"
          "       sph run --restart SNAPSHOT [-o DIR] [--threads N] [--set time.end=T] [--quiet]\n"
          "\n"
          "Runs the case file CASE (YAML; every key: doc/case-files.md, man sph). CASE may\n"
          "also name an installed example case (e.g. martin_moyce) when no such file is\n"
          "here: they are in %s ($SPH_CASES_DIR overrides). Without CASE,\n"
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
          "  -q, --quiet        no start-up listing and no progress bar or lines\n"
          "      --progress S   when standard error is not a terminal (a log file, a\n"
          "                     batch job): a progress line every S seconds of wall time\n"
          "                     (default 60, so a shorter run writes none; 0: none); on a\n"
          "                     terminal the progress bar instead\n"
          "      --balance MODE under mpirun: how the particles are cut among the\n"
          "                     processes: 'work' (default) by their measured work, so that\n"
          "                     a process on a slower core gets fewer; 'weights' by the\n"
          "                     particles' estimated cost alone (the same cut every run).\n"
          "                     The results are the same bits either way\n"
          "      --max-particles N\n"
          "                     refuse a case whose geometry makes more than N particles\n"
          "                     (default: half this machine's memory at 1200 bytes each)\n"
          "  -h, --help         this help\n"
          "\n"
          "SIGINT or SIGTERM (Ctrl-C) ends the run after the current step: a final snapshot\n"
          "is written (restartable with --restart) and the exit status is 4 (during the\n"
          "set-up: nothing is written, exit 4); a second signal ends it at once.\n"
          "Exit status: 0 done, 1 bad input or I/O error, 2 usage error, 3 numerical blow-up\n"
          "(last good state in DIR/last_good.h5), 4 interrupted.\n",
          sph_case_cases_dir());
}

typedef struct progress_ctx {
  sph_progress bar;
} progress_ctx;

static void on_progress(void *ctx, const sph_sim *s) {
  progress_ctx *pc = ctx;
  double now = 0.0, stop = 0.0;
  sph_run_stop_measure(s, &now, &stop);
  sph_progress_update(&pc->bar, sph_sim_time(s), sph_sim_steps(s), now, stop);
}

typedef struct run_args {
  const char *case_path, *outdir, *restart;
  int threads, quiet;
  int weights_only;     /* --balance weights */
  double max_particles; /* --max-particles; 0: the default bound */
  double progress;      /* --progress: seconds between lines in a log */
  const char **sets;
  size_t n_set;
} run_args;

/* The command line into a; -1 after --help (printed), 0, or 2 (usage
 * error, message printed). */
static int parse_run_args(int argc, char **argv, run_args *a) {
  static const char *const with_value[] = {
      "-o",        "--output",        "-t",         "--threads", "-s", "--set", "-r",
      "--restart", "--max-particles", "--progress", "--balance", NULL};
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i];
    if (!strcmp(o, "-h") || !strcmp(o, "--help")) {
      run_usage(stdout);
      return -1;
    } else if (!strcmp(o, "-q") || !strcmp(o, "--quiet")) {
      a->quiet = 1;
    } else if (sph_cli_is_one_of(o, with_value)) {
      if (i + 1 >= argc) {
        fprintf(stderr, "sph run: option %s needs a value\n", o);
        return 2;
      }
      const char *v = argv[++i];
      if (!strcmp(o, "-o") || !strcmp(o, "--output")) {
        a->outdir = v;
      } else if (!strcmp(o, "-r") || !strcmp(o, "--restart")) {
        a->restart = v;
      } else if (!strcmp(o, "-t") || !strcmp(o, "--threads")) {
        if (sph_cli_parse_threads("sph run", v, &a->threads)) return 2;
      } else if (!strcmp(o, "--max-particles")) {
        if (sph_cli_parse_max_particles("sph run", v, &a->max_particles)) return 2;
      } else if (!strcmp(o, "--progress")) {
        if (sph_cli_parse_progress("sph run", v, &a->progress)) return 2;
      } else if (!strcmp(o, "--balance")) {
        if (strcmp(v, "work") && strcmp(v, "weights")) {
          fprintf(stderr, "sph run: --balance: expected 'work' or 'weights', got '%s'\n", v);
          return 2;
        }
        a->weights_only = !strcmp(v, "weights");
      } else if (!strchr(v, '=')) {
        fprintf(stderr, "sph run: --set: expected key=value, got '%s'\n", v);
        return 2;
      } else {
        a->sets[a->n_set++] = v;
      }
    } else if (o[0] == '-' && o[1]) {
      fprintf(stderr, "sph run: unknown option '%s' (see sph run --help)\n", o);
      return 2;
    } else if (!a->case_path) {
      a->case_path = o;
    } else {
      fprintf(stderr, "sph run: more than one case file given ('%s', '%s')\n", a->case_path, o);
      return 2;
    }
  }
  if (!a->case_path && !a->restart) {
    run_usage(stderr);
    return 2;
  }
  return 0;
}

static int setup_interrupted(void);

/* The signals a run catches, blocked (how = SIG_BLOCK) or unblocked. A
 * blocked signal stays pending across the hand-over's exec, and the other
 * program's handler gets it once installed (issue 61: the window between
 * the two programs' handlers). */
static void catchable_signals(int how) {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGHUP);
  sigprocmask(how, &set, NULL);
}

/* Hands the case (its text, len bytes) or, with text NULL, the --restart
 * snapshot to the other build where it is of the other dimension, the
 * signals held across the exec: 0 where this build runs it, else the exit
 * status (message printed; 4 for a signal that came before). */
static int hand_over(const run_args *a, const char *text, size_t len) {
  catchable_signals(SIG_BLOCK);
  if (interrupted) { /* before the hand-over: this program says it */
    catchable_signals(SIG_UNBLOCK);
    return setup_interrupted();
  }
  const int rc = text ? sph_cli_hand_over("run", a->case_path, text, len, a->sets, a->n_set)
                      : sph_cli_hand_over_snapshot("run", a->restart);
  catchable_signals(SIG_UNBLOCK); /* this program runs it: a pending signal now */
  return rc ? 1 : 0;
}

/* The case: from CASE, or with --restart alone from the snapshot (whose
 * directory is then the default output, into snapdir). 0, or 1 with the
 * message printed. */
static int load_run_case(run_args *a, sph_case *c, char *snapdir, size_t n) {
  sph_error err = {{0}};
  if (a->case_path) {
    static char found[4096]; /* outlives the call: a->case_path points into it */
    char why[8192];
    const char *path = sph_case_find(a->case_path, found, sizeof found, why, sizeof why);
    if (!path) {
      fprintf(stderr, "sph run: %s\n", why);
      return 1;
    }
    a->case_path = path;
    /* the file is read once: a FIFO, /dev/stdin or <(...) gives its text
     * only once (issue 61, E4) */
    char *text;
    size_t len;
    if (sph_cli_read_case(a->case_path, &text, &len, &err)) {
      fprintf(stderr, "sph run: %s\n", err.msg);
      return 1;
    }
    const int st = hand_over(a, text, len);
    if (st) {
      free(text);
      return st;
    }
    const int rc = sph_case_parse(text, len, a->case_path, a->sets, a->n_set, c, &err);
    free(text);
    if (rc == 0) return 0;
    fprintf(stderr, "sph run: %s\n", err.msg);
    sph_case_free(c);
    return 1;
  }
  const int st = hand_over(a, NULL, 0);
  if (st) return st;
  sph_snapshot *snap;
  int rc = sph_snapshot_open(a->restart, &snap, &err);
  if (rc == 0) {
    rc = sph_cli_snapshot_case_set(snap, a->sets, a->n_set, c, &err);
    sph_snapshot_close(snap);
  }
  if (rc) {
    fprintf(stderr, "sph run: --restart: %s\n", err.msg);
    return 1;
  }
  a->case_path = "the snapshot's case";
  if (!a->outdir) {
    snprintf(snapdir, n, "%s", a->restart);
    char *slash = strrchr(snapdir, '/');
    if (slash)
      *slash = '\0';
    else
      snprintf(snapdir, n, ".");
    a->outdir = snapdir;
  }
  return 0;
}

/* Before the set-up allocates anything: what it will make, from the case
 * alone (the counts are estimated from above; a large case's set-up
 * takes a while, and its memory is known before it is spent). */
static void print_plan(const run_args *a, const sph_case *c) {
  const double max = c->max_particles > 0.0 ? c->max_particles : sph_case_default_max();
  const double n = c->est_fluid + c->est_wall;
  const double bytes = n * SPH_BYTES_PER_PARTICLE;
  const double unit = bytes < 1e9 ? 1e6 : bytes < 1e12 ? 1e9 : 1e12;
  printf("%s: case %s (%s)\n", sph_version(), c->name, a->case_path);
  /* whole counts up to a billion; beyond (a case that will be refused:
   * the bound is below), three digits, never a 300-digit number (E12) */
  const char *fmt = n < 1e9 ? "  setting up about %.0f particles (fluid %.0f, walls at most %.0f): "
                              "memory about %.3g %s (%.0f bytes per particle); at most %.0f "
                              "particles allowed\n"
                            : "  setting up about %.3g particles (fluid %.3g, walls at most %.3g): "
                              "memory about %.3g %s (%.0f bytes per particle); at most %.0f "
                              "particles allowed\n";
  printf(fmt, n, c->est_fluid, c->est_wall, bytes / unit,
         unit == 1e6   ? "MB"
         : unit == 1e9 ? "GB"
                       : "TB",
         SPH_BYTES_PER_PARTICLE, max);
  fflush(stdout);
}

/* The start-up listing after the set-up: the run's own facts, then the
 * case exactly as it runs, line for line the listing sph_case_describe
 * gives the snapshots (numbers shortened to 6 significant digits for
 * reading). */
static void print_banner(const run_args *a, const sph_case *c, sph_sim *s, int nthreads) {
  const sph_particles *p = sph_sim_particles(s);
  const size_t nf = sph_particles_count_kind(p, SPH_KIND_FLUID);
  if (sph_procs_count() > 1)
    printf("  particles %zu (fluid %zu, wall %zu), %d processes (mpirun) of %d threads, output "
           "%s\n",
           p->n, nf, p->n - nf, sph_procs_count(), nthreads, a->outdir);
  else
    printf("  particles %zu (fluid %zu, wall %zu), threads %d, output %s\n", p->n, nf, p->n - nf,
           nthreads, a->outdir);
  double ratio = 1.0;
  const char *loop = sph_sim_loop(s, &ratio);
  if (ratio != 1.0)
    printf("  interaction loop: %s (the AVX2 loop took %.2f times the AVX-512 loop's time at "
           "start-up)\n",
           loop, ratio);
  if (sph_sim_fluid_removed(s))
    printf("  %zu fluid particles not made: closer than dx/2 to a wall particle (a wall drawn "
           "through the fluid)\n",
           sph_sim_fluid_removed(s));
  if (sph_sim_fluid_in_obstacles(s))
    printf(c->n_vessels ? "  %zu fluid particles not made: inside an obstacle, or outside every "
                          "vessel (a fluid block drawn through them)\n"
                        : "  %zu fluid particles not made: inside an obstacle box (a fluid block "
                          "drawn through it)\n",
           sph_sim_fluid_in_obstacles(s));
  if (sph_sim_walls_dropped(s))
    printf("  %zu wall particles not made: closer than dx/2 to an earlier wall's (walls that "
           "meet or cross)\n",
           sph_sim_walls_dropped(s));
  if (a->restart)
    printf("  restarting from %s at t = %.9g s, step %ld\n", a->restart, sph_sim_time(s),
           sph_sim_steps(s));
  if (c->scheme_kept && c->scheme_kept[0]) /* "" without a scheme */
    printf("  numerics.scheme %s: the case gives its own %s (kept: they replace the scheme's)\n",
           sph_scheme_name(c->scheme), c->scheme_kept);
  char *d = sph_case_describe(c);
  if (d) {
    printf("  the case as it runs (the parameters stored in every snapshot):\n");
    sph_cli_print_listing(stdout, d, "    ");
    free(d);
  }
  fflush(stdout);
}

/* SIGINT, SIGTERM and SIGHUP (a closed terminal or ssh session) end the
 * run after the current step with a final snapshot (doc/cli.md). A signal
 * the run was started ignoring stays ignored: `nohup sph run ...` survives
 * the hangup it asked to survive (issue 61, E3). */
static void install_signals(void) {
  static const int sigs[] = {SIGINT, SIGTERM, SIGHUP};
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  for (size_t k = 0; k < sizeof sigs / sizeof *sigs; k++) {
    struct sigaction old;
    if (sigaction(sigs[k], NULL, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    sigaction(sigs[k], &sa, NULL);
  }
  /* a program handed the run holds what came during the hand-over: now */
  catchable_signals(SIG_UNBLOCK);
}

static const char *signal_name(int sig) {
  return sig == SIGTERM ? "SIGTERM" : sig == SIGHUP ? "SIGHUP" : "SIGINT";
}

/* The message of how the run ended; its exit status. */
static int report_end(const sph_run_result *r, const sph_sim *s, const sph_error *err,
                      const char *outdir) {
  switch (r->status) {
  case SPH_RUN_END:
  case SPH_RUN_STOPPED: return 0;
  case SPH_RUN_INTERRUPTED:
    fprintf(stderr,
            "sph run: interrupted by %s at t = %.9g s (step %ld); final snapshot %s\n"
            "sph run: continue with: %s%s run --restart %s -o %s\n",
            signal_name(interrupted), sph_sim_time(s), r->steps,
            r->last_snapshot[0] ? r->last_snapshot : "(none)",
            sph_procs_count() > 1 ? "mpirun -n N " : "", sph_cli_program,
            r->last_snapshot[0] ? r->last_snapshot : "SNAPSHOT", outdir);
    return 4;
  case SPH_RUN_BLOWUP:
    fprintf(stderr, "sph run: %s\n", err->msg);
    fprintf(stderr, "sph run: last regular snapshot kept: %s\n",
            r->last_snapshot[0] ? r->last_snapshot : "(none)");
    return 3;
  case SPH_RUN_ERROR: break;
  }
  fprintf(stderr, "sph run: %s\n", err->msg);
  return 1;
}

/* Runs s (restored from a->restart when set) with progress and signals;
 * the exit status. */
static int run_sim(const run_args *a, const sph_case *c, sph_sim *s,
                   sph_snapshot_restart_data *rd) {
  progress_ctx pc;
  sph_progress_init(&pc.bar, stderr, c->t_end, c->stop == SPH_STOP_FRONT_AT_WALL ? "front" : NULL,
                    a->quiet, a->progress);
  /* under mpirun only rank 0 writes (procs.h); every process stops together */
  const int root = sph_procs_rank() == 0;
  sph_run_options opt = {
      root ? a->outdir : NULL, root ? on_progress : NULL, &pc, &interrupted, NULL, NULL};
  sph_run_result r;
  sph_error err = {{0}};
  const long steps0 = sph_sim_steps(s); /* a restart's steps before this run */
  const double w0 = sph_wall_seconds();
  sph_run_resume(s, &opt, a->restart ? rd : NULL, &r, &err);
  const double wall = sph_wall_seconds() - w0;
  sph_progress_done(&pc.bar);
  const int status = report_end(&r, s, &err, a->outdir);
  sph_procs_figures f; /* every process: a collective step */
  sph_sim_procs_figures(s, &f);
  sph_diag_row end; /* every process: a collective step (each sums its share) */
  sph_sim_diag(s, &end);
  if (!a->quiet && status != 1 && f.processes > 1 && f.passes > 0)
    printf("  %d processes: ghosts %.3g of the owned particles (each process's halo), %.3g MB "
           "sent per pass, all processes together; %s\n",
           f.processes, f.own > 0 ? f.ghosts / f.own : 0.0, f.bytes / (double)f.passes / 1e6,
           f.crowded ? "waits napping (more threads than cores)"
                     : "waits blocking (a core for every thread)");
  if (!a->quiet && status != 1 && f.processes > 1 && f.passes > 0)
    printf("  the cut: %s; the processes' shares of its weight %.3f to %.3f (moved at %ld "
           "cut%s); each waited %.3g to %.3g s for the others (%.2g to %.2g %% of the run)\n",
           f.balance ? "by measured work (--balance work)" : "by weights (--balance weights)",
           f.share_min, f.share_max, f.balanced, f.balanced == 1 ? "" : "s", f.waited_min,
           f.waited_max, wall > 0.0 ? 100.0 * f.waited_min / wall : 0.0,
           wall > 0.0 ? 100.0 * f.waited_max / wall : 0.0);
  if (!a->quiet && status != 1) {
    /* the steps the rule chose (sph_sim_step_range), then the closing line */
    double dt_first, dt_min, t_min;
    if (sph_sim_step_range(s, &dt_first, &dt_min, &t_min))
      printf("  steps: the first %.3g s, the smallest %.3g s (%.3g of the first) at t = %.9g s\n",
             dt_first, dt_min, dt_min / dt_first, t_min);
    if (end.n_removed)
      printf("  %zu fluid particles left the domain and were taken out (geometry.leaving: "
             "remove): %.3g %% of the fluid's mass\n",
             end.n_removed, 100.0 * end.mass_removed / (end.mass_removed + end.mass));
    /* the rate of this run's own steps (a restart's began at steps0) */
    const double n = (double)sph_sim_particles((sph_sim *)s)->n;
    const long mine = r.steps - steps0;
    const double ps = wall > 0 ? n * (double)mine / wall : 0.0;
    if (steps0 > 0)
      printf("%s at t = %.9g s: step %ld, %ld steps in this run, %zu outputs, %.2f s wall, %.3g "
             "particle-steps/s\n",
             sph_run_status_name(r.status), sph_sim_time(s), r.steps, mine, r.outputs, wall, ps);
    else
      printf("%s at t = %.9g s: %ld steps, %zu outputs, %.2f s wall, %.3g particle-steps/s\n",
             sph_run_status_name(r.status), sph_sim_time(s), r.steps, r.outputs, wall, ps);
  }
  return status;
}

/* A signal that came before the run started: nothing was written (issue
 * 21, D11). */
static int setup_interrupted(void) {
  fprintf(stderr, "sph run: interrupted by %s during set-up; nothing written\n",
          signal_name(interrupted));
  return 4;
}

/* Test hook (doc/testing.md): SPH_TEST_SETUP_PAUSE=S waits up to S seconds
 * before the set-up, or until a signal, so a test can signal the set-up;
 * it says so on stderr first, so the test knows when to. */
static void setup_pause(void) {
  const char *e = getenv("SPH_TEST_SETUP_PAUSE");
  const double secs = e ? atof(e) : 0.0;
  if (secs > 0.0) {
    fprintf(stderr, "sph run: SPH_TEST_SETUP_PAUSE: the set-up waits\n");
    fflush(stderr);
  }
  for (double t = 0.0; t < secs && !interrupted; t += 0.01) {
    struct timespec ts = {0, 10000000L};
    nanosleep(&ts, NULL);
  }
}

/* Under an MPI launcher (procs.h): rank 0 speaks for every process (the
 * others' messages are rank 0's, their state the same), and a build
 * without MPI refuses to run as several copies of one case. 0, or the exit
 * status. */
static int launched(void) {
  const int rank = sph_procs_launched_rank(), count = sph_procs_launched_count();
  if (count == 1) return 0;
  if (rank > 0 && (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr)))
    return 1;
  if (!sph_procs_built()) {
    fprintf(stderr,
            "sph run: started as %d processes (mpirun), but this sph was built without MPI: "
            "build it with ./configure --with-mpi (doc/parallel.md), or run one process\n",
            count);
    return 1;
  }
  return 0;
}

static int run_case(int argc, char **argv);

int sph_cli_run(int argc, char **argv) {
  const int status = run_case(argc, argv);
  sph_procs_end();
  return status;
}

static int run_case(int argc, char **argv) {
  install_signals(); /* from the start: a signal during set-up is reported too */
  const int st = launched();
  if (st) return st;
  run_args a = {.progress = SPH_CLI_PROGRESS_DEFAULT};
  a.sets = calloc((size_t)argc, sizeof *a.sets);
  if (!a.sets) return 1;
  int status = parse_run_args(argc, argv, &a);
  sph_case c;
  char snapdir[4096], defdir[4096];
  if (status == 0) status = load_run_case(&a, &c, snapdir, sizeof snapdir);
  free(a.sets);
  if (status) return status < 0 ? 0 : status;
  c.max_particles = a.max_particles;
  sph_error err = {{0}};
  if (sph_procs_start(&err)) { /* after the hand-over's exec: this program runs the case */
    fprintf(stderr, "sph run: %s\n", err.msg);
    sph_case_free(&c);
    return 1;
  }
  const int root = sph_procs_rank() == 0;
  if (!root) a.quiet = 1;
  const int nthreads = sph_cli_set_threads(a.threads, a.quiet);
  if (!a.outdir) {
    snprintf(defdir, sizeof defdir, "out/%s", c.name);
    a.outdir = defdir;
  }
  sph_sim *s = NULL;
  sph_snapshot_restart_data rd;
  sph_cli_lock lock = {-1, {0}};
  /* at once, before the set-up; rank 0 alone writes, so it alone asks */
  const long holder = root ? sph_cli_dir_holder(a.outdir) : 0;
  if (sph_procs_any(holder != 0)) {
    sph_case_free(&c);
    return sph_cli_dir_busy("sph run", a.outdir, holder);
  }
  status = 1;
  if (!a.quiet) print_plan(&a, &c);
  setup_pause();
  if (sph_procs_any(interrupted)) {
    status = setup_interrupted();
  } else if (sph_sim_create(&c, &s, &err)) {
    fprintf(stderr, "sph run: %s\n", err.msg);
  } else if (a.restart && sph_sim_restore(s, a.restart, &rd, &err)) {
    fprintf(stderr, "sph run: --restart: %s\n", err.msg);
  } else if (sph_procs_any(interrupted)) { /* during the set-up: nothing written yet */
    status = setup_interrupted();
    if (a.restart) sph_snapshot_restart_free(&rd);
  } else if (sph_procs_any(root && sph_cli_make_dirs(a.outdir))) {
    fprintf(stderr, "sph run: cannot create output directory %s: %s\n", a.outdir, strerror(errno));
    if (a.restart) sph_snapshot_restart_free(&rd);
  } else {
    if (a.weights_only) sph_sim_set_balance(s, 0);
    if (!sph_procs_any(root && sph_cli_dir_take("sph run", a.outdir, &lock) != 0)) {
      if (!a.quiet) print_banner(&a, &c, s, nthreads);
      status = run_sim(&a, &c, s, &rd);
    }
    sph_cli_dir_unlock(&lock);
    if (a.restart) sph_snapshot_restart_free(&rd);
  }
  sph_sim_free(s);
  sph_case_free(&c);
  return status;
}
