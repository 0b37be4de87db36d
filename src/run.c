/*
 * run.c - the run loop and its outputs (see run.h).
 *
 * Files are only ever replaced atomically (snapshots and the XDMF index by
 * the snapshot module; diagnostics.csv is appended row by row and flushed,
 * so an interrupted run keeps every complete row).
 */
#include "config.h"

#include "run.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "snapshot.h"

typedef struct outputs {
  const char *dir;
  FILE *diag;
  FILE *gauges;      /* gauges.csv, when the case has wave gauges */
  double *still;     /* each gauge's level at t = 0 */
  size_t n, cap;
  char **names;
  double *times;
} outputs;

static void outputs_free(outputs *o) {
  if (o->diag) fclose(o->diag);
  if (o->gauges) fclose(o->gauges);
  free(o->still);
  for (size_t i = 0; i < o->n; i++) free(o->names[i]);
  free(o->names);
  free(o->times);
}

/* One row of gauges.csv: time, then each gauge's elevation above its level
 * at t = 0 (the highest fluid particle within dx of the gauge, diag.h). */
static int write_gauges(sph_sim *s, outputs *o, sph_error *err) {
  const sph_case *c = sph_sim_case(s);
  const sph_particles *p = sph_sim_particles(s);
  if (!o->gauges) return 0;
  if (fprintf(o->gauges, "%.17g", sph_sim_time(s)) < 0) goto fail;
  for (size_t g = 0; g < c->n_gauges; g++) {
    const double level = sph_diag_surface_at(p, c->gauges[g], c->dx, c->dx);
    if (sph_sim_time(s) == 0.0) o->still[g] = level;
    if (fprintf(o->gauges, ",%.17g", level - o->still[g]) < 0) goto fail;
  }
  if (fputc('\n', o->gauges) == EOF || fflush(o->gauges)) goto fail;
  return 0;
fail:
  return sph_error_set(err, "%s/gauges.csv: write failed: %s", o->dir, strerror(errno));
}

static int write_output(sph_sim *s, outputs *o, sph_run_result *r, sph_error *err) {
  sph_diag_row row;
  sph_sim_diag(s, &row);
  r->outputs++;
  if (!o->dir) return 0;
  if (sph_diag_write_row(o->diag, &row) || fflush(o->diag))
    return sph_error_set(err, "%s/diagnostics.csv: write failed: %s", o->dir, strerror(errno));
  if (write_gauges(s, o, err)) return -1;
  if (!sph_sim_case(s)->snapshots) return 0;
  if (o->n == o->cap) {
    size_t cap = o->cap ? 2 * o->cap : 64;
    char **nn = realloc(o->names, cap * sizeof *nn);
    if (nn) o->names = nn;
    double *nt = realloc(o->times, cap * sizeof *nt);
    if (nt) o->times = nt;
    if (!nn || !nt) return sph_error_set(err, "out of memory");
    o->cap = cap;
  }
  char name[64], path[4096];
  snprintf(name, sizeof name, "snap_%04zu.h5", o->n);
  snprintf(path, sizeof path, "%s/%s", o->dir, name);
  if (sph_sim_write_snapshot(s, path, err)) return -1;
  o->names[o->n] = strdup(name);
  if (!o->names[o->n]) return sph_error_set(err, "out of memory");
  o->times[o->n] = sph_sim_time(s);
  o->n++;
  snprintf(r->last_snapshot, sizeof r->last_snapshot, "%s", path);
  snprintf(path, sizeof path, "%s/snapshots.xmf", o->dir);
  return sph_xdmf_write(path, o->n, (const char *const *)o->names, o->times,
                        sph_sim_particles(s)->n, sph_case_needs_free_surface(sph_sim_case(s)),
                        err);
}

static int stop_condition(sph_sim *s) {
  const sph_case *c = sph_sim_case(s);
  if (c->stop == SPH_STOP_FRONT_AT_WALL) {
    const double front = sph_diag_front(sph_sim_particles(s), sph_sim_floor(s), 2.0 * c->dx);
    return front >= c->tank.x1 - c->dx;
  }
  return 0;
}

int sph_run(sph_sim *s, const sph_run_options *o, sph_run_result *r, sph_error *err) {
  const sph_case *c = sph_sim_case(s);
  outputs out = {0};
  memset(r, 0, sizeof *r);
  out.dir = o->outdir;
  int rc = 0;
  if (out.dir) {
    char path[4096];
    snprintf(path, sizeof path, "%s/diagnostics.csv", out.dir);
    out.diag = fopen(path, "w");
    if (!out.diag) {
      sph_error_set(err, "%s: cannot create: %s", path, strerror(errno));
      r->status = SPH_RUN_ERROR;
      return -1;
    }
    if (c->n_gauges) {
      snprintf(path, sizeof path, "%s/gauges.csv", out.dir);
      out.gauges = fopen(path, "w");
      out.still = calloc(c->n_gauges, sizeof *out.still);
      int bad = !out.gauges || !out.still || fprintf(out.gauges, "time") < 0;
      for (size_t g = 0; !bad && g < c->n_gauges; g++)
        bad = fprintf(out.gauges, ",eta_%.6g", c->gauges[g]) < 0;
      if (bad || fputc('\n', out.gauges) == EOF) {
        sph_error_set(err, "%s: cannot create: %s", path, strerror(errno));
        r->status = SPH_RUN_ERROR;
        outputs_free(&out);
        return -1;
      }
    }
    if (sph_diag_write_header(out.diag, sph_case_needs_free_surface(c), c->energy)) {
      sph_error_set(err, "%s: write failed", path);
      r->status = SPH_RUN_ERROR;
      outputs_free(&out);
      return -1;
    }
  }
  if (o->progress) o->progress(o->progress_ctx, s);
  if (write_output(s, &out, r, err)) goto io_error;
  long k = 1;    /* next multiple of output_interval */
  size_t j = 0;  /* next of time.output_times */
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
    int st = sph_sim_step(s, next, err);
    if (o->progress) o->progress(o->progress_ctx, s);
    if (st == SPH_BLOWUP) {
      r->status = SPH_RUN_BLOWUP;
      rc = -1;
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
    const int at_output = sph_sim_time(s) == next;
    if (at_output) {
      if (c->output_interval > 0.0 && next == (double)k * c->output_interval) k++;
      if (j < c->n_output_times && next == c->output_times[j]) j++;
      if (write_output(s, &out, r, err)) goto io_error;
    }
    if (stop_condition(s)) {
      if (!at_output && write_output(s, &out, r, err)) goto io_error;
      r->status = SPH_RUN_STOPPED;
      break;
    }
    if (o->interrupt && *o->interrupt) {
      if (!at_output && write_output(s, &out, r, err)) goto io_error;
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
