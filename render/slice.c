/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * slice.c - a 3-D snapshot cut by a plane (see slice.h).
 */
#include "config.h"

#include "slice.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int rslice_parse(const char *text, rslice *sl, sph_error *err) {
  const char *form = "--slice: '%s': expected AXIS=POS[,THICKNESS] (AXIS x, y or z; metres), "
                     "e.g. y=0.5,0.02";
  if (!text || !strchr("xyz", text[0]) || text[0] == '\0' || text[1] != '=')
    return sph_error_set(err, form, text ? text : "");
  sl->axis = text[0] - 'x';
  char *end;
  errno = 0;
  sl->pos = strtod(text + 2, &end);
  if (end == text + 2 || errno == ERANGE || !isfinite(sl->pos))
    return sph_error_set(err, form, text);
  sl->thickness = 0.0;
  if (*end == ',') {
    const char *t = end + 1;
    sl->thickness = strtod(t, &end);
    if (end == t || errno == ERANGE || !(sl->thickness > 0.0) || !isfinite(sl->thickness))
      return sph_error_set(err, "--slice: '%s': the thickness must be metres > 0", text);
  }
  if (*end != '\0') return sph_error_set(err, form, text);
  return 0;
}

int rslice_axis(int axis, int which) {
  if (axis == 2) return which; /* across z: x, y */
  return which == 0 ? (axis == 0 ? 1 : 0) : 2;
}

int rslice_apply(const rslice *sl, rsnap *s, sph_error *err) {
  if (s->dim != 3 || !s->z)
    return sph_error_set(err, "%s is 2-D: --slice cuts 3-D snapshots", s->path);
  const double half = 0.5 * (sl->thickness > 0.0 ? sl->thickness : s->dx);
  if (!(half > 0.0))
    return sph_error_set(err,
                         "%s: no particle spacing (attribute dx): give --slice %c=%g,THICKNESS",
                         s->path, 'x' + sl->axis, sl->pos);
  /* a cut outside the domain would draw an empty panel (issue 61, E11) */
  const double lo = s->box[2 * sl->axis], hi = s->box[2 * sl->axis + 1];
  if (isfinite(lo) && isfinite(hi) && !(sl->pos >= lo && sl->pos <= hi))
    return sph_error_set(err, "%s: --slice %c=%g is outside the domain, %c [%g, %g]", s->path,
                         'x' + sl->axis, sl->pos, 'x' + sl->axis, lo, hi);
  const int u = rslice_axis(sl->axis, 0), v = rslice_axis(sl->axis, 1);
  double *c[3] = {s->x, s->y, s->z};
  double *nu = malloc((s->n ? s->n : 1) * sizeof *nu), *nv = malloc((s->n ? s->n : 1) * sizeof *nv);
  double *off = malloc((s->n ? s->n : 1) * sizeof *off);
  if (!nu || !nv || !off) {
    free(nu), free(nv), free(off);
    return sph_error_set(err, "%s: out of memory for a slice", s->path);
  }
  size_t n = 0;
  for (size_t i = 0; i < s->n; i++) {
    const double d = c[sl->axis][i] - sl->pos;
    const double reach = s->h ? fmax(half, 2.0 * s->h[i]) : half; /* the kernel's support */
    if (!(fabs(d) <= reach)) continue;
    nu[n] = c[u][i];
    nv[n] = c[v][i];
    off[n] = d;
    s->wall[n] = s->wall[i];
    if (s->val) s->val[n] = s->val[i];
    if (s->h) s->h[n] = s->h[i];
    if (s->vol) s->vol[n] = s->vol[i];
    n++;
  }
  free(s->x), free(s->y), free(s->z);
  s->x = nu, s->y = nv, s->z = NULL;
  s->off = off;
  s->slab = half * (1.0 + 1e-9); /* a layer exactly half the thickness away counts */
  s->n = n;
  if (isfinite(s->box[0])) {
    s->view[0] = s->box[2 * u], s->view[1] = s->box[2 * u + 1];
    s->view[2] = s->box[2 * v], s->view[3] = s->box[2 * v + 1];
  }
  return 0;
}
