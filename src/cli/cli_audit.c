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
 */
#include "config.h"

#include <errno.h>
#include <math.h>
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

#define MAX_RUNS 32
#define MAX_TIMES 64

static void audit_usage(FILE *f) {
  fprintf(f,
          "usage: sph audit CASE --particles N1,N2,... [--times t1,t2,...] [-o DIR]\n"
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
    if (*s == ',') s++;
    else if (*s) return -1;
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

/* Reads the rows of DIR/diagnostics.csv at the given times. */
static int read_diag(const char *dir, const double *times, int nt, double gmag, audit_row *row) {
  char path[4096], line[8192];
  if (path_join(path, sizeof path, dir, "diagnostics.csv")) return -1;
  FILE *f = fopen(path, "r");
  if (!f) return -1;
  int c_time = -1, c_dev = -1, c_fdev = -1, c_mass = -1, c_step = -1, c_rx = -1, c_ry = -1;
  int found = 0;
  double mass0 = NAN, mass_last = NAN, res_last = NAN, t_last = NAN;
  for (int i = 0; i < nt; i++) row->dev[i] = row->fdev[i] = NAN;
  while (fgets(line, sizeof line, f)) {
    double v[32];
    int n = 0, col = 0;
    if (c_time < 0) {
      for (char *tok = strtok(line, ",\n"); tok; tok = strtok(NULL, ",\n"), col++) {
        if (!strcmp(tok, "time")) c_time = col;
        if (!strcmp(tok, "energy_deviation")) c_dev = col;
        if (!strcmp(tok, "fluid_energy_deviation")) c_fdev = col;
        if (!strcmp(tok, "mass")) c_mass = col;
        if (!strcmp(tok, "step")) c_step = col;
        if (!strcmp(tok, "momentum_residual_x")) c_rx = col;
        if (!strcmp(tok, "momentum_residual_y")) c_ry = col;
      }
      if (c_time < 0 || c_dev < 0 || c_fdev < 0 || c_mass < 0 || c_step < 0 || c_rx < 0 ||
          c_ry < 0)
        break;
      continue;
    }
    for (char *tok = strtok(line, ",\n"); tok && n < 32; tok = strtok(NULL, ",\n")) v[n++] = strtod(tok, NULL);
    if (n <= c_fdev || n <= c_ry || n <= c_rx) continue;
    if (isnan(mass0)) mass0 = v[c_mass];
    mass_last = v[c_mass];
    res_last = hypot(v[c_rx], v[c_ry]);
    t_last = v[c_time];
    row->steps = (long)v[c_step];
    for (int i = 0; i < nt; i++)
      if (fabs(v[c_time] - times[i]) <= 1e-12 * (1.0 + times[i])) {
        row->dev[i] = v[c_dev];
        row->fdev[i] = v[c_fdev];
        found++;
      }
  }
  fclose(f);
  row->mass_drift = (mass_last - mass0) / mass0;
  row->momentum_drift = res_last / (mass_last * gmag * t_last);
  return found == nt ? 0 : -1;
}

static void print_table(FILE *f, int md, const audit_row *rows, int nr, const double *times, int nt,
                        int fluid) {
  if (md) {
    fprintf(f, "| particles \\ t (s) |");
    for (int i = 0; i < nt; i++) fprintf(f, " %g |", times[i]);
    fprintf(f, "\n|---|");
    for (int i = 0; i < nt; i++) fprintf(f, "---|");
    fprintf(f, "\n");
  } else {
    fprintf(f, "%10s", "particles");
    for (int i = 0; i < nt; i++) fprintf(f, " %10g", times[i]);
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

int sph_cli_audit(int argc, char **argv) {
  const char *case_path = NULL, *outdir = NULL;
  double counts[MAX_RUNS], times[MAX_TIMES];
  int ncounts = 0, ntimes = 0, threads = 0, quiet = 0;
  const char **sets = calloc((size_t)argc + 8, sizeof *sets);
  size_t n_set = 0;
  if (!sets) return 1;
  int status = 2;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
      audit_usage(stdout);
      free(sets);
      return 0;
    } else if (!strcmp(a, "-q") || !strcmp(a, "--quiet")) {
      quiet = 1;
    } else if (!strcmp(a, "-p") || !strcmp(a, "--particles") || !strcmp(a, "-T") ||
               !strcmp(a, "--times") || !strcmp(a, "-o") || !strcmp(a, "--output") ||
               !strcmp(a, "-t") || !strcmp(a, "--threads") || !strcmp(a, "-s") ||
               !strcmp(a, "--set")) {
      if (i + 1 >= argc) {
        fprintf(stderr, "sph audit: option %s needs a value\n", a);
        goto done;
      }
      const char *v = argv[++i];
      if (!strcmp(a, "-p") || !strcmp(a, "--particles")) {
        ncounts = parse_list(v, counts, MAX_RUNS);
        for (int k = 0; k < ncounts; k++)
          if (counts[k] < 4 || counts[k] != floor(counts[k])) ncounts = -1;
        if (ncounts <= 0) {
          fprintf(stderr, "sph audit: --particles: expected whole numbers >= 4 separated by "
                          "commas, got '%s'\n", v);
          goto done;
        }
      } else if (!strcmp(a, "-T") || !strcmp(a, "--times")) {
        ntimes = parse_list(v, times, MAX_TIMES);
        for (int k = 0; k < ntimes; k++)
          if (!(times[k] > (k ? times[k - 1] : 0.0))) ntimes = -1;
        if (ntimes <= 0) {
          fprintf(stderr, "sph audit: --times: expected increasing positive times separated by "
                          "commas, got '%s'\n", v);
          goto done;
        }
      } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
        outdir = v;
      } else if (!strcmp(a, "-t") || !strcmp(a, "--threads")) {
        char *end;
        long t = strtol(v, &end, 10);
        if (*end || t < 1 || t > 4096) {
          fprintf(stderr, "sph audit: --threads: expected a whole number >= 1, got '%s'\n", v);
          goto done;
        }
        threads = (int)t;
      } else {
        if (!strchr(v, '=')) {
          fprintf(stderr, "sph audit: --set: expected key=value, got '%s'\n", v);
          goto done;
        }
        sets[n_set++] = v;
      }
    } else if (a[0] == '-' && a[1]) {
      fprintf(stderr, "sph audit: unknown option '%s' (see sph audit --help)\n", a);
      goto done;
    } else if (!case_path) {
      case_path = a;
    } else {
      fprintf(stderr, "sph audit: more than one case file given\n");
      goto done;
    }
  }
  if (!case_path || ncounts <= 0) {
    audit_usage(stderr);
    goto done;
  }
#ifdef _OPENMP
  if (threads > 0) omp_set_num_threads(threads);
#else
  (void)threads;
#endif
  status = 1;
  sph_error err = {{0}};
  sph_case base;
  if (sph_case_load(case_path, sets, n_set, &base, &err)) {
    fprintf(stderr, "sph audit: %s\n", err.msg);
    sph_case_free(&base);
    goto done;
  }
  if (ntimes == 0) {
    if (base.n_output_times) {
      for (size_t k = 0; k < base.n_output_times && ntimes < MAX_TIMES; k++)
        times[ntimes++] = base.output_times[k];
    } else {
      for (int k = 1; k * base.output_interval <= base.t_end * (1 + 1e-12) && ntimes < MAX_TIMES;
           k++)
        times[ntimes++] = k * base.output_interval;
    }
  }
  char defdir[4096];
  if (!outdir) {
    snprintf(defdir, sizeof defdir, "out/%s_audit", base.name);
    outdir = defdir;
  }
  if (sph_cli_make_dirs(outdir)) {
    fprintf(stderr, "sph audit: cannot create %s: %s\n", outdir, strerror(errno));
    sph_case_free(&base);
    goto done;
  }
  audit_row rows[MAX_RUNS];
  char set_dx[128], set_times[4096], set_end[128];
  {
    size_t len = (size_t)snprintf(set_times, sizeof set_times, "time.output_times=[");
    for (int k = 0; k < ntimes; k++)
      len += (size_t)snprintf(set_times + len, sizeof set_times - len, "%s%.17g", k ? "," : "",
                              times[k]);
    snprintf(set_times + len, sizeof set_times - len, "]");
  }
  snprintf(set_end, sizeof set_end, "time.end=%.17g", times[ntimes - 1]);
  const size_t n_user = n_set;
  sets[n_set++] = "output.energy=true";
  sets[n_set++] = "output.snapshots=false";
  sets[n_set++] = set_times;
  sets[n_set++] = set_end;
  sets[n_set++] = "time.stop=none";
  sets[n_set++] = set_dx;
  for (int r = 0; r < ncounts; r++) {
    long got;
    const double dx = dx_for(&base, (long)counts[r], &got);
    snprintf(set_dx, sizeof set_dx, "numerics.dx=%.17g", dx);
    sph_case c;
    if (sph_case_load(case_path, sets, n_set, &c, &err)) {
      fprintf(stderr, "sph audit: %s\n", err.msg);
      sph_case_free(&base);
      goto done;
    }
    char dir[4096], name[64];
    snprintf(name, sizeof name, "n%ld", got);
    if (path_join(dir, sizeof dir, outdir, name)) {
      fprintf(stderr, "sph audit: output path too long\n");
      sph_case_free(&c);
      sph_case_free(&base);
      goto done;
    }
    sph_sim *s = NULL;
    const int no_dir = sph_cli_make_dirs(dir) != 0;
    if (no_dir) sph_error_set(&err, "cannot create %s: %s", dir, strerror(errno));
    if (no_dir || sph_sim_create(&c, &s, &err)) {
      fprintf(stderr, "sph audit: %s\n", err.msg);
      sph_case_free(&c);
      sph_case_free(&base);
      goto done;
    }
    sph_progress bar;
    sph_progress_init(&bar, stderr, c.t_end, quiet);
    sph_run_options opt = {dir, on_progress, &bar, NULL};
    sph_run_result res;
    const double w0 = sph_wall_seconds();
    int rc = sph_run(s, &opt, &res, &err);
    rows[r].wall = sph_wall_seconds() - w0;
    sph_progress_done(&bar);
    rows[r].particles = got;
    rows[r].dx = dx;
    const double gmag = hypot(c.gravity[0], c.gravity[1]);
    if (rc || read_diag(dir, times, ntimes, gmag > 0.0 ? gmag : 1.0, &rows[r])) {
      fprintf(stderr, "sph audit: run %d (%ld particles): %s\n", r + 1, got,
              rc ? err.msg : "diagnostics lack the audit times");
      sph_sim_free(s);
      sph_case_free(&c);
      sph_case_free(&base);
      status = res.status == SPH_RUN_BLOWUP ? 3 : 1;
      goto done;
    }
    if (!quiet)
      fprintf(stderr,
              "audit: run %d/%d: %ld fluid particles (asked %ld), dx = %.6g m, %ld steps, "
              "%.1f s wall; deviation at t = %g s: %+.4f %% (fluid's own: %+.4f %%)\n",
              r + 1, ncounts, got, (long)counts[r], dx, rows[r].steps, rows[r].wall,
              times[ntimes - 1], 100 * rows[r].dev[ntimes - 1], 100 * rows[r].fdev[ntimes - 1]);
    sph_sim_free(s);
    sph_case_free(&c);
  }
  (void)n_user;

  printf("Energy deviation (E - E0)/E0, closed balance (kinetic + potential + internal\n"
         "- moving-wall work - XSPH drift), case %s:\n", base.name);
  print_table(stdout, 0, rows, ncounts, times, ntimes, 0);
  printf("\nThe fluid's own kinetic + potential + internal energy against its start\n"
         "(the quantity of paper A, Table 4):\n");
  print_table(stdout, 0, rows, ncounts, times, ntimes, 1);
  printf("\nMass drift at t = %g s:", times[ntimes - 1]);
  for (int r = 0; r < ncounts; r++) printf(" %ld: %.3g", rows[r].particles, rows[r].mass_drift);
  printf("\nMomentum drift |P - P0 - impulse of walls and gravity| / (M |g| t) at t = %g s:",
         times[ntimes - 1]);
  for (int r = 0; r < ncounts; r++)
    printf(" %ld: %.3g", rows[r].particles, rows[r].momentum_drift);
  printf("\n");

  char path[4096];
  FILE *f = path_join(path, sizeof path, outdir, "audit.csv") ? NULL : fopen(path, "w");
  if (f) {
    fprintf(f, "particles,dx,time,energy_deviation,fluid_energy_deviation,mass_drift,"
               "momentum_drift\n");
    for (int r = 0; r < ncounts; r++)
      for (int k = 0; k < ntimes; k++)
        fprintf(f, "%ld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", rows[r].particles, rows[r].dx,
                times[k], rows[r].dev[k], rows[r].fdev[k], rows[r].mass_drift,
                rows[r].momentum_drift);
    fclose(f);
  }
  FILE *m = path_join(path, sizeof path, outdir, "audit.md") ? NULL : fopen(path, "w");
  if (m) {
    fprintf(m, "Energy audit of case `%s`.\n\nClosed balance, (E - E0)/E0:\n\n", base.name);
    print_table(m, 1, rows, ncounts, times, ntimes, 0);
    fprintf(m, "\nThe fluid's own kinetic + potential + internal energy (paper A, Table 4):\n\n");
    print_table(m, 1, rows, ncounts, times, ntimes, 1);
    fprintf(m, "\n| particles | mass drift | momentum drift (t = %g s) |\n|---|---|---|\n",
            times[ntimes - 1]);
    for (int r = 0; r < ncounts; r++)
      fprintf(m, "| %ld | %.3g | %.3g |\n", rows[r].particles, rows[r].mass_drift,
              rows[r].momentum_drift);
    fclose(m);
  }
  if (!f || !m) {
    fprintf(stderr, "sph audit: cannot write %s/audit.{csv,md}\n", outdir);
    sph_case_free(&base);
    goto done;
  }
  sph_case_free(&base);
  status = 0;
done:
  free(sets);
  return status;
}
