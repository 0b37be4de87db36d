/*
 * cli_audit.c - `sph audit CASE --particles N1,N2,... [--times t1,t2,...]`
 *
 * The energy audit of paper A §9 (Table 4): the case is run once per
 * requested fluid-particle count, with the energy ledger on and snapshots
 * off, and the deviation of the total energy from its initial value is
 * tabulated against particle count and time. For each count the spacing dx
 * is chosen so that the lattice fill of the case's fluid blocks gives the
 * count closest to the one asked for (the actual count is reported).
 *
 * Two deviations are reported: the closed balance (kinetic + potential +
 * internal energy of fluid and walls - work of moving walls - XSPH drift,
 * diagnostics column energy_deviation) and the paper-style deviation of the
 * fluid's own kinetic + potential + internal energy (fluid_energy_deviation),
 * which moving walls and the heat taken by the walls also change. Plus the
 * mass drift (exactly zero: masses never change) and the momentum drift,
 * |P - P0 - impulse of the walls and gravity on the fluid| / (M |g| t), at
 * the last time (the momentum balance of the ledger).
 * Output: a table on stdout, DIR/audit.csv and DIR/audit.md, and each run's
 * diagnostics in DIR/n<count>/. A progress line per run goes to stderr.
 * The table's numbers are the diagnostics rows the run hands over as it
 * writes them (sph_run_options.row), not a re-reading of the CSV.
 */
#include "config.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"
#include "cli/progress.h"
#include "sph.h"

#define MAX_RUNS 32
#define MAX_TIMES 64

static void audit_usage(FILE *f) {
  fprintf(f, "usage: sph audit CASE --particles N1,N2,... [--times t1,t2,...] [-o DIR]\n"
             "                 [--threads N] [--set key=value]... [--quiet]\n"
             "\n"
             "Runs CASE once per fluid-particle count with the energy ledger on and prints\n"
             "the relative deviation of the total energy from its initial value against\n"
             "particle count and time (paper A, Table 4), as a closed balance and as the\n"
             "fluid's own energy, plus the mass drift.\n"
             "\n"
             "  -p, --particles LIST  fluid-particle counts; dx is chosen for each\n"
             "  -T, --times LIST      times of the table (default: the case's\n"
             "                        time.output_times, else its output interval)\n"
             "  -o, --output DIR      where audit.csv, audit.md and the runs go\n"
             "                        (default out/<case name>_audit)\n"
             "  -t, --threads N       OpenMP threads\n"
             "  -s, --set K=V         case override, as for sph run\n"
             "  -q, --quiet           no progress lines\n");
}

/* dir/name into out (n bytes); -1 if it does not fit. */
static int path_join(char *out, size_t n, const char *dir, const char *name) {
  const int k = snprintf(out, n, "%s/%s", dir, name);
  return k < 0 || (size_t)k >= n ? -1 : 0;
}

/* Comma-separated numbers into v (at most max); returns the count or -1. */
static int parse_list(const char *s, double *v, int max) {
  int n = 0;
  while (*s) {
    char *end;
    errno = 0;
    double x = strtod(s, &end);
    if (end == s || errno || !isfinite(x) || n == max) return -1;
    v[n++] = x;
    s = end;
    if (*s == ',')
      s++;
    else if (*s)
      return -1;
  }
  return n;
}

/* Fluid particles the case's blocks hold at spacing dx (as sim.c fills them). */
static long count_at(const sph_case *c, double dx) {
  long n = 0;
  for (size_t b = 0; b < c->n_fluid; b++) {
    const sph_fluid_block *f = &c->fluid[b];
    n += (long)floor((f->x1 - f->x0) / dx + 1e-9) * (long)floor((f->y1 - f->y0) / dx + 1e-9);
  }
  return n;
}

/* dx whose fill is closest to `want` particles: sqrt(area / want), then the
 * best of 401 values within +-20 % of it (ties: the one nearer the start). */
static double dx_for(const sph_case *c, long want, long *got) {
  double area = 0.0;
  for (size_t b = 0; b < c->n_fluid; b++)
    area += (c->fluid[b].x1 - c->fluid[b].x0) * (c->fluid[b].y1 - c->fluid[b].y0);
  const double dx0 = sqrt(area / (double)want);
  double best = dx0;
  long bestn = count_at(c, dx0);
  for (int k = 1; k <= 200; k++)
    for (int sgn = -1; sgn <= 1; sgn += 2) {
      const double dx = dx0 * (1.0 + sgn * 1e-3 * k);
      const long n = count_at(c, dx);
      if (labs(n - want) < labs(bestn - want)) {
        best = dx;
        bestn = n;
      }
    }
  *got = bestn;
  return best;
}

static void on_progress(void *ctx, const sph_sim *s) {
  sph_progress_update(ctx, sph_sim_time(s), sph_sim_steps(s));
}

typedef struct audit_row {
  long particles;
  double dx;
  double dev[MAX_TIMES], fdev[MAX_TIMES];
  double mass_drift;
  double momentum_drift; /* |P - P0 - impulse| / (M |g| t) at the last time */
  long steps;
  double wall;
} audit_row;

typedef struct audit_args {
  const char *case_path, *outdir;
  double counts[MAX_RUNS], times[MAX_TIMES];
  int ncounts, ntimes, threads, quiet;
  const char **sets; /* the user's --set overrides, then the audit's own */
  size_t n_set;
} audit_args;

/* What the run hands over, row by row (sph_run_options.row). */
typedef struct row_sink {
  const double *times;
  int nt, found;
  double gmag;
  double mass0, mass_last, res_last, t_last;
  audit_row *row;
} row_sink;

static void on_row(void *ctx, const sph_diag_row *d) {
  row_sink *k = ctx;
  if (isnan(k->mass0)) k->mass0 = d->mass;
  k->mass_last = d->mass;
  k->res_last = hypot(d->momentum_residual_x, d->momentum_residual_y);
  k->t_last = d->time;
  k->row->steps = d->step;
  for (int i = 0; i < k->nt; i++)
    if (fabs(d->time - k->times[i]) <= 1e-12 * (1.0 + k->times[i])) {
      k->row->dev[i] = d->deviation;
      k->row->fdev[i] = d->fluid_deviation;
      k->found++;
    }
}

static void print_table(FILE *f, int md, const audit_row *rows, int nr, const double *times, int nt,
                        int fluid) {
  if (md) {
    fprintf(f, "| particles \\ t (s) |");
    for (int i = 0; i < nt; i++)
      fprintf(f, " %g |", times[i]);
    fprintf(f, "\n|---|");
    for (int i = 0; i < nt; i++)
      fprintf(f, "---|");
    fprintf(f, "\n");
  } else {
    fprintf(f, "%10s", "particles");
    for (int i = 0; i < nt; i++)
      fprintf(f, " %10g", times[i]);
    fprintf(f, "\n");
  }
  for (int r = 0; r < nr; r++) {
    fprintf(f, md ? "| %ld |" : "%10ld", rows[r].particles);
    for (int i = 0; i < nt; i++) {
      const double d = 100.0 * (fluid ? rows[r].fdev[i] : rows[r].dev[i]);
      fprintf(f, md ? " %.4f %% |" : " %+9.4f%%", d);
    }
    fprintf(f, "\n");
  }
}

/* One option with its value (argv[*i + 1]) into a; 0, or 2 (usage error,
 * message printed). */
static int audit_option(audit_args *a, int argc, char **argv, int *i) {
  const char *o = argv[*i];
  if (*i + 1 >= argc) {
    fprintf(stderr, "sph audit: option %s needs a value\n", o);
    return 2;
  }
  const char *v = argv[++*i];
  if (!strcmp(o, "-p") || !strcmp(o, "--particles")) {
    a->ncounts = parse_list(v, a->counts, MAX_RUNS);
    for (int k = 0; k < a->ncounts; k++)
      if (a->counts[k] < 4 || a->counts[k] != floor(a->counts[k])) a->ncounts = -1;
    if (a->ncounts <= 0) {
      fprintf(stderr,
              "sph audit: --particles: expected whole numbers >= 4 separated by "
              "commas, got '%s'\n",
              v);
      return 2;
    }
  } else if (!strcmp(o, "-T") || !strcmp(o, "--times")) {
    a->ntimes = parse_list(v, a->times, MAX_TIMES);
    for (int k = 0; k < a->ntimes; k++)
      if (!(a->times[k] > (k ? a->times[k - 1] : 0.0))) a->ntimes = -1;
    if (a->ntimes <= 0) {
      fprintf(stderr,
              "sph audit: --times: expected increasing positive times separated by "
              "commas, got '%s'\n",
              v);
      return 2;
    }
  } else if (!strcmp(o, "-o") || !strcmp(o, "--output")) {
    a->outdir = v;
  } else if (!strcmp(o, "-t") || !strcmp(o, "--threads")) {
    if (sph_cli_parse_threads("sph audit", v, &a->threads)) return 2;
  } else {
    if (!strchr(v, '=')) {
      fprintf(stderr, "sph audit: --set: expected key=value, got '%s'\n", v);
      return 2;
    }
    a->sets[a->n_set++] = v;
  }
  return 0;
}

/* The command line into a; -1 after --help (printed), 0, or 2. */
static int parse_audit_args(int argc, char **argv, audit_args *a) {
  static const char *const with_value[] = {"-p", "--particles", "-T", "--times", "-o", "--output",
                                           "-t", "--threads",   "-s", "--set",   NULL};
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i];
    if (!strcmp(o, "-h") || !strcmp(o, "--help")) {
      audit_usage(stdout);
      return -1;
    } else if (!strcmp(o, "-q") || !strcmp(o, "--quiet")) {
      a->quiet = 1;
    } else if (sph_cli_is_one_of(o, with_value)) {
      if (audit_option(a, argc, argv, &i)) return 2;
    } else if (o[0] == '-' && o[1]) {
      fprintf(stderr, "sph audit: unknown option '%s' (see sph audit --help)\n", o);
      return 2;
    } else if (!a->case_path) {
      a->case_path = o;
    } else {
      fprintf(stderr, "sph audit: more than one case file given\n");
      return 2;
    }
  }
  if (!a->case_path || a->ncounts <= 0) {
    audit_usage(stderr);
    return 2;
  }
  return 0;
}

/* Without --times: the case's output times, else its output interval. */
static void default_times(audit_args *a, const sph_case *base) {
  if (a->ntimes) return;
  if (base->n_output_times) {
    for (size_t k = 0; k < base->n_output_times && a->ntimes < MAX_TIMES; k++)
      a->times[a->ntimes++] = base->output_times[k];
    return;
  }
  for (int k = 1; k * base->output_interval <= base->t_end * (1 + 1e-12) && a->ntimes < MAX_TIMES;
       k++)
    a->times[a->ntimes++] = k * base->output_interval;
}

/* The overrides every audit run gets after the user's: ledger on,
 * snapshots off, outputs at the audit times, to the last of them, and
 * the spacing (set_dx, filled per run). */
static void audit_sets(audit_args *a, char *set_times, size_t n_times, char *set_end, size_t n_end,
                       char *set_dx) {
  size_t len = (size_t)snprintf(set_times, n_times, "time.output_times=[");
  for (int k = 0; k < a->ntimes; k++)
    len += (size_t)snprintf(set_times + len, n_times - len, "%s%.17g", k ? "," : "", a->times[k]);
  snprintf(set_times + len, n_times - len, "]");
  snprintf(set_end, n_end, "time.end=%.17g", a->times[a->ntimes - 1]);
  a->sets[a->n_set++] = "output.energy=true";
  a->sets[a->n_set++] = "output.snapshots=false";
  a->sets[a->n_set++] = set_times;
  a->sets[a->n_set++] = set_end;
  a->sets[a->n_set++] = "time.stop=none";
  a->sets[a->n_set++] = set_dx;
}

/* Run r of the audit (the case as loaded with a->sets) into row; 0, or
 * the exit status (message printed). */
static int audit_run(const audit_args *a, int r, long got, double dx, audit_row *row) {
  sph_error err = {{0}};
  sph_case c;
  if (sph_case_load(a->case_path, a->sets, a->n_set, &c, &err)) {
    fprintf(stderr, "sph audit: %s\n", err.msg);
    return 1;
  }
  char dir[4096], name[64];
  snprintf(name, sizeof name, "n%ld", got);
  sph_sim *s = NULL;
  int status = 1;
  if (path_join(dir, sizeof dir, a->outdir, name)) {
    fprintf(stderr, "sph audit: output path too long\n");
  } else if (sph_cli_make_dirs(dir)) {
    fprintf(stderr, "sph audit: cannot create %s: %s\n", dir, strerror(errno));
  } else if (sph_sim_create(&c, &s, &err)) {
    fprintf(stderr, "sph audit: %s\n", err.msg);
  } else {
    const double g = hypot(c.gravity[0], c.gravity[1]);
    row_sink sink = {a->times, a->ntimes, 0, g > 0.0 ? g : 1.0, NAN, NAN, NAN, NAN, row};
    for (int i = 0; i < a->ntimes; i++)
      row->dev[i] = row->fdev[i] = NAN;
    sph_progress bar;
    sph_progress_init(&bar, stderr, c.t_end, a->quiet);
    sph_run_options opt = {dir, on_progress, &bar, NULL, on_row, &sink};
    sph_run_result res;
    const double w0 = sph_wall_seconds();
    const int rc = sph_run(s, &opt, &res, &err);
    row->wall = sph_wall_seconds() - w0;
    sph_progress_done(&bar);
    row->particles = got;
    row->dx = dx;
    row->mass_drift = (sink.mass_last - sink.mass0) / sink.mass0;
    row->momentum_drift = sink.res_last / (sink.mass_last * sink.gmag * sink.t_last);
    if (rc || sink.found != a->ntimes) {
      fprintf(stderr, "sph audit: run %d (%ld particles): %s\n", r + 1, got,
              rc ? err.msg : "diagnostics lack the audit times");
      status = res.status == SPH_RUN_BLOWUP ? 3 : 1;
    } else {
      status = 0;
    }
  }
  sph_sim_free(s);
  sph_case_free(&c);
  return status;
}

/* The tables on stdout. */
static void print_report(const char *name, const audit_row *rows, int nr, const double *times,
                         int nt) {
  printf("Energy deviation (E - E0)/E0, closed balance (kinetic + potential + internal\n"
         "- moving-wall work - XSPH drift), case %s:\n",
         name);
  print_table(stdout, 0, rows, nr, times, nt, 0);
  printf("\nThe fluid's own kinetic + potential + internal energy against its start\n"
         "(the quantity of paper A, Table 4; it differs from the closed balance by the\n"
         "work of moving walls and the heat the walls take, which the fluid alone\n"
         "does not hold):\n");
  print_table(stdout, 0, rows, nr, times, nt, 1);
  printf("\nMass drift at t = %g s:", times[nt - 1]);
  for (int r = 0; r < nr; r++)
    printf(" %ld: %.3g", rows[r].particles, rows[r].mass_drift);
  printf("\nMomentum drift |P - P0 - impulse of walls and gravity| / (M |g| t) at t = %g s:",
         times[nt - 1]);
  for (int r = 0; r < nr; r++)
    printf(" %ld: %.3g", rows[r].particles, rows[r].momentum_drift);
  printf("\n");
}

/* DIR/audit.csv and DIR/audit.md; 0 or -1. */
static int write_report(const char *outdir, const char *name, const audit_row *rows, int nr,
                        const double *times, int nt) {
  char path[4096];
  FILE *f = path_join(path, sizeof path, outdir, "audit.csv") ? NULL : fopen(path, "w");
  if (f) {
    fprintf(f, "particles,dx,time,energy_deviation,fluid_energy_deviation,mass_drift,"
               "momentum_drift\n");
    for (int r = 0; r < nr; r++)
      for (int k = 0; k < nt; k++)
        fprintf(f, "%ld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", rows[r].particles, rows[r].dx,
                times[k], rows[r].dev[k], rows[r].fdev[k], rows[r].mass_drift,
                rows[r].momentum_drift);
    fclose(f);
  }
  FILE *m = path_join(path, sizeof path, outdir, "audit.md") ? NULL : fopen(path, "w");
  if (m) {
    fprintf(m, "Energy audit of case `%s`.\n\nClosed balance, (E - E0)/E0:\n\n", name);
    print_table(m, 1, rows, nr, times, nt, 0);
    fprintf(m, "\nThe fluid's own kinetic + potential + internal energy (paper A, Table 4):\n\n");
    print_table(m, 1, rows, nr, times, nt, 1);
    fprintf(m, "\n| particles | mass drift | momentum drift (t = %g s) |\n|---|---|---|\n",
            times[nt - 1]);
    for (int r = 0; r < nr; r++)
      fprintf(m, "| %ld | %.3g | %.3g |\n", rows[r].particles, rows[r].mass_drift,
              rows[r].momentum_drift);
    fclose(m);
  }
  return f && m ? 0 : -1;
}

/* Every run of the audit, then the report; the exit status. */
static int audit_all(audit_args *a, const sph_case *base) {
  audit_row rows[MAX_RUNS];
  char set_dx[128], set_times[4096], set_end[128];
  audit_sets(a, set_times, sizeof set_times, set_end, sizeof set_end, set_dx);
  for (int r = 0; r < a->ncounts; r++) {
    long got;
    const double dx = dx_for(base, (long)a->counts[r], &got);
    snprintf(set_dx, sizeof set_dx, "numerics.dx=%.17g", dx);
    const int st = audit_run(a, r, got, dx, &rows[r]);
    if (st) return st;
    if (!a->quiet)
      fprintf(stderr,
              "audit: run %d/%d: %ld fluid particles (asked %ld), dx = %.6g m, %ld steps, "
              "%.1f s wall; deviation at t = %g s: %+.4f %% (fluid's own: %+.4f %%)\n",
              r + 1, a->ncounts, got, (long)a->counts[r], dx, rows[r].steps, rows[r].wall,
              a->times[a->ntimes - 1], 100 * rows[r].dev[a->ntimes - 1],
              100 * rows[r].fdev[a->ntimes - 1]);
  }
  print_report(base->name, rows, a->ncounts, a->times, a->ntimes);
  if (write_report(a->outdir, base->name, rows, a->ncounts, a->times, a->ntimes)) {
    fprintf(stderr, "sph audit: cannot write %s/audit.{csv,md}\n", a->outdir);
    return 1;
  }
  return 0;
}

int sph_cli_audit(int argc, char **argv) {
  audit_args a = {0};
  a.sets = calloc((size_t)argc + 8, sizeof *a.sets);
  if (!a.sets) return 1;
  int status = parse_audit_args(argc, argv, &a);
  if (status) {
    free(a.sets);
    return status < 0 ? 0 : status;
  }
  sph_cli_set_threads(a.threads, 1);
  sph_error err = {{0}};
  sph_case base;
  char defdir[4096];
  if (sph_case_load(a.case_path, a.sets, a.n_set, &base, &err)) {
    fprintf(stderr, "sph audit: %s\n", err.msg);
    status = 1;
  } else {
    default_times(&a, &base);
    if (!a.outdir) {
      snprintf(defdir, sizeof defdir, "out/%s_audit", base.name);
      a.outdir = defdir;
    }
    if (sph_cli_make_dirs(a.outdir)) {
      fprintf(stderr, "sph audit: cannot create %s: %s\n", a.outdir, strerror(errno));
      status = 1;
    } else {
      status = audit_all(&a, &base);
    }
  }
  sph_case_free(&base);
  free(a.sets);
  return status;
}
