/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * snapdata.c - loads the parts of a snapshot the renderer draws
 * (see snapdata.h), through the reader of src/io/snapshot.h only.
 *
 * Every failure leaves *s empty and names the file and the field or
 * attribute, because the user's fix is in one of those: a missing field
 * lists the fields the file does have. Values are read as doubles in id
 * order (the file's order), which is also the drawing order, so a frame
 * does not depend on how the solver stored particles in memory.
 */
#include "config.h"

#include "snapdata.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "interp.h"
#include "io/snapshot.h"

typedef struct field_info {
  const char *name, *dataset;
  int is_signed;
} field_info;

static const field_info fields[] = {
    {"speed", "speed", 0}, {"vx", "vx", 1},      {"vy", "vy", 1},
    {"vz", "vz", 1},       {"pressure", "p", 0}, {"density", "rho", 0},
};

static const field_info *info(const char *field) {
  for (size_t i = 0; i < sizeof fields / sizeof fields[0]; i++)
    if (strcmp(fields[i].name, field) == 0) return &fields[i];
  return NULL;
}

const char *rsnap_canonical(const char *field) {
  const field_info *f = info(field);
  return f ? f->dataset : field;
}

/* The dataset whose units a field has (speed: vx's). */
static const char *units_dataset(const char *field) {
  return strcmp(field, "speed") == 0 ? "vx" : rsnap_canonical(field);
}

int rsnap_units(const char *path, const char *field, char *buf, size_t size, sph_error *err) {
  sph_snapshot *ss = NULL;
  if (size) buf[0] = '\0';
  if (sph_snapshot_open_any(path, &ss, err) != 0) return -1;
  sph_snapshot_field_units(ss, units_dataset(field), buf, size);
  sph_snapshot_close(ss);
  return 0;
}

int rsnap_signed(const char *field) {
  const field_info *f = info(field);
  return f ? f->is_signed : 0;
}

/* "FILE: no field 'NAME' (fields: a, b, c)" */
static int missing_field(const sph_snapshot *ss, const char *path, const char *name,
                         const char *why, sph_error *err) {
  char list[600] = "";
  size_t used = 0, n = sph_snapshot_field_count(ss);
  for (size_t i = 0; i < n && used + 4 < sizeof list; i++) {
    int w = snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "",
                     sph_snapshot_field_name(ss, i));
    if (w < 0) break;
    used += (size_t)w;
  }
  return sph_error_set(err, "%s: no field '%s'%s (fields: %s)", path, name, why, list);
}

/* Field `name` of the snapshot's rows s keeps (s->rows; all of them when NULL) into out. */
static int read_into(const sph_snapshot *ss, const rsnap *s, const char *name, double *out,
                     const char *why, sph_error *err) {
  if (!sph_snapshot_has_field(ss, name)) return missing_field(ss, s->path, name, why, err);
  if (!s->rows) return sph_snapshot_read_field(ss, name, out, err);
  double *all = malloc((s->n_file ? s->n_file : 1) * sizeof *all);
  if (!all) return sph_error_set(err, "%s: out of memory for %zu particles", s->path, s->n_file);
  const int rc = sph_snapshot_read_field(ss, name, all, err);
  for (size_t k = 0; rc == 0 && k < s->n; k++)
    out[k] = all[s->rows[k]];
  free(all);
  return rc;
}

/* The rows of a two-phase run's snapshot (field `phase`) that the
 * renderer shows: the liquid's and the walls' (phase 0), unless the air is
 * asked for too (then, as in a one-phase file, every row: s->rows NULL). */
static int select_rows(const sph_snapshot *ss, rsnap *s, int air, sph_error *err) {
  s->n_file = s->n;
  if (air || !sph_snapshot_has_field(ss, "phase")) return 0;
  double *ph = malloc((s->n ? s->n : 1) * sizeof *ph);
  s->rows = malloc((s->n ? s->n : 1) * sizeof *s->rows);
  if (!ph || !s->rows) {
    free(ph);
    return sph_error_set(err, "%s: out of memory for %zu particles", s->path, s->n);
  }
  const int rc = sph_snapshot_read_field(ss, "phase", ph, err);
  size_t k = 0;
  for (size_t i = 0; rc == 0 && i < s->n_file; i++)
    if (ph[i] == 0.0) s->rows[k++] = i;
  free(ph);
  s->n = k;
  return rc;
}

int rsnap_peek(const char *path, double *time, double view[4], sph_error *err) {
  sph_snapshot *ss = NULL;
  if (sph_snapshot_open_any(path, &ss, err) != 0) return -1;
  *time = sph_snapshot_time(ss);
  if (view && sph_snapshot_number(ss, "view", view, 4, NULL) != 0)
    view[0] = view[1] = view[2] = view[3] = NAN;
  sph_snapshot_close(ss);
  return 0;
}

int rsnap_load(const char *path, const char *field, rsnap *s, sph_error *err) {
  return rsnap_load_phases(path, field, 0, s, err);
}

int rsnap_load_phases(const char *path, const char *field, int air, rsnap *s, sph_error *err) {
  memset(s, 0, sizeof *s);
  sph_snapshot *ss = NULL;
  if (sph_snapshot_open_any(path, &ss, err) != 0) return -1;
  int rc = 0;
  double *tmp = NULL;
  s->path = strdup(path);
  s->time = sph_snapshot_time(ss);
  s->n = sph_snapshot_count(ss);
  s->dim = sph_snapshot_dimension(ss);
  if (s->dim != 3 || sph_snapshot_number(ss, "view", s->box, 6, NULL) != 0)
    for (int k = 0; k < 6; k++)
      s->box[k] = NAN;
  if (sph_snapshot_number(ss, "dx", &s->dx, 1, NULL) != 0) s->dx = NAN;
  if (sph_snapshot_number(ss, "view", s->view, 4, NULL) != 0)
    s->view[0] = s->view[1] = s->view[2] = s->view[3] = NAN;
  const char *cn = sph_snapshot_text(ss, "case_name");
  snprintf(s->case_name, sizeof s->case_name, "%s", cn ? cn : "");
  if (field) sph_snapshot_field_units(ss, units_dataset(field), s->units, sizeof s->units);
  if (!s->path) {
    rc = sph_error_set(err, "%s: out of memory", path);
    goto done;
  }
  if ((rc = select_rows(ss, s, air, err)) != 0) goto done;
  size_t n = s->n ? s->n : 1;
  s->x = malloc(n * sizeof *s->x);
  s->y = malloc(n * sizeof *s->y);
  if (s->dim == 3) s->z = malloc(n * sizeof *s->z);
  s->wall = malloc(n);
  tmp = malloc(n * sizeof *tmp);
  if (field) s->val = malloc(n * sizeof *s->val);
  if (!s->path || !s->x || !s->y || (s->dim == 3 && !s->z) || !s->wall || !tmp ||
      (field && !s->val)) {
    rc = sph_error_set(err, "%s: out of memory for %zu particles", path, s->n);
    goto done;
  }
  if ((rc = read_into(ss, s, "x", s->x, "", err)) != 0) goto done;
  if ((rc = read_into(ss, s, "y", s->y, "", err)) != 0) goto done;
  if (s->z && (rc = read_into(ss, s, "z", s->z, "", err)) != 0) goto done;
  if ((rc = read_into(ss, s, "kind", tmp, "", err)) != 0) goto done;
  for (size_t i = 0; i < s->n; i++)
    s->wall[i] = tmp[i] != 0.0;
  if (field) {
    if (strcmp(field, "speed") == 0) {
      const char *why = s->dim == 3 ? " (speed is computed from vx, vy and vz)"
                                    : " (speed is computed from vx and vy)";
      if ((rc = read_into(ss, s, "vx", s->val, why, err)) != 0) goto done;
      for (size_t i = 0; i < s->n; i++)
        s->val[i] *= s->val[i];
      for (int a = 1; a < s->dim; a++) {
        if ((rc = read_into(ss, s, a == 1 ? "vy" : "vz", tmp, why, err)) != 0) goto done;
        for (size_t i = 0; i < s->n; i++)
          s->val[i] += tmp[i] * tmp[i];
      }
      for (size_t i = 0; i < s->n; i++)
        s->val[i] = sqrt(s->val[i]);
    } else {
      const char *ds = rsnap_canonical(field);
      char why[64] = "";
      if (strcmp(ds, field) != 0) snprintf(why, sizeof why, " (read for '%s')", field);
      if ((rc = read_into(ss, s, ds, s->val, why, err)) != 0) goto done;
    }
  }
done:
  free(tmp);
  sph_snapshot_close(ss);
  if (rc) rsnap_free(s);
  return rc;
}

int rsnap_load_volumes(rsnap *s, sph_error *err) {
  sph_snapshot *ss = NULL;
  if (sph_snapshot_open_any(s->path, &ss, err) != 0) return -1;
  size_t n = s->n ? s->n : 1;
  const char *why = " (the interpolated view needs h, mass and rho)";
  double *rho = malloc(n * sizeof *rho);
  s->h = malloc(n * sizeof *s->h);
  s->vol = malloc(n * sizeof *s->vol);
  int rc = 0;
  if (!rho || !s->h || !s->vol)
    rc = sph_error_set(err, "%s: out of memory for %zu particles", s->path, s->n);
  if (!rc) rc = read_into(ss, s, "h", s->h, why, err);
  if (!rc) rc = read_into(ss, s, "mass", s->vol, why, err);
  if (!rc) rc = read_into(ss, s, "rho", rho, why, err);
  for (size_t i = 0; !rc && i < s->n; i++)
    s->vol[i] = rho[i] > 0.0 ? s->vol[i] / rho[i] : 0.0;
  if (!rc) s->kernel = rinterp_kernel_of(ss);
  free(rho);
  sph_snapshot_close(ss);
  if (rc) {
    free(s->h);
    free(s->vol);
    s->h = s->vol = NULL;
  }
  return rc;
}

void rsnap_free(rsnap *s) {
  if (!s) return;
  free(s->h);
  free(s->vol);
  free(s->off);
  free(s->path);
  free(s->x);
  free(s->y);
  free(s->z);
  free(s->val);
  free(s->wall);
  free(s->rows);
  memset(s, 0, sizeof *s);
}

size_t rsnap_fluid_range(const rsnap *s, double *lo, double *hi) {
  size_t count = 0;
  if (!s->val) return 0;
  for (size_t i = 0; i < s->n; i++) {
    double v = s->val[i];
    if (s->wall[i] || !isfinite(v)) continue;
    if (count == 0 || v < *lo) *lo = v;
    if (count == 0 || v > *hi) *hi = v;
    count++;
  }
  return count;
}
