/* SPDX-License-Identifier: BSD-3-Clause */
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
 * which moving walls and the heat taken by the walls also change. The two
 * differ by what the fluid alone does not hold, tabulated as its two
 * parts: the work of moving walls (boundary_work + xsph_drift) and the heat
 * the wall particles took (their half of each fluid-wall pair's heat),
 * both in E0. With --reference FILE (a CSV with columns particles, time,
 * deviation_pct, e.g. tests/data/paper_a_table4.csv) the reference's values
 * are printed beside the fluid's own deviation at the audit's times. Plus
 * the mass drift (exactly zero: masses never change) and the momentum
 * drift, |P - P0 - impulse of the walls and gravity on the fluid| /
 * (M |g| t), at the last time (the momentum balance of the ledger).
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
             "                 [--reference FILE] [--threads N] [--max-particles N]\n"
             "                 [--set key=value]... [--quiet]\n"
             "\n"
             "Runs CASE once per fluid-particle count with the energy ledger on and prints\n"
             "the relative deviation of the total energy from its initial value against\n"
             "particle count and time (paper A, Table 4), as a closed balance and as the\n"
             "fluid's own energy, what makes them differ (the work of moving walls, the\n"
             "heat the walls took), plus the mass drift.\n"
             "\n"
             "  -p, --particles LIST  fluid-particle counts; dx is chosen for each\n"
             "  -T, --times LIST      times of the table (default: the case's\n"
             "                        time.output_times, else its output interval)\n"
             "  -o, --output DIR      where audit.csv, audit.md and the runs go\n"
             "                        (default out/<case name>_audit)\n"
             "  -r, --reference FILE  a published table to print beside the fluid's own\n"
             "                        deviation: CSV columns particles,time,deviation_pct\n"
             "                        (paper A's: tests/data/paper_a_table4.csv)\n"
             "  -t, --threads N       OpenMP threads\n"
             "      --max-particles N the bound on each run's particle count, as for sph run\n"
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
  for (size_t b = 0; b < c->n_fluid; b++)
    n += sph_case_block_points(&c->fluid[b], dx);
  return n;
}

/* dx whose fill is closest to `want` particles: (volume / want)^(1/d), then
 * the best of 401 values within +-20 % of it (ties: the one nearer the
 * start). */
static double dx_for(const sph_case *c, long want, long *got) {
  double area = 0.0;
  for (size_t b = 0; b < c->n_fluid; b++)
    area += sph_case_block_measure(&c->fluid[b]);
  const double dx0 = pow(area / (double)want, 1.0 / SPH_DIM);
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
  sph_progress_update(ctx, sph_sim_time(s), sph_sim_steps(s), 0.0, 0.0);
}

typedef struct audit_row {
  long particles;
  double dx;
  double dev[MAX_TIMES], fdev[MAX_TIMES];
  double work[MAX_TIMES], wall_heat[MAX_TIMES]; /* in E0: the walls' work, the heat they took */
  double mass_drift;
  double momentum_drift; /* |P - P0 - impulse| / (M |g| t) at the last time */
  long steps;
  double wall;
} audit_row;

typedef struct audit_args {
  const char *case_path, *outdir, *reference;
  double counts[MAX_RUNS], times[MAX_TIMES];
  int ncounts, ntimes, threads, quiet;
  double max_particles; /* --max-particles; 0: the default bound */
  const char **sets;    /* the user's --set overrides, then the audit's own */
  size_t n_set;
  char *text; /* the case file's text, read once */
  size_t len;
} audit_args;

/* What the run hands over, row by row (sph_run_options.row). */
typedef struct row_sink {
  const double *times;
  int nt, found;
  double gmag, e0;
  double mass0, mass_last, res_last, t_last;
  audit_row *row;
} row_sink;

static void on_row(void *ctx, const sph_diag_row *d) {
  row_sink *k = ctx;
  if (isnan(k->mass0)) k->mass0 = d->mass, k->e0 = d->total;
  k->mass_last = d->mass;
  k->res_last = hypot(d->momentum_residual_x, d->momentum_residual_y);
  k->t_last = d->time;
  k->row->steps = d->step;
  for (int i = 0; i < k->nt; i++)
    if (fabs(d->time - k->times[i]) <= 1e-12 * (1.0 + k->times[i])) {
      k->row->dev[i] = d->deviation;
      k->row->fdev[i] = d->fluid_deviation;
      /* E - E_f = U_walls - W - D, and E0 = E_f0 (walls start without heat) */
      const double w = k->e0 != 0.0 ? (d->boundary_work + d->xsph_drift) / k->e0 : 0.0;
      k->row->work[i] = w;
      k->row->wall_heat[i] = d->deviation - d->fluid_deviation + w;
      k->found++;
    }
}

/* Which column print_table shows. */
enum { COL_CLOSED, COL_FLUID, COL_WORK, COL_WALL_HEAT };

static void print_table(FILE *f, int md, const audit_row *rows, int nr, const double *times, int nt,
                        int col) {
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
      const double v[4] = {rows[r].dev[i], rows[r].fdev[i], rows[r].work[i], rows[r].wall_heat[i]};
      const double d = 100.0 * v[col];
      fprintf(f, md ? " %.4f %% |" : " %+9.4f%%", d);
    }
    fprintf(f, "\n");
  }
}

/* A published table to set beside the audit's (--reference): its particle
 * counts in the order of the file and its values (in %) at the audit's
 * times, NaN where it has none. */
typedef struct reference {
  const char *path;
  int n;
  long counts[MAX_RUNS];
  double pct[MAX_RUNS][MAX_TIMES];
} reference;

/* Reads path (CSV: particles, time, deviation_pct) into ref for the times
 * of the audit; 0, or -1 with err set. */
static int read_reference(const char *path, const double *times, int nt, reference *ref,
                          sph_error *err) {
  sph_csv t;
  *ref = (reference){path, 0, {0}, {{0}}};
  if (sph_csv_read(path, &t, err)) return -1;
  const int cn = sph_csv_column(&t, "particles", err), ct = sph_csv_column(&t, "time", err),
            cd = sph_csv_column(&t, "deviation_pct", err);
  int rc = cn < 0 || ct < 0 || cd < 0 ? -1 : 0;
  for (size_t r = 0; rc == 0 && r < t.nrow; r++) {
    const double *row = t.data + r * t.ncol;
    int k = 0;
    while (k < ref->n && ref->counts[k] != (long)row[cn])
      k++;
    if (k == ref->n) {
      if (ref->n == MAX_RUNS) {
        rc = sph_error_set(err, "%s: more than %d particle counts", path, MAX_RUNS);
        break;
      }
      ref->counts[ref->n++] = (long)row[cn];
      for (int i = 0; i < MAX_TIMES; i++)
        ref->pct[k][i] = NAN;
    }
    for (int i = 0; i < nt; i++)
      if (fabs(row[ct] - times[i]) <= 1e-9 * (1.0 + times[i])) ref->pct[k][i] = row[cd];
  }
  sph_csv_free(&t);
  return rc;
}

/* The reference's table, as print_table's (md or text). */
static void print_reference(FILE *f, int md, const reference *ref, int nt) {
  for (int r = 0; r < ref->n; r++) {
    fprintf(f, md ? "| %ld |" : "%10ld", ref->counts[r]);
    for (int i = 0; i < nt; i++) {
      const double v = ref->pct[r][i];
      if (isnan(v))
        fprintf(f, md ? " - |" : " %10s", "-");
      else
        fprintf(f, md ? " %g %% |" : " %9g%%", v);
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
              "sph audit: --particles: expected 1 to %d whole numbers >= 4 separated by "
              "commas, got '%s'\n",
              MAX_RUNS, v);
      return 2;
    }
  } else if (!strcmp(o, "-T") || !strcmp(o, "--times")) {
    a->ntimes = parse_list(v, a->times, MAX_TIMES);
    for (int k = 0; k < a->ntimes; k++)
      if (!(a->times[k] > (k ? a->times[k - 1] : 0.0))) a->ntimes = -1;
    if (a->ntimes <= 0) {
      fprintf(stderr,
              "sph audit: --times: expected 1 to %d increasing positive times separated by "
              "commas, got '%s'\n",
              MAX_TIMES, v);
      return 2;
    }
  } else if (!strcmp(o, "-o") || !strcmp(o, "--output")) {
    a->outdir = v;
  } else if (!strcmp(o, "-r") || !strcmp(o, "--reference")) {
    a->reference = v;
  } else if (!strcmp(o, "-t") || !strcmp(o, "--threads")) {
    if (sph_cli_parse_threads("sph audit", v, &a->threads)) return 2;
  } else if (!strcmp(o, "--max-particles")) {
    if (sph_cli_parse_max_particles("sph audit", v, &a->max_particles)) return 2;
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
  static const char *const with_value[] = {
      "-p",          "--particles", "-T",        "--times", "-o",    "--output",        "-r",
      "--reference", "-t",          "--threads", "-s",      "--set", "--max-particles", NULL};
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
                       char *set_end_interval, char *set_dx) {
  size_t len = (size_t)snprintf(set_times, n_times, "time.output_times=[");
  for (int k = 0; k < a->ntimes; k++)
    len += (size_t)snprintf(set_times + len, n_times - len, "%s%.17g", k ? "," : "", a->times[k]);
  snprintf(set_times + len, n_times - len, "]");
  snprintf(set_end, n_end, "time.end=%.17g", a->times[a->ntimes - 1]);
  if (set_end_interval)
    snprintf(set_end_interval, n_end, "time.output_interval=%.17g", a->times[a->ntimes - 1]);
  a->sets[a->n_set++] = "output.energy=true";
  a->sets[a->n_set++] = "output.snapshots=false";
  a->sets[a->n_set++] = set_times;
  a->sets[a->n_set++] = set_end;
  /* an interval longer than the audit's last time would be refused: the
   * outputs are then the audit's times alone */
  if (set_end_interval) a->sets[a->n_set++] = set_end_interval;
  a->sets[a->n_set++] = "time.stop=none";
  a->sets[a->n_set++] = set_dx;
}

/* Run r of the audit (the case as loaded with a->sets) into row; 0, or
 * the exit status (message printed). */
static int audit_run(const audit_args *a, int r, long got, double dx, audit_row *row) {
  sph_error err = {{0}};
  sph_case c;
  if (sph_case_parse(a->text, a->len, a->case_path, a->sets, a->n_set, &c, &err)) {
    /* the case read, so the audit's own settings broke it: say so (E12) */
    fprintf(stderr,
            "sph audit: the case with the audit's settings (time.end = %g, the last of --times, "
            "and dx = %g for %ld particles): %s\n",
            a->times[a->ntimes - 1], dx, got, err.msg);
    return 1;
  }
  c.max_particles = a->max_particles;
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
    row_sink sink = {a->times, a->ntimes, 0, g > 0.0 ? g : 1.0, NAN, NAN, NAN, NAN, NAN, row};
    for (int i = 0; i < a->ntimes; i++)
      row->dev[i] = row->fdev[i] = row->work[i] = row->wall_heat[i] = NAN;
    sph_progress bar;
    sph_progress_init(&bar, stderr, c.t_end, NULL, a->quiet, 0.0); /* (a line per run instead) */
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

/* The tables on stdout (md = 0) or in audit.md (md = 1). */
static void print_tables(FILE *f, int md, const char *name, const audit_row *rows, int nr,
                         const double *times, int nt, const reference *ref) {
  static const char *const title[2][5] = {
      {"Energy deviation (E - E0)/E0, closed balance (kinetic + potential + internal\n"
       "- moving-wall work - XSPH drift), case %s:\n",
       "\nThe fluid's own kinetic + potential + internal energy against its start\n"
       "(the quantity of paper A, Table 4):\n",
       "\nBeside it, %s:\n",
       "\nWhat the fluid alone does not hold, in E0: the work of moving walls (and the\n"
       "XSPH drift)\n",
       "\nand the heat the wall particles took (their half of the fluid-wall pairs'\n"
       "heat); closed balance = the fluid's own + heat - work:\n"},
      {"Energy audit of case `%s`.\n\nClosed balance, (E - E0)/E0:\n\n",
       "\nThe fluid's own kinetic + potential + internal energy (paper A, Table 4):\n\n",
       "\nBeside it, %s:\n\n",
       "\nWhat the fluid alone does not hold, in E0: the work of moving walls (and the XSPH "
       "drift)\n\n",
       "\nand the heat the wall particles took (their half of the fluid-wall pairs' heat); "
       "closed balance = the fluid's own + heat - work:\n\n"}};
  fprintf(f, title[md][0], name);
  print_table(f, md, rows, nr, times, nt, COL_CLOSED);
  fprintf(f, "%s", title[md][1]);
  print_table(f, md, rows, nr, times, nt, COL_FLUID);
  if (ref && ref->n) {
    fprintf(f, title[md][2], ref->path);
    print_table(f, md, NULL, 0, times, nt, COL_FLUID); /* the header */
    print_reference(f, md, ref, nt);
  }
  fprintf(f, "%s", title[md][3]);
  print_table(f, md, rows, nr, times, nt, COL_WORK);
  fprintf(f, "%s", title[md][4]);
  print_table(f, md, rows, nr, times, nt, COL_WALL_HEAT);
}

/* The report on stdout. */
static void print_report(const char *name, const audit_row *rows, int nr, const double *times,
                         int nt, const reference *ref) {
  print_tables(stdout, 0, name, rows, nr, times, nt, ref);
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
                        const double *times, int nt, const reference *ref) {
  char path[4096];
  FILE *f = path_join(path, sizeof path, outdir, "audit.csv") ? NULL : fopen(path, "w");
  if (f) {
    static const char *const cols[] = {
        "particles", "dx",        "time",       "energy_deviation", "fluid_energy_deviation",
        "wall_work", "wall_heat", "mass_drift", "momentum_drift",   NULL};
    sph_csv_put_columns(f, cols, 1);
    fputc('\n', f);
    for (int r = 0; r < nr; r++)
      for (int k = 0; k < nt; k++)
        fprintf(f, "%ld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", rows[r].particles,
                rows[r].dx, times[k], rows[r].dev[k], rows[r].fdev[k], rows[r].work[k],
                rows[r].wall_heat[k], rows[r].mass_drift, rows[r].momentum_drift);
    fclose(f);
  }
  FILE *m = path_join(path, sizeof path, outdir, "audit.md") ? NULL : fopen(path, "w");
  if (m) {
    print_tables(m, 1, name, rows, nr, times, nt, ref);
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
static int audit_all(audit_args *a, const sph_case *base, const reference *ref) {
  audit_row rows[MAX_RUNS];
  char set_dx[128], set_times[4096], set_end[128], set_interval[128];
  const int long_interval = base->output_interval > a->times[a->ntimes - 1];
  audit_sets(a, set_times, sizeof set_times, set_end, sizeof set_end,
             long_interval ? set_interval : NULL, set_dx);
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
  print_report(base->name, rows, a->ncounts, a->times, a->ntimes, ref);
  if (write_report(a->outdir, base->name, rows, a->ncounts, a->times, a->ntimes, ref)) {
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
  /* a case of the other dimension goes to the other program (issue 61, E9) */
  int loaded = sph_cli_read_case(a.case_path, &a.text, &a.len, &err) == 0;
  if (loaded && sph_cli_hand_over("audit", a.case_path, a.text, a.len, a.sets, a.n_set)) {
    free(a.text);
    free(a.sets);
    return 1;
  }
  loaded = loaded && sph_case_parse(a.text, a.len, a.case_path, a.sets, a.n_set, &base, &err) == 0;
  if (!loaded) {
    fprintf(stderr, "sph audit: %s\n", err.msg);
    status = 1;
  } else {
    default_times(&a, &base);
    if (!a.outdir) {
      snprintf(defdir, sizeof defdir, "out/%s_audit", base.name);
      a.outdir = defdir;
    }
    sph_cli_lock lock = {-1, {0}};
    if (sph_cli_make_dirs(a.outdir)) {
      fprintf(stderr, "sph audit: cannot create %s: %s\n", a.outdir, strerror(errno));
      status = 1;
    } else if (sph_cli_dir_take("sph audit", a.outdir, &lock)) { /* one run per directory */
      status = 1;
    } else {
      static reference ref; /* large: not on the stack */
      if (a.reference && read_reference(a.reference, a.times, a.ntimes, &ref, &err)) {
        fprintf(stderr, "sph audit: --reference: %s\n", err.msg);
        status = 1;
      } else {
        status = audit_all(&a, &base, a.reference ? &ref : NULL);
      }
    }
    sph_cli_dir_unlock(&lock);
  }
  sph_case_free(&base);
  free(a.text);
  free(a.sets);
  return status;
}
