/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * mesh_run.c - the mesh mode (see mesh_run.h). The snapshots are chosen
 * and every output named before the first surface is made; the surfaces
 * are then made one after the other, each written atomically.
 */
#include "config.h"

#include "mesh_run.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "inputs.h"
#include "ply_out.h"
#include "snapdata.h"
#include "surface.h"
#include "vtk_out.h"

/* Whether path ends with ext. */
static int ends_with(const char *path, const char *ext) {
  const size_t n = strlen(path), e = strlen(ext);
  return n > e && strcmp(path + n - e, ext) == 0;
}

/* The output of snapshot path: OUT, or OUT/surface_NNNN.ply (.vtk with --format vtk). */
static char *output_of(const roptions *o, int single, const char *path) {
  if (single) return strdup(o->output);
  const char *ext = o->mesh_vtk ? "vtk" : "ply";
  char num[256], stem[256];
  rinputs_number(path, num, sizeof num);
  rinputs_stem(path, stem, sizeof stem);
  const size_t len = strlen(o->output) + strlen(stem) + 32;
  char *out = malloc(len);
  if (!out) return NULL;
  if (num[0])
    snprintf(out, len, "%s/surface_%s.%s", o->output, num, ext);
  else
    snprintf(out, len, "%s/%s.%s", o->output, stem, ext);
  return out;
}

/* One snapshot's surface into out. */
static int one(const roptions *o, const char *path, const char *out, size_t *nt, sph_error *err) {
  rsnap s;
  if (rsnap_load_phases(path, o->field_given ? o->field : NULL, o->air, &s, err) != 0) return -1;
  int rc = 0;
  if (s.dim != 3)
    rc = sph_error_set(err, "%s is 2-D: the mesh mode writes the surfaces of 3-D snapshots", path);
  double cell = 0.0;
  if (!rc) rc = rsnap_load_volumes(&s, err);
  if (!rc) rc = rsurface_cell(&s, o->surface_cell, &cell, err);
  rmesh m = {0};
  if (!rc) rc = rsurface_of(&s, cell, o->field_given, &m, err);
  if (!rc) {
    char c[4][600];
    snprintf(c[0], sizeof c[0], "sph-render free surface: level %g of the fluid's SPH kernel sum",
             RSURFACE_LEVEL);
    snprintf(c[1], sizeof c[1], "source %s", path);
    snprintf(c[2], sizeof c[2], "time %.9g s", s.time);
    snprintf(c[3], sizeof c[3], "cell %.9g m", cell);
    const char *const comments[4] = {c[0], c[1], c[2], c[3]};
    const char *field = o->field_given ? rsnap_canonical(o->field) : NULL;
    if (ends_with(out, ".vtk")) {
      char title[256];
      snprintf(title, sizeof title, "sph-render free surface, time %.9g s, cell %.9g m", s.time,
               cell);
      rc = rvtk_write(out, &m, field, title, err);
    } else {
      rc = rply_write(out, &m, field, comments, 4, err);
    }
    *nt = m.nt;
  }
  rmesh_free(&m);
  rsnap_free(&s);
  return rc;
}

int rmesh_run(const roptions *o, const char *prog, sph_error *err) {
  rinputs in = {0};
  char **outs = NULL;
  size_t *pick = NULL, n = 0;
  int rc = -1;
  for (int i = 0; i < o->n_inputs; i++)
    if (rinputs_add(&in, o->inputs[i], err) != 0) goto done;
  const size_t want = o->n_times > 0 ? (size_t)o->n_times : in.n;
  if (o->n_times > 0 && rinputs_times(&in, err) != 0) goto done;
  pick = malloc((want ? want : 1) * sizeof *pick);
  outs = calloc(want ? want : 1, sizeof *outs);
  if (!pick || !outs) {
    sph_error_set(err, "out of memory");
    goto done;
  }
  for (size_t i = 0; i < want; i++) { /* the nearest snapshot to each time, each once */
    const size_t k = o->n_times > 0 ? rinputs_nearest(&in, o->times[i]) : i;
    int dup = 0;
    for (size_t j = 0; j < n; j++)
      dup |= pick[j] == k;
    if (!dup) pick[n++] = k;
  }
  const int single = ends_with(o->output, ".ply") || ends_with(o->output, ".vtk");
  if (single && n != 1) {
    sph_error_set(err, "-o %s names one file but there are %zu snapshots: give a directory",
                  o->output, n);
    goto done;
  }
  for (size_t i = 0; i < n; i++)
    if (!(outs[i] = output_of(o, single, in.v[pick[i]].path))) {
      sph_error_set(err, "out of memory");
      goto done;
    }
  if (!single && rinputs_mkdirs(o->output, err) != 0) goto done;
  for (size_t i = 0; i < n; i++) {
    size_t nt = 0;
    if (one(o, in.v[pick[i]].path, outs[i], &nt, err) != 0) goto done;
    if (o->verbose) fprintf(stderr, "%s: wrote %s (%zu triangles)\n", prog, outs[i], nt);
  }
  if (n > 1 || o->verbose)
    fprintf(stderr, "%s: wrote %zu surface%s (%s)\n", prog, n, n == 1 ? "" : "s", o->output);
  rc = 0;
done:
  for (size_t i = 0; outs && i < n; i++)
    free(outs[i]);
  free(outs);
  free(pick);
  rinputs_free(&in);
  return rc;
}
