/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * run.c - the run loop and its outputs (see run.h).
 *
 * Files are only ever replaced atomically (snapshots and the XDMF index by
 * the snapshot module; diagnostics.csv is appended row by row and flushed,
 * so an interrupted run keeps every complete row).
 *
 * Every snapshot carries the restart record (sim.h): besides the sim's own
 * state, its number k and the gauges' levels at t = 0. A resumed run
 * (sph_run_resume) writes snap_{k+1} onwards; it keeps the rows of an
 * existing diagnostics.csv / gauges.csv (same header) up to the restart
 * time, drops the later ones (a run that went on past the snapshot) and
 * appends, so a run interrupted and resumed in its own directory ends with
 * the files of the uninterrupted run; in a fresh directory the files start
 * with the row of the restart time. The XDMF index lists the earlier
 * snapshots still present in the directory.
 */
#include "config.h"

#include "solver/run.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/probe_terms.h"
#include "analysis/probes.h"
#include "core/parallel.h"
#include "io/csv.h"
#include "io/snapshot.h"
#include "solver/diag_sums.h"
#include "solver/procs.h"
#include "solver/sim_internal.h"

typedef struct outputs {
  const char *dir;
  void (*row)(void *ctx, const sph_diag_row *r); /* sph_run_options.row */
  void *row_ctx;
  FILE *diag;
  FILE *gauges;  /* gauges.csv, when the case has wave gauges */
  double *still; /* each gauge's level at t = 0 */
  FILE *probes;  /* probes.csv, when the case has probes */
  long probe_k;  /* the next probe row is due at probe_k * probe_interval */
  double *lp;    /* per probe: its low-pass output at the last row (probes.h) */
  double lp_t;   /* the time of the last probe row */
  int lp_rows;   /* probe rows the filters have seen */
  double *share; /* a row's readings (read_probes) */
  int read;      /* some process writes probes.csv: every one reads its share of a row */
  int rows;      /* some process writes diagnostics rows: every one sums its share of a row */
  int levels;    /* some process writes gauges.csv: every one reads its share of a row */
  double *tops;  /* the gauges' readings of every process's share (sph_diag_gauge_top) */
  sph_probe_term *terms, *every; /* a row's probe terms of this process's share, of all */
  size_t n_terms, cap_terms;
  size_t slot;            /* the terms of a process's record (read_probes_shared) */
  unsigned char *records; /* every process's record of a row, then this process's */
  int64_t *term_counts;   /* each probe's count of terms, and whether it failed: this process's,
                             then every process's */
  int team;               /* the processes write each snapshot together (snapshot.h), the first's
                             name and restart record */
  size_t index;           /* number of the next snapshot file, snap_<index>.h5 */
  size_t n, cap;          /* snapshots listed in the XDMF index */
  char **names;
  double *times;
  size_t *counts; /* each one's particles (fluid that leaves the domain may be taken out) */
} outputs;

static void outputs_free(outputs *o) {
  if (o->diag) fclose(o->diag);
  if (o->gauges) fclose(o->gauges);
  if (o->probes) fclose(o->probes);
  free(o->still);
  free(o->lp);
  free(o->share);
  free(o->tops);
  free(o->terms);
  free(o->every);
  free(o->records);
  free(o->term_counts);
  for (size_t i = 0; i < o->n; i++)
    free(o->names[i]);
  free(o->names);
  free(o->times);
  free(o->counts);
}

/* One row of gauges.csv: time, then each gauge's elevation above its level
 * at t = 0. The level is the top of the highest fluid particle within dx
 * of the gauge (diag.h; in 3-D within dx along x and along y), or the case's floor (sph_sim_floor)
 * where no water is: a gauge over a dry bed reads 0 until the water arrives, then the depth, and
 * every value is finite. */
static int write_gauges(sph_sim *s, outputs *o, sph_error *err) {
  const sph_case *c = sph_sim_case(s);
  const sph_particles *p = sph_sim_particles(s);
  if (!o->levels) return 0;
  /* each gauge's highest fluid centre in this process's share of the store (sim_internal.h),
   * then (under mpirun) the largest of every process's, in one collective step */
  const size_t ng = c->n_gauges;
  const int procs = sph_procs_count();
  double *mine = o->tops + (size_t)procs * ng;
  size_t from, to;
  sph_sim_span(s, &from, &to);
  for (size_t g = 0; g < ng; g++)
    mine[g] = sph_diag_gauge_top(p, from, to, &c->gauges[(SPH_DIM - 1) * g], c->dx,
                                 c->periodic ? c->periodic_axis : -1, c->periodic_range);
  sph_procs_gather(mine, ng * sizeof *mine, o->tops); /* (one process: a copy) */
  if (!o->gauges) return 0;
  if (fprintf(o->gauges, "%.17g", sph_sim_time(s)) < 0) goto fail;
  for (size_t g = 0; g < ng; g++) {
    double top = -INFINITY;
    for (int q = 0; q < procs; q++)
      top = fmax(top, o->tops[(size_t)q * ng + g]);
    double level = top + 0.5 * c->dx;
    if (!isfinite(level)) level = sph_sim_floor(s); /* dry */
    if (sph_sim_time(s) == 0.0) o->still[g] = level;
    if (fprintf(o->gauges, ",%.17g", level - o->still[g]) < 0) goto fail;
  }
  if (fputc('\n', o->gauges) == EOF || fflush(o->gauges)) goto fail;
  return 0;
fail:
  return sph_error_set(err, "%s/gauges.csv: write failed: %s", o->dir, strerror(errno));
}

/* Whether some probe of c has a low-pass filter. */
static int has_low_pass(const sph_case *c) {
  for (size_t k = 0; k < c->n_probes; k++)
    if (sph_probe_filtered(&c->probes[k])) return 1;
  return 0;
}

/* The low-pass filters of the probes that have one, past a row of time t
 * with the probes' raw readings raw[k] (probes.h). Their state goes into
 * every snapshot's restart record after the row of its time, so a resumed
 * run continues them with the same bits (a row written again at that time
 * has dt = 0 and changes nothing). */
static void low_pass_row(outputs *o, const sph_case *c, double t, const double *raw) {
  for (size_t k = 0; k < c->n_probes; k++) {
    const sph_probe *q = &c->probes[k];
    if (!sph_probe_filtered(q)) continue;
    o->lp[k] = o->lp_rows ? sph_probe_low_pass(o->lp[k], raw[k], t - o->lp_t, q->low_pass) : raw[k];
  }
  o->lp_t = t;
  o->lp_rows++;
}

/* The probe terms a process's record carries at first (read_probes_shared). */
#define SPH_PROBE_SLOT 1024

/* Room for the shared probe rows of `procs` processes: 0, or -1. */
static int probe_records(outputs *o, const sph_case *c, int procs) {
  const size_t np = c->n_probes, head = (np + 1) * sizeof(int64_t);
  /* SPH_TEST_PROBE_SLOT=N (doc/testing.md): N terms at first, for the test of a longer list */
  const char *e = getenv("SPH_TEST_PROBE_SLOT");
  o->slot = e && atol(e) > 0 ? (size_t)atol(e) : SPH_PROBE_SLOT;
  o->term_counts = calloc((np + 1) * (1 + (size_t)procs), sizeof *o->term_counts);
  o->records = malloc((size_t)(procs + 1) * (head + o->slot * sizeof(sph_probe_term)));
  o->every = malloc((size_t)procs * o->slot * sizeof(sph_probe_term));
  return o->term_counts && o->records && o->every ? 0 : -1;
}

/* A row's readings under mpirun, every process making this call at once:
 * each lists the terms of every probe over its share of the store
 * (probe_terms.h), and the lists of all are shared, from which each
 * probe's reading is folded in storage order: the bits of one process
 * reading the whole store. One collective step: each process sends a
 * record of a fixed size, its count of each probe's terms, whether it
 * failed, and its first o->slot terms (the same slot on every process);
 * where a list was longer, the rest follows in one more step and the slot
 * grows (the same on all: from the counts every process has). The readings
 * into `mine` (SPH_DIM a probe); 0, or -1 with err on every process. */
static int read_probes_shared(sph_sim *s, outputs *o, double *mine, sph_error *err) {
  const sph_case *c = sph_sim_case(s);
  const sph_particles *p = sph_sim_particles(s);
  const size_t np = c->n_probes, head = (np + 1) * sizeof(int64_t), tz = sizeof(sph_probe_term);
  const int procs = sph_procs_count(), me = sph_procs_rank();
  size_t from, to;
  sph_sim_span(s, &from, &to);
  int64_t *cnt = o->term_counts; /* (np + 1) a process: this one's, then each one's */
  o->n_terms = 0;
  int failed = 0;
  for (size_t k = 0; k < np; k++) {
    const size_t before = o->n_terms;
    if (!failed && sph_probe_terms(&c->probes[k], p, from, to, c->kernel, c->h, c->dx, c->gravity,
                                   &o->terms, &o->n_terms, &o->cap_terms))
      failed = 1;
    cnt[k] = (int64_t)(o->n_terms - before);
  }
  cnt[np] = failed;
  const size_t slot = o->slot, rec = head + slot * tz;
  unsigned char *my = o->records + (size_t)procs * rec;
  memcpy(my, cnt, head);
  memcpy(my + head, o->terms, (o->n_terms < slot ? o->n_terms : slot) * tz);
  sph_procs_gather(my, rec, o->records);
  size_t counts[SPH_PROCS_MAX], over[SPH_PROCS_MAX], most = 0, extra = 0, total = 0;
  int first = -1;
  for (int q = 0; q < procs; q++) {
    int64_t *cq = cnt + (size_t)(1 + q) * (np + 1);
    memcpy(cq, o->records + (size_t)q * rec, head);
    if (cq[np] && first < 0) first = q;
    counts[q] = 0;
    for (size_t k = 0; k < np; k++)
      counts[q] += (size_t)cq[k];
    over[q] = counts[q] > slot ? counts[q] - slot : 0;
    extra += over[q], total += counts[q];
    if (counts[q] > most) most = counts[q];
  }
  if (first >= 0) {
    if (first == me) sph_error_set(err, "out of memory for the probes' terms");
    return sph_procs_failed(first, err);
  }
  /* (o->every holds procs slots: room for every list when none is longer) */
  unsigned char *rest = NULL; /* the terms past the slot, then this process's own again */
  if (extra) {
    /* the slot grows for the rows to come, the same on every process */
    const size_t grown = 2 * most, every = total > procs * grown ? total : procs * grown;
    int room = !sph_procs_records_fit(over, tz);
    unsigned char *r = room ? NULL : realloc(o->records, (size_t)(procs + 1) * (head + grown * tz));
    if (r) o->records = r;
    sph_probe_term *e = r ? realloc(o->every, every * tz) : NULL;
    if (e) o->every = e;
    rest = e ? malloc((extra + over[me]) * tz) : NULL;
    if (!rest) room = -1;
    if (sph_procs_agree(room ? sph_error_set(err, "out of memory for the probes' terms") : 0,
                        err)) {
      free(rest);
      return -1;
    }
    o->slot = grown;
    if (over[me]) memcpy(rest + extra * tz, o->terms + slot, over[me] * tz);
    sph_procs_gather_records(rest + extra * tz, over, tz, rest);
  }
  size_t off = 0, roff = 0;
  const sph_probe_term *at[SPH_PROCS_MAX];
  for (int q = 0; q < procs; q++) {
    const size_t in_slot = counts[q] - over[q];
    memcpy(o->every + off, o->records + (size_t)q * rec + head, in_slot * tz);
    if (over[q]) memcpy(o->every + off + in_slot, rest + roff * tz, over[q] * tz);
    at[q] = o->every + off;
    off += counts[q], roff += over[q];
  }
  free(rest);
  for (size_t k = 0; k < np; k++) {
    size_t ck[SPH_PROCS_MAX];
    for (int q = 0; q < procs; q++)
      ck[q] = (size_t)cnt[(size_t)(1 + q) * (np + 1) + k];
    sph_probe_fold(&c->probes[k], at, ck, procs, c->h, c->dx, sph_sim_floor(s), mine + k * SPH_DIM);
    for (int q = 0; q < procs; q++)
      at[q] += ck[q];
  }
  return 0;
}

/* A row's readings: raw (a velocity's vx), then a velocity's vy (, vz), n
 * probes each (raw may be NULL: a process that does not write). Each probe
 * reads serially (probes.h): one probe to a thread, the same bits for any
 * team. Shared (every process reading the row at once), with more than one
 * process: read_probes_shared. 0, or -1 with err (on every process when
 * shared). */
static int read_probes(sph_sim *s, outputs *o, int shared, double *raw, double *vy, double *vz,
                       sph_error *err) {
  const sph_case *c = sph_sim_case(s);
  const sph_particles *p = sph_sim_particles(s);
  const long np = (long)c->n_probes;
  double *mine = o->share;
  if (shared && sph_procs_count() > 1) {
    if (read_probes_shared(s, o, mine, err)) return -1;
  } else {
#pragma omp parallel for schedule(dynamic, 1) if (np > 1 && (long)p->n > SPH_OMP_MIN)
    for (long k = 0; k < np; k++) {
      for (int d = 0; d < SPH_DIM; d++)
        mine[k * SPH_DIM + d] = 0.0;
      sph_probe_read(&c->probes[k], p, c->kernel, c->h, c->dx, sph_sim_floor(s), c->gravity,
                     mine + k * SPH_DIM);
    }
  }
  if (!raw) return 0;
  for (long k = 0; k < np; k++) {
    const double *v = mine + k * SPH_DIM;
    raw[k] = v[0];
    vy[k] = v[1];
    if (vz) vz[k] = v[SPH_DIM - 1];
  }
  return 0;
}

/* One row of probes.csv: time, then each probe's reading (probes.h), a
 * pressure probe's low-pass output after its raw reading. */
static int write_probes(sph_sim *s, outputs *o, int shared, sph_error *err) {
  const sph_case *c = sph_sim_case(s);
  const double t = sph_sim_time(s);
  /* this row's readings: raw (a velocity's vx), then a velocity's vy (, vz) */
  double *raw = o->lp + c->n_probes, *vy = raw + c->n_probes;
  SPH_IF3(double *vz = vy + c->n_probes;)
  if (read_probes(s, o, shared, raw, vy, SPH_DIM == 3 ? vy + c->n_probes : NULL, err)) return -1;
  low_pass_row(o, c, t, raw);
  if (fprintf(o->probes, "%.17g", t) < 0) goto fail;
  for (size_t k = 0; k < c->n_probes; k++) {
    const int vel = c->probes[k].kind == SPH_PROBE_VELOCITY;
    const double v[SPH_DIM] = {SPH_XYZ(raw[k], vel ? vy[k] : o->lp[k], vz[k])};
    for (int m = 0; m < sph_probe_columns(&c->probes[k]); m++)
      if (fprintf(o->probes, ",%.17g", v[m]) < 0) goto fail;
  }
  if (fputc('\n', o->probes) == EOF || fflush(o->probes)) goto fail;
  return 0;
fail:
  return sph_error_set(err, "%s/probes.csv: write failed: %s", o->dir, strerror(errno));
}

/* The smallest k >= 1 with k * interval > t (interval > 0, t >= 0 finite,
 * as the restart checks): found from t / interval and corrected by a step
 * or two, the same k the count from 1 up gives, without counting to a time
 * far past the first multiples (a restart late in a run; issue 39, D3).
 * The output times and the probe rows both take their next index here. */
static long first_multiple_after(double interval, double t) {
  const double q = floor(t / interval);
  long k = q < 1.0 ? 1 : q < 1e15 ? (long)q : (long)1e15;
  while (k > 1 && (double)(k - 1) * interval > t)
    k--;
  while ((double)k * interval <= t)
    k++;
  return k;
}

/* After a step: the probes' row when one is due (every step with interval
 * 0, else at the step that ends on k * interval, where the run lands one;
 * k counted in integers so that no row is merged or skipped), then the
 * next k. Shared: every process makes this call at this step (the run's
 * loop; a resumed run's missing row is the writer's alone). */
static int probe_step(sph_sim *s, outputs *o, int shared, sph_error *err) {
  const sph_case *c = sph_sim_case(s);
  const double iv = c->probe_interval, t = sph_sim_time(s);
  if (!c->n_probes || (iv > 0.0 && t < (double)o->probe_k * iv)) return 0;
  if (o->probes) {
    if (write_probes(s, o, shared, err)) return -1;
  } else if (shared && o->read && sph_procs_count() > 1) { /* its share (read_probes) */
    if (read_probes(s, o, 1, NULL, NULL, NULL, err)) return -1;
  }
  if (iv > 0.0) o->probe_k = first_multiple_after(iv, t);
  return 0;
}

/* Adds a snapshot to the XDMF list. */
static int list_snapshot(outputs *o, const char *name, double t, size_t count, sph_error *err) {
  if (o->n == o->cap) {
    size_t cap = o->cap ? 2 * o->cap : 64;
    char **nn = realloc(o->names, cap * sizeof *nn);
    if (nn) o->names = nn;
    double *nt = realloc(o->times, cap * sizeof *nt);
    if (nt) o->times = nt;
    size_t *nc = realloc(o->counts, cap * sizeof *nc);
    if (nc) o->counts = nc;
    if (!nn || !nt || !nc) return sph_error_set(err, "out of memory");
    o->cap = cap;
  }
  if (!(o->names[o->n] = strdup(name))) return sph_error_set(err, "out of memory");
  o->counts[o->n] = count;
  o->times[o->n++] = t;
  return 0;
}

/* The diagnostics row of the current state (which & 1) and its gauges
 * row (which & 2); under mpirun every process makes this call at once
 * (each sums its share of the rows) and the first writes them. */
static int write_rows(sph_sim *s, outputs *o, int which, sph_error *err) {
  int rc = 0;
  sph_sim_catch_up(s); /* (the diagnostics and the snapshot read every process's walls) */
  if ((which & 1) && o->rows) {
    sph_diag_row row;
    sph_sim_diag(s, &row);
    if (o->row) o->row(o->row_ctx, &row);
    if (o->diag && (sph_diag_write_row(o->diag, &row) || fflush(o->diag)))
      rc = sph_error_set(err, "%s/diagnostics.csv: write failed: %s", o->dir, strerror(errno));
  }
  /* (the gauges' collective step is made after a failed write too: the others make it) */
  sph_error later;
  if ((which & 2) && write_gauges(s, o, rc ? &later : err)) rc = -1;
  if (rc) return -1;
  return (which & 4) && o->read ? probe_step(s, o, 1, err) : 0;
}

/* Writes the rows of an output and its snapshot. With a team (every
 * process of the run) a collective step: the first process's name for
 * the file and its restart record's gauge levels and probe filters go to
 * the others, and all write the file. */
static int write_output(sph_sim *s, outputs *o, sph_run_result *r, sph_error *err) {
  r->outputs++;
  if (write_rows(s, o, 3, err)) return -1;
  if (!o->dir && !o->team) return 0;
  if (!sph_sim_case(s)->snapshots) return 0;
  char name[64], path[4096] = ""; /* (all of it sent to a team) */
  snprintf(name, sizeof name, "snap_%04zu.h5", o->index);
  if (o->dir) snprintf(path, sizeof path, "%s/%s", o->dir, name);
  /* the probes' filters: outputs, then the last row's time and whether there was one */
  const sph_case *c = sph_sim_case(s);
  const size_t nf = has_low_pass(c) ? c->n_probes + 2 : 0;
  if (nf && o->dir) {
    o->lp[c->n_probes] = o->lp_t;
    o->lp[c->n_probes + 1] = o->lp_rows ? 1.0 : 0.0;
  }
  if (o->team) {
    int64_t index = (int64_t)o->index;
    sph_procs_share(&index, sizeof index);
    sph_procs_share(path, sizeof path);
    if (c->n_gauges) sph_procs_share(o->still, c->n_gauges * sizeof *o->still);
    if (nf) sph_procs_share(o->lp, nf * sizeof *o->lp);
    o->index = (size_t)index;
  }
  if (sph_sim_write_run_snapshot(s, path, (int64_t)o->index, o->still, c->n_gauges, o->lp, nf, err))
    return -1;
  o->index++;
  if (!o->dir) return 0; /* a team's other process: the list is the first's */
  if (list_snapshot(o, name, sph_sim_time(s), sph_sim_particles(s)->n, err)) return -1;
  snprintf(r->last_snapshot, sizeof r->last_snapshot, "%s", path);
  snprintf(path, sizeof path, "%s/snapshots.xmf", o->dir);
  return sph_xdmf_write(path, o->n, (const char *const *)o->names, o->times, o->counts,
                        (sph_case_needs_free_surface(sph_sim_case(s)) ? SPH_XDMF_FREE_SURFACE : 0) |
                            (sph_sim_case(s)->air ? SPH_XDMF_PHASE : 0),
                        err);
}

/* The stop condition (time.stop: front_at_wall) over particles [from,
 * to): 1 with the surge front there (sph_diag_front_span, within 2 dx of
 * the floor) in *now and its mark, dx short of the tank's far wall, in
 * *stop; 0 where the case has no such condition. */
static int stop_front(const sph_sim *s, size_t from, size_t to, double *now, double *stop) {
  const sph_case *c = sph_sim_case(s);
  if (c->stop != SPH_STOP_FRONT_AT_WALL) return 0;
  sph_sim *m = (sph_sim *)s; /* read only: the store is not changed */
  *now = sph_diag_front_span(sph_sim_particles(m), from, to, sph_sim_floor(s), 2.0 * c->dx);
  *stop = c->tank.x1 - c->dx;
  return 1;
}

int sph_run_stop_measure(const sph_sim *s, double *now, double *stop) {
  return stop_front(s, 0, sph_sim_particles((sph_sim *)s)->n, now, stop);
}

/* Whether the stop condition holds in this process's share of the store
 * (sim_internal.h): the front past its mark there; under mpirun the
 * processes' answers are agreed, the front's maximum being past the mark
 * where any share's is (the answer of sph_run_stop_measure's whole store). */
static int stop_here(sph_sim *s) {
  size_t from, to;
  double now, stop;
  sph_sim_span(s, &from, &to);
  return stop_front(s, from, to, &now, &stop) && now >= stop;
}

/* Whether two header lines name the same columns, the units after the
 * names aside: a run written before the headers gave units ("time,step")
 * resumes into today's ("time (s),step"). */
static int same_columns(const char *a, const char *b) {
  for (;;) {
    const size_t la = strcspn(a, ",\n"), lb = strcspn(b, ",\n");
    const size_t n = sph_csv_bare_length(a, la);
    if (n != sph_csv_bare_length(b, lb) || memcmp(a, b, n) != 0 || a[la] != b[lb]) return 0;
    if (a[la] != ',') return 1; /* both lines end here */
    a += la + 1;
    b += lb + 1;
  }
}

/* A line's CR before its LF (a file saved with CRLF line ends) is
 * dropped: the rows are kept with LF ends. */
static void drop_cr(char *line, ssize_t *len) {
  if (*len >= 2 && line[*len - 1] == '\n' && line[*len - 2] == '\r') {
    line[*len - 2] = '\n';
    line[*len - 1] = '\0';
    (*len)--;
  }
}

/* Reads a resumed run's CSV file `old` (its header first) and copies its
 * rows of time <= t_keep to out (NULL: read only); CRLF line ends are read
 * as LF, a torn last row (no line end, as a killed run leaves it) is
 * dropped. A file this run cannot read (other columns than header, a row
 * whose time is not a number) is refused: -1 with err naming path and the
 * line, and its rows are never dropped unread (issue 61, E6). 1 if out
 * failed, else 0; *kept_last tells whether a row of time t_keep was kept. */
static int scan_csv(FILE *old, const char *path, const char *header, double t_keep, FILE *out,
                    int *kept_last, sph_error *err) {
  char *line = NULL;
  size_t cap = 0;
  long row = 1;
  int rc = 0;
  *kept_last = 0;
  ssize_t len = getline(&line, &cap, old);
  if (len > 0) drop_cr(line, &len);
  if (len > 0 && !same_columns(line, header)) {
    const size_t shown = strcspn(line, "\n");
    rc = sph_error_set(err,
                       "%s: its header is not the columns this case writes (line 1: '%.*s%s'); "
                       "a restart in place keeps a file's rows and would drop these: left as it "
                       "is (restart into another directory with -o, or move the file away)",
                       path, shown > 80 ? 80 : (int)shown, line, shown > 80 ? "..." : "");
  }
  while (len > 0 && rc == 0 && (len = getline(&line, &cap, old)) > 0) {
    row++;
    if (line[len - 1] != '\n') break; /* a torn last row */
    drop_cr(line, &len);
    char *end;
    const double t = strtod(line, &end);
    if (end == line || *end != ',' || isnan(t)) {
      const size_t shown = strcspn(line, "\n");
      rc = sph_error_set(err,
                         "%s:%ld: expected a row that starts with its time, got '%.*s': the rows "
                         "after it would be dropped unread; left as it is (mend the row, or "
                         "restart into another directory with -o)",
                         path, row, shown > 40 ? 40 : (int)shown, line);
      break;
    }
    if (!(t <= t_keep)) break;
    *kept_last = t == t_keep;
    if (out && fputs(line, out) == EOF) rc = 1;
  }
  free(line);
  return rc;
}

/* Opens a CSV file of the run for writing: a new file gets the header; on
 * a resumed run (t_keep >= 0) an existing file keeps the rows scan_csv
 * keeps (the rest is dropped: rewritten through a temporary file and
 * renamed) and is opened for appending; one scan_csv refuses is left as it
 * is (NULL with err). */
static FILE *open_csv(const char *path, const char *header, double t_keep, int *kept_last,
                      sph_error *err) {
  *kept_last = 0;
  FILE *old = t_keep >= 0.0 ? fopen(path, "r") : NULL;
  char tmp[4200];
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  FILE *f = fopen(old ? tmp : path, "w");
  if (!f) {
    sph_error_set(err, "%s: cannot create: %s", old ? tmp : path, strerror(errno));
    if (old) fclose(old);
    return NULL;
  }
  int bad = fputs(header, f) == EOF;
  if (old) {
    const int rc = bad ? 0 : scan_csv(old, path, header, t_keep, f, kept_last, err);
    fclose(old);
    if (rc < 0) {
      fclose(f);
      remove(tmp);
      return NULL;
    }
    bad = bad || rc;
  }
  if (bad || fflush(f)) {
    sph_error_set(err, "%s: write failed: %s", old ? tmp : path, strerror(errno));
    fclose(f);
    if (old) remove(tmp);
    return NULL;
  }
  if (old) {
    fclose(f);
    if (rename(tmp, path) != 0) {
      sph_error_set(err, "%s: cannot rename %s to it: %s", path, tmp, strerror(errno));
      remove(tmp);
      return NULL;
    }
    f = fopen(path, "a");
    if (!f) sph_error_set(err, "%s: cannot open: %s", path, strerror(errno));
  }
  return f;
}

/* The header line of diagnostics.csv (what 0), gauges.csv (1) or
 * probes.csv (2), in a malloc'd string. */
static char *csv_header(const sph_case *c, int what) {
  char *buf = NULL;
  size_t len = 0;
  FILE *m = open_memstream(&buf, &len);
  if (!m) return NULL;
  int bad;
  if (what == 2) {
    bad = sph_csv_put_column(m, "time", 1) != 0;
    for (size_t k = 0; !bad && k < c->n_probes; k++) {
      char col[200];
      sph_probe_header(&c->probes[k], col, sizeof col);
      bad = fputs(col, m) == EOF;
    }
    bad = bad || fputc('\n', m) == EOF;
  } else if (what == 1) {
    bad = sph_csv_put_column(m, "time", 1) != 0;
    for (size_t g = 0; !bad && g < c->n_gauges; g++) {
      char col[64];
      sph_case_gauge_column(c, g, col, sizeof col);
      bad = sph_csv_put_column(m, col, 0) != 0;
    }
    bad = bad || fputc('\n', m) == EOF;
  } else {
    bad = sph_diag_write_header(m, sph_case_needs_free_surface(c), c->energy,
                                c->diffusion != SPH_DIFFUSION_NONE || c->riemann,
                                sph_case_has_boundary(c, SPH_BOUNDARY_REPULSIVE), c->shifting,
                                c->leaving == SPH_LEAVING_REMOVE) != 0;
  }
  if (fclose(m) || bad) {
    free(buf);
    return NULL;
  }
  return buf;
}

/* The path of the run's CSV file `what` (0 diagnostics.csv, 1 gauges.csv,
 * 2 probes.csv) in out->dir. */
static void run_csv_path(const outputs *out, int what, char *path, size_t n) {
  static const char *const names[] = {"diagnostics.csv", "gauges.csv", "probes.csv"};
  snprintf(path, n, "%s/%s", out->dir, names[what]);
}

/* Opens the run's CSV file `what` with its header (open_csv: kept rows up
 * to t_keep on a resumed run). */
static FILE *open_run_csv(const outputs *out, const sph_case *c, int what, double t_keep,
                          int *kept_last, sph_error *err) {
  char *header = csv_header(c, what), path[4096];
  if (!header) {
    sph_error_set(err, "out of memory");
    return NULL;
  }
  run_csv_path(out, what, path, sizeof path);
  FILE *f = open_csv(path, header, t_keep, kept_last, err);
  free(header);
  return f;
}

/* A resumed run's CSV files, each read (scan_csv, nothing written) before
 * any is rewritten: one that would be refused leaves all of them as they
 * were. */
static int check_run_csvs(const outputs *out, const sph_case *c, double t_keep, sph_error *err) {
  for (int what = 0; what < 3; what++) {
    if ((what == 1 && !c->n_gauges) || (what == 2 && !c->n_probes)) continue;
    char path[4096];
    run_csv_path(out, what, path, sizeof path);
    FILE *old = fopen(path, "r");
    if (!old) continue; /* none: nothing to lose */
    char *header = csv_header(c, what);
    int kept, rc = header ? scan_csv(old, path, header, t_keep, NULL, &kept, err)
                          : sph_error_set(err, "out of memory");
    free(header);
    fclose(old);
    if (rc) return -1;
  }
  return 0;
}

/* The snapshots snap_0000 .. snap_<last> still in dir, for the XDMF index
 * of a resumed run (a missing or unreadable one is left out). */
static int list_earlier(outputs *o, size_t last, sph_error *err) {
  for (size_t k = 0; k <= last; k++) {
    char name[64], path[4200];
    snprintf(name, sizeof name, "snap_%04zu.h5", k);
    snprintf(path, sizeof path, "%s/%s", o->dir, name);
    sph_snapshot *snap;
    sph_error e2;
    if (sph_snapshot_open(path, &snap, &e2)) continue;
    const double t = sph_snapshot_time(snap);
    const size_t count = sph_snapshot_count(snap);
    sph_snapshot_close(snap);
    if (list_snapshot(o, name, t, count, err)) return -1;
  }
  return 0;
}

/* Opens diagnostics.csv (and gauges.csv). *need_row: the current state's
 * row still has to be written to diagnostics.csv (bit 0) or gauges.csv
 * (bit 1): a resumed run whose files lack it. */
static int open_outputs(sph_sim *s, outputs *out, const sph_snapshot_restart_data *rd,
                        int *need_row, sph_error *err) {
  const sph_case *c = sph_sim_case(s);
  const double t_keep = rd ? sph_sim_time(s) : -1.0;
  int kept_diag = 0, kept_gauges = 1, kept_probes = 1;
  *need_row = 0;
  if (rd && check_run_csvs(out, c, t_keep, err)) return -1;
  if (!(out->diag = open_run_csv(out, c, 0, t_keep, &kept_diag, err))) return -1;
  if (c->n_gauges) {
    out->still = calloc(c->n_gauges, sizeof *out->still);
    if (!out->still) return sph_error_set(err, "out of memory");
    if (rd) {
      if (rd->n_levels != c->n_gauges)
        return sph_error_set(err,
                             "restart: the snapshot holds %zu gauge levels, the case has %zu "
                             "gauges",
                             rd->n_levels, c->n_gauges);
      memcpy(out->still, rd->levels, c->n_gauges * sizeof *out->still);
    }
    if (!(out->gauges = open_run_csv(out, c, 1, t_keep, &kept_gauges, err))) return -1;
  }
  if (c->n_probes) {
    /* the filters' outputs, then room for a row's readings (write_probes) */
    if (!(out->lp = calloc((2 + SPH_DIM) * c->n_probes, sizeof *out->lp)))
      return sph_error_set(err, "out of memory");
    if (!(out->probes = open_run_csv(out, c, 2, t_keep, &kept_probes, err))) return -1;
    if (rd && rd->n_filters == c->n_probes + 2 && has_low_pass(c)) { /* snapshot.h */
      memcpy(out->lp, rd->filters, c->n_probes * sizeof *out->lp);
      out->lp_t = rd->filters[c->n_probes];
      out->lp_rows = rd->filters[c->n_probes + 1] > 0.0;
    }
    /* the first row due: the current time's, unless a resumed run's file
     * already has it */
    const double iv = c->probe_interval, t = sph_sim_time(s);
    out->probe_k = 0;
    if (iv > 0.0) {
      out->probe_k = first_multiple_after(iv, t); /* the first past t */
      if (!(rd && kept_probes) && (double)(out->probe_k - 1) * iv == t) out->probe_k--; /* t's */
    }
  }
  if (rd) {
    /* a file that lacks the restart time's row gets it */
    *need_row = (!kept_diag ? 1 : 0) | (!kept_gauges ? 2 : 0) | (!kept_probes ? 4 : 0);
    out->index = (size_t)rd->output_index + 1;
    if (c->snapshots && list_earlier(out, (size_t)rd->output_index, err)) return -1;
  }
  return 0;
}

/* The outputs are one process's to write (procs.h): whether they were
 * written is every process's to know, so that all stop together. */
static int agreed(int rc, sph_error *err) { return sph_procs_agree(rc, err); }

int sph_run(sph_sim *s, const sph_run_options *o, sph_run_result *r, sph_error *err) {
  return sph_run_resume(s, o, NULL, r, err);
}

int sph_run_resume(sph_sim *s, const sph_run_options *o, const sph_snapshot_restart_data *rd,
                   sph_run_result *r, sph_error *err) {
  const sph_case *c = sph_sim_case(s);
  outputs out = {0};
  memset(r, 0, sizeof *r);
  s->fig_waited0 = sph_procs_waited(); /* (the run's waits: sph_sim_procs_figures) */
  out.dir = o->outdir;
  out.row = o->row;
  out.row_ctx = o->row_ctx;
  int rc = 0;
  int need_row = 0;
  if (agreed(out.dir ? open_outputs(s, &out, rd, &need_row, err) : 0, err)) {
    r->status = SPH_RUN_ERROR;
    outputs_free(&out);
    return -1;
  }
  /* room for a row's readings, on every process (read_probes), and whether
   * any process writes them (one collective step) */
  out.read = c->n_probes && sph_procs_any(out.probes != NULL);
  /* and the diagnostics' and the gauges' rows, which every process sums its share of */
  out.rows = sph_procs_any(out.diag != NULL || out.row != NULL);
  out.levels = c->n_gauges && sph_procs_any(out.gauges != NULL);
  /* the processes write the snapshots together when one writes them: the
   * others keep room for the restart record's levels and filters */
  out.team = sph_procs_count() > 1 && c->snapshots && sph_procs_any(out.dir != NULL);
  const size_t share = c->n_probes * SPH_DIM;
  int room = 0;
  if (out.team && !out.dir &&
      ((c->n_gauges && !(out.still = calloc(c->n_gauges, sizeof *out.still))) ||
       (c->n_probes && !(out.lp = calloc(c->n_probes + 2, sizeof *out.lp)))))
    room = sph_error_set(err, "out of memory for the snapshots' restart record");
  else if (share && !(out.share = calloc(share, sizeof *out.share)))
    room = sph_error_set(err, "out of memory for the probes' readings");
  else if (out.read && sph_procs_count() > 1 && probe_records(&out, c, sph_procs_count()))
    room = sph_error_set(err, "out of memory for the probes' readings");
  else if (out.levels &&
           !(out.tops = calloc(c->n_gauges * (1 + (size_t)sph_procs_count()), sizeof *out.tops)))
    room = sph_error_set(err, "out of memory for the gauges' readings");
  if (agreed(room, err)) {
    r->status = SPH_RUN_ERROR;
    outputs_free(&out);
    return -1;
  }
  /* a run without the file lands on the probes' row times too: its steps
   * are those of the run that writes them (procs.h: a process that does
   * not write follows the one that does) */
  if (!out.probes && c->n_probes && c->probe_interval > 0.0)
    out.probe_k = first_multiple_after(c->probe_interval, sph_sim_time(s));
  /* and the writer's count (rank 0's: its row at the start time itself, a resumed file's kept
   * rows), on every process, which a step that lands on a row time reads */
  if (out.read && sph_procs_count() > 1) sph_procs_share(&out.probe_k, sizeof out.probe_k);
  if (o->progress) o->progress(o->progress_ctx, s);
  if (!rd && sph_sim_check_state(s, err)) { /* the initial state is checked like any other */
    r->status = SPH_RUN_BLOWUP;
    outputs_free(&out);
    return -1;
  }
  if (!rd) {
    if (agreed(write_output(s, &out, r, err), err)) goto io_error;
    /* the probes' row agreed, and an interrupt on any process seen by all,
     * in one collective step: all stop after this step */
    int interrupted = o->interrupt && *o->interrupt;
    if (sph_procs_agree_any(probe_step(s, &out, 1, err), &interrupted, err)) goto io_error;
  } else {
    /* the rows the first process's files lack (open_outputs), made by all */
    int64_t need = need_row;
    if (sph_procs_count() > 1) sph_procs_share(&need, sizeof need);
    need_row = (int)need;
    if (agreed(need_row ? write_rows(s, &out, need_row, err) : 0, err)) goto io_error;
  }
  /* the next output times after the current time */
  /* Output times closer than `same` to each other (or to the end) are one
   * time: a listed time that is also a multiple of the interval up to
   * rounding (0.4004 against 52 * 0.0077) gives one snapshot, not a second
   * one after a step of 1e-17 s. */
  const double same = 1e-9 * c->t_end;
  long k = 1;   /* next multiple of output_interval */
  size_t j = 0; /* next of time.output_times */
  if (c->output_interval > 0.0)
    k = first_multiple_after(c->output_interval, sph_sim_time(s) + same);
  while (j < c->n_output_times && c->output_times[j] <= sph_sim_time(s) + same)
    j++;
  for (;;) {
    const double t = sph_sim_time(s);
    if (t >= c->t_end) {
      r->status = SPH_RUN_END;
      break;
    }
    double next = c->t_end;
    if (c->output_interval > 0.0 && (double)k * c->output_interval < next)
      next = (double)k * c->output_interval;
    if (j < c->n_output_times && c->output_times[j] < next) next = c->output_times[j];
    if (c->t_end - next <= same) next = c->t_end;
    /* a probe row's time is landed on too, so that probes.csv's rows fall on
     * the interval (issue 39, D11); one closer than `same` to the output is it */
    double target = next;
    if (c->n_probes && c->probe_interval > 0.0) {
      const double pt = (double)out.probe_k * c->probe_interval;
      if (pt > t && pt < next - same) target = pt;
    }
    int st = sph_sim_step(s, target, err);
    if (o->progress) o->progress(o->progress_ctx, s);
    if (st == SPH_BLOWUP) {
      r->status = SPH_RUN_BLOWUP;
      rc = -1;
      sph_sim_catch_up(s); /* (every process's at once: the step's verdict is all of theirs) */
      if (out.dir) {
        char path[4096];
        sph_error e2;
        snprintf(path, sizeof path, "%s/last_good.h5", out.dir);
        if (sph_sim_write_saved_snapshot(s, path, &e2) == 0) {
          size_t len = strlen(err->msg);
          snprintf(err->msg + len, sizeof err->msg - len, "; last good state written to %s", path);
        }
      }
      break;
    }
    if (st) goto io_error;
    /* the probes' row agreed, and an interrupt on any process and the stop
     * condition in any process's share seen by all, in one collective step:
     * all stop after this step */
    int flags[2] = {o->interrupt && *o->interrupt, stop_here(s)};
    if (sph_procs_agree_flags(probe_step(s, &out, 1, err), flags, 2, err)) goto io_error;
    const int interrupted = flags[0], stopped = flags[1];
    const int at_output = sph_sim_time(s) == next;
    if (at_output) {
      if (c->output_interval > 0.0) k = first_multiple_after(c->output_interval, next + same);
      while (j < c->n_output_times && c->output_times[j] <= next + same)
        j++;
      if (agreed(write_output(s, &out, r, err), err)) goto io_error;
    }
    if (stopped) {
      if (agreed(!at_output ? write_output(s, &out, r, err) : 0, err)) goto io_error;
      r->status = SPH_RUN_STOPPED;
      break;
    }
    if (interrupted) {
      if (agreed(!at_output ? write_output(s, &out, r, err) : 0, err)) goto io_error;
      r->status = SPH_RUN_INTERRUPTED;
      break;
    }
  }
  r->steps = sph_sim_steps(s);
  outputs_free(&out);
  return rc;
io_error:
  r->status = SPH_RUN_ERROR;
  r->steps = sph_sim_steps(s);
  outputs_free(&out);
  return -1;
}

const char *sph_run_status_name(sph_run_status st) {
  switch (st) {
  case SPH_RUN_END: return "reached the end time";
  case SPH_RUN_STOPPED: return "stop condition met";
  case SPH_RUN_INTERRUPTED: return "interrupted";
  case SPH_RUN_BLOWUP: return "blow-up";
  case SPH_RUN_ERROR: return "error";
  }
  return "?";
}
