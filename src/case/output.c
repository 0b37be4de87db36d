/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * output.c - the case file's output section (see case.h): snapshots, the
 * free-surface flags, the energy ledger, wave gauges and probes, each
 * gauge and probe inside the domain the water can reach (issue 39, D6).
 */
#include "config.h"

#include "case/case_read.h"

#include "case/domain.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SPH_MAX_PROBE_ROWS 1000000 /* rows of probes.csv from output.probe_interval, at most */

static const char *const output_keys[] = {"snapshots", "free_surface",   "energy", "gauges",
                                          "probes",    "probe_interval", NULL};
static const char *const probe_keys[] = {
    "name",     "kind",   "at",     "x",         "diameter",      "along",
    "low_pass", "wetted", "points", "smoothing", "clip_negative", "hydrostatic",
    "wet_sum",
#if SPH_DIM == 3
    "normal",
#endif
    NULL};
static const char *const probe_kind_names[] = {"pressure", "level", "velocity", NULL};
static const char *const along_names[] = {"y", "x", NULL};

const char *sph_probe_kind_name(sph_probe_kind k) {
  return sph_case_choice_name(probe_kind_names, (int)k);
}

/* The domain the water can reach, from the case alone: the domain the run
 * takes (domain.h) around the box of the tank's inner faces, the walls and
 * the fluid blocks instead of the particles'; the probes and gauges must
 * lie in it (issue 39, D6). */
static void reach_box(const sph_case *c, double box[2 * SPH_DIM]) {
  double bb[2 * SPH_DIM];
  for (int k = 0; k < 2 * SPH_DIM; k += 2)
    bb[k] = INFINITY, bb[k + 1] = -INFINITY;
#define GROW(k, a, b)                                                                              \
  do {                                                                                             \
    bb[k] = fmin(bb[k], fmin(a, b));                                                               \
    bb[k + 1] = fmax(bb[k + 1], fmax(a, b));                                                       \
  } while (0)
  for (int a = 0; a < SPH_DIM; a++)
    if (c->tank.present) GROW(2 * a, c->tank.lo[a], c->tank.hi[a]);
  for (size_t i = 0; i < c->n_walls; i++) {
    GROW(0, c->walls[i].x0, c->walls[i].x1);
    GROW(2, c->walls[i].y0, c->walls[i].y1);
    SPH_IF3(GROW(4, c->walls[i].z0, c->walls[i].z1);)
  }
  for (size_t i = 0; i < c->n_fluid; i++)
    for (int a = 0; a < SPH_DIM; a++)
      GROW(2 * a, c->fluid[i].lo[a], c->fluid[i].hi[a]);
#undef GROW
  sph_case_domain_around(c, bb, box);
}

void sph_case_gauge_column(const sph_case *c, size_t g, char *buf, size_t len) {
  /* the gauge's horizontal coordinates: x (2-D), x and y (3-D) */
  const double *at = &c->gauges[(SPH_DIM - 1) * g];
  size_t n = (size_t)snprintf(buf, len, "eta");
  for (int a = 0; a < SPH_DIM - 1 && n < len; a++)
    n += (size_t)snprintf(buf + n, len - n, "_%.6g", at[a]);
}

/* Whether the comma-separated column list `cols` (",NAME (unit),...", a
 * probe's sph_probe_header) names `name` (units aside). */
static int names_column(const char *cols, const char *name) {
  const size_t n = strlen(name);
  for (const char *p = cols; p && *p; p = strchr(p + 1, ',')) {
    const char *q = p + 1;
    if (strncmp(q, name, n) == 0 && (q[n] == ' ' || q[n] == ',' || q[n] == '\0')) return 1;
  }
  return 0;
}

/* Probe i's columns against the time column and every earlier probe's:
 * each column of probes.csv has a name of its own (a level probe "V_vx"
 * beside a velocity probe "V" gave two columns "V_vx"; issue 61, E10). */
static int unique_columns(const ctx *x, const node *t, const sph_case *c, size_t i) {
  char mine[256], other[256];
  sph_probe_header(&c->probes[i], mine, sizeof mine);
  for (const char *p = mine; p && *p; p = strchr(p + 1, ',')) {
    char col[160];
    const size_t n = strcspn(p + 1, " ,");
    snprintf(col, sizeof col, "%.*s", (int)(n < sizeof col ? n : sizeof col - 1), p + 1);
    char nk[SPH_YAML_KEYLEN];
    sph_yaml_bprintf(nk, sizeof nk, "output.probes[%zu].name", i);
    const node *v = sph_yaml_find(t->items[i], "name")->val;
    if (strcmp(col, "time") == 0)
      return sph_yaml_fail_at(&x->t, v, nk,
                              "expected a name whose columns are its own, got '%s' (its column "
                              "'time' is probes.csv's first)",
                              c->probes[i].name);
    for (size_t k = 0; k < i; k++) {
      sph_probe_header(&c->probes[k], other, sizeof other);
      if (names_column(other, col))
        return sph_yaml_fail_at(&x->t, v, nk,
                                "expected a name whose columns are its own, got '%s' (its column "
                                "'%s' is one of output.probes[%zu]'s, '%s')",
                                c->probes[i].name, col, k, c->probes[k].name);
    }
  }
  return 0;
}

/* A probe's or gauge's place outside box (the node t at key k): the error. */
static int outside_reach(const ctx *x, const node *t, const char *k, const char *what,
                         const double box[2 * SPH_DIM]) {
  char z[96] = ""; /* 3-D: the third range */
  for (int a = 2; a < SPH_DIM; a++)
    snprintf(z, sizeof z, " z [%.9g, %.9g]", box[2 * a], box[2 * a + 1]);
  return sph_yaml_fail_at(&x->t, t, k,
                          "%s is outside the domain, x [%.9g, %.9g] y [%.9g, %.9g]%s "
                          "(geometry.domain, or its default from the geometry): the water cannot "
                          "reach it",
                          what, box[0], box[1], box[2], box[3], z);
}

/* A pressure sensor's interpolation where it states its own (probes.h):
 * points (1 to SPH_PROBE_MAX_POINTS in 2-D, 1 or 5 in 3-D), smoothing (> 0),
 * clip_negative, hydrostatic (true: carried along g) and wet_sum (> 0). */
static int read_interpolation(const ctx *x, const node *m, const char *p, sph_probe *pr) {
  const node *t;
  char kp[SPH_YAML_KEYLEN];
  pr->points = 0;
  if (sph_yaml_get_int(&x->t, m, p, "points", 1, SPH_PROBE_MAX_POINTS, &pr->points) < 0) return -1;
  if (SPH_DIM == 3 && pr->points != 0 && pr->points != 1 && pr->points != 5) {
    sph_yaml_lookup(&x->t, m, p, "points", 1, &t, kp);
    return sph_yaml_fail_at(&x->t, t, kp,
                            "expected 1 or 5 (a 3-D sensor's face: its centre, or the centre "
                            "and four points across it), got %d",
                            pr->points);
  }
  int carry = 1;
  if (sph_yaml_get_number(&x->t, m, p, "smoothing", 0, &SPH_YAML_POS, &pr->smoothing) < 0 ||
      sph_yaml_get_bool(&x->t, m, p, "clip_negative", &pr->clip_negative) < 0 ||
      sph_yaml_get_bool(&x->t, m, p, "hydrostatic", &carry) < 0 ||
      sph_yaml_get_number(&x->t, m, p, "wet_sum", 0, &SPH_YAML_POS, &pr->wet_sum) < 0)
    return -1;
  pr->no_carry = !carry;
  return 0;
}

/* One entry of output.probes (p its key, output.probes[i]), inside box. */
static int read_probe(const ctx *x, const node *m, const char *p, const double box[2 * SPH_DIM],
                      sph_probe *pr) {
  const node *t;
  char kp[SPH_YAML_KEYLEN], b[96];
  if (m->kind != SPH_YAML_MAP)
    return sph_yaml_fail_at(&x->t, m, p, "expected a mapping, got %s",
                            sph_yaml_got(m, b, sizeof b));
  if (sph_yaml_check_keys(&x->t, m, p, probe_keys)) return -1;
  const char *s;
  if (sph_case_read_plain_name(x, m, p, "name", &s)) return -1;
  memcpy(pr->name, s, strlen(s) + 1);
  int kind = -1;
  if (sph_yaml_lookup(&x->t, m, p, "kind", 1, &t, kp) < 0 ||
      sph_yaml_read_choice(&x->t, t, kp, probe_kind_names, &kind))
    return -1;
  pr->kind = (sph_probe_kind)kind;
  const int level = pr->kind == SPH_PROBE_LEVEL, pressure = pr->kind == SPH_PROBE_PRESSURE;
  /* the keys each kind takes (3-D: a level gauge is at (x, y), a pressure
   * sensor has a normal instead of along) */
  enum { N_ONLY = 12 };
  static const char *const only[N_ONLY] = {
      "at",     "x",      "diameter",  "along",         "low_pass",    "normal",
      "wetted", "points", "smoothing", "clip_negative", "hydrostatic", "wet_sum"};
#if SPH_DIM == 2
  const int allowed[3][N_ONLY] = {{1, 0, 1, 1, 1, 0, 0, 1, 1, 1, 1, 1},
                                  {0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0},
                                  {1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}};
#else
  const int allowed[3][N_ONLY] = {{1, 0, 1, 0, 1, 1, 0, 1, 1, 1, 1, 1},
                                  {1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0},
                                  {1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}};
#endif
  for (int k = 0; k < N_ONLY; k++)
    if (!allowed[kind][k] && sph_yaml_lookup(&x->t, m, p, only[k], 0, &t, kp) > 0)
      return sph_yaml_fail_at(&x->t, t, kp, "not a key of a %s probe", probe_kind_names[kind]);
  if (level && sph_yaml_get_bool(&x->t, m, p, "wetted", &pr->wetted) < 0) return -1;
  if (pressure && read_interpolation(x, m, p, pr)) return -1;
#if SPH_DIM == 3
  if (level) { /* the vertical line at (x, y) */
    double at[2];
    if (sph_yaml_get_vector(&x->t, m, p, "at", 1, 2, at) < 0) return -1;
    pr->x = at[0];
    pr->y = at[1];
    if (!(at[0] >= box[0] && at[0] <= box[1] && at[1] >= box[2] && at[1] <= box[3])) {
      sph_yaml_lookup(&x->t, m, p, "at", 1, &t, kp);
      sph_yaml_bprintf(b, sizeof b, "(%g, %g)", at[0], at[1]);
      return outside_reach(x, t, kp, b, box);
    }
    return 0;
  }
  double at[3];
  if (sph_yaml_get_vector(&x->t, m, p, "at", 1, 3, at) < 0) return -1;
  pr->x = at[0];
  pr->y = at[1];
  pr->z = at[2];
  if (!(at[0] >= box[0] && at[0] <= box[1] && at[1] >= box[2] && at[1] <= box[3] &&
        at[2] >= box[4] && at[2] <= box[5])) {
    sph_yaml_lookup(&x->t, m, p, "at", 1, &t, kp);
    sph_yaml_bprintf(b, sizeof b, "(%g, %g, %g)", at[0], at[1], at[2]);
    return outside_reach(x, t, kp, b, box);
  }
  if (pressure) {
    const double side = fmax(fmax(box[1] - box[0], box[3] - box[2]), box[5] - box[4]);
    const range dia = {0, side, '[', ']', NULL};
    if (sph_yaml_get_number(&x->t, m, p, "diameter", 0, &dia, &pr->diameter) < 0 ||
        sph_yaml_get_number(&x->t, m, p, "low_pass", 0, &SPH_YAML_POS, &pr->low_pass) < 0 ||
        sph_yaml_get_vector(&x->t, m, p, "normal", 1, 3, pr->normal) < 0)
      return -1;
    const double *nv = pr->normal;
    const double len = sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
    if (!(len > 0.0) || !isfinite(len)) {
      sph_yaml_lookup(&x->t, m, p, "normal", 1, &t, kp);
      return sph_yaml_fail_at(&x->t, t, kp, "expected a non-zero vector, got [%g, %g, %g]", nv[0],
                              nv[1], nv[2]);
    }
    for (int d = 0; d < 3; d++)
      pr->normal[d] /= len;
  }
  return 0;
#endif
  if (level) {
    if (sph_yaml_get_number(&x->t, m, p, "x", 1, &SPH_YAML_ANY, &pr->x) < 0) return -1;
    if (!(pr->x >= box[0] && pr->x <= box[1])) {
      sph_yaml_lookup(&x->t, m, p, "x", 1, &t, kp);
      sph_yaml_bprintf(b, sizeof b, "x = %g", pr->x);
      return outside_reach(x, t, kp, b, box);
    }
    return 0;
  }
  double v[2] = {0, 0};
  if (sph_yaml_get_pair(&x->t, m, p, "at", 1, 0, v) < 0) return -1;
  pr->x = v[0];
  pr->y = v[1];
  if (!(v[0] >= box[0] && v[0] <= box[1] && v[1] >= box[2] && v[1] <= box[3])) {
    sph_yaml_lookup(&x->t, m, p, "at", 1, &t, kp);
    sph_yaml_bprintf(b, sizeof b, "(%g, %g)", v[0], v[1]);
    return outside_reach(x, t, kp, b, box);
  }
  if (pressure) {
    /* a face no wider than the domain */
    const double side = fmax(box[1] - box[0], box[3] - box[2]);
    const range dia = {0, side, '[', ']', NULL};
    int along = 0;
    if (sph_yaml_get_number(&x->t, m, p, "diameter", 0, &dia, &pr->diameter) < 0 ||
        sph_yaml_get_choice(&x->t, m, p, "along", along_names, &along) < 0 ||
        sph_yaml_get_number(&x->t, m, p, "low_pass", 0, &SPH_YAML_POS, &pr->low_pass) < 0)
      return -1;
    pr->along_x = along;
  }
  return 0;
}

/* output.probes and output.probe_interval. */
static int read_probes(const ctx *x, const node *s, sph_case *c) {
  const node *t;
  char kp[SPH_YAML_KEYLEN], b[96];
  if (sph_yaml_lookup(&x->t, s, "output", "probes", 0, &t, kp) <= 0) {
    if (sph_yaml_lookup(&x->t, s, "output", "probe_interval", 0, &t, kp) > 0)
      return sph_yaml_fail_at(&x->t, t, kp, "expected output.probes alongside it");
    return 0;
  }
  if (t->kind != SPH_YAML_LIST || t->n == 0)
    return sph_yaml_fail_at(&x->t, t, kp, "expected a non-empty list of probes, got %s",
                            sph_yaml_got(t, b, sizeof b));
  if (t->n > 1000)
    return sph_yaml_fail_at(&x->t, t, kp, "expected at most 1000 probes, got %zu", t->n);
  if (!(c->probes = calloc(t->n, sizeof *c->probes))) return sph_yaml_oom(&x->t);
  c->n_probes = t->n;
  double box[2 * SPH_DIM];
  reach_box(c, box);
  for (size_t i = 0; i < t->n; i++) {
    sph_yaml_bprintf(kp, sizeof kp, "output.probes[%zu]", i);
    if (read_probe(x, t->items[i], kp, box, &c->probes[i])) return -1;
    for (size_t k = 0; k < i; k++)
      if (strcmp(c->probes[k].name, c->probes[i].name) == 0) {
        char nk[SPH_YAML_KEYLEN];
        sph_yaml_bprintf(nk, sizeof nk, "%s.name", kp);
        return sph_yaml_fail_at(
            &x->t, sph_yaml_find(t->items[i], "name")->val, nk,
            "expected a name of its own, got '%s' (the name of output.probes[%zu])",
            c->probes[i].name, k);
      }
    if (unique_columns(x, t, c, i)) return -1;
  }
  /* 0 (a row every step) or at most SPH_MAX_PROBE_ROWS rows: each row
   * time is landed on, so a tiny interval would shorten every step to it
   * and write a row a step for ever (issue 61, E5) */
  const double least = c->t_end / SPH_MAX_PROBE_ROWS;
  char what[160];
  sph_yaml_bprintf(what, sizeof what,
                   "0 (a row every step) or a number from time.end/%d (%g, at most %d rows) to "
                   "time.end (%g)",
                   SPH_MAX_PROBE_ROWS, least, SPH_MAX_PROBE_ROWS, c->t_end);
  const range iv = {0, c->t_end, '[', ']', what};
  if (sph_yaml_get_number(&x->t, s, "output", "probe_interval", 0, &iv, &c->probe_interval) < 0)
    return -1;
  if (c->probe_interval > 0.0 && c->probe_interval < least) {
    sph_yaml_lookup(&x->t, s, "output", "probe_interval", 0, &t, kp);
    return sph_yaml_fail_at(&x->t, t, kp, "expected %s, got %g", what, c->probe_interval);
  }
  return 0;
}

/* The output section: snapshots, free_surface, energy, gauges and probes. */
int sph_case_read_output(const ctx *x, const node *root, sph_case *c) {
  const node *s;
  int rc = sph_yaml_get_section(&x->t, root, "", "output", 0, output_keys, &s);
  if (rc > 0) rc = sph_yaml_get_bool(&x->t, s, "output", "snapshots", &c->snapshots);
  if (rc >= 0 && s)
    rc = sph_yaml_get_bool(&x->t, s, "output", "free_surface", &c->output_free_surface);
  if (rc >= 0 && s) rc = sph_yaml_get_bool(&x->t, s, "output", "energy", &c->energy);
  const node *gl;
  char gk[SPH_YAML_KEYLEN];
  if (rc >= 0 && s && sph_yaml_lookup(&x->t, s, "output", "gauges", 0, &gl, gk) > 0) {
    char b[96];
    enum { H = SPH_DIM - 1 }; /* a gauge's horizontal coordinates */
    if (gl->kind != SPH_YAML_LIST || gl->n == 0)
      return sph_yaml_fail_at(&x->t, gl, gk, "expected a non-empty list of %s, got %s",
                              H == 1 ? "x positions" : "[x, y] positions",
                              sph_yaml_got(gl, b, sizeof b));
    if (!(c->gauges = calloc(gl->n * H, sizeof *c->gauges))) return sph_yaml_oom(&x->t);
    c->n_gauges = gl->n;
    double box[2 * SPH_DIM];
    reach_box(c, box);
    for (size_t i = 0; i < gl->n; i++) {
      char ik[SPH_YAML_KEYLEN];
      double *at = c->gauges + i * H;
      sph_yaml_bprintf(ik, sizeof ik, "output.gauges[%zu]", i);
      if (H == 1 ? sph_yaml_read_number(&x->t, gl->items[i], ik, &SPH_YAML_ANY, at)
                 : sph_yaml_read_vector(&x->t, gl->items[i], ik, H, at))
        return -1;
      for (int a = 0; a < H; a++)
        if (!(at[a] >= box[2 * a] && at[a] <= box[2 * a + 1])) {
          sph_yaml_bprintf(b, sizeof b, "%c = %g", "xy"[a], at[a]);
          return outside_reach(x, gl->items[i], ik, b, box);
        }
      /* a column of its own in gauges.csv (issue 61, E10) */
      char mine[64], other[64];
      sph_case_gauge_column(c, i, mine, sizeof mine);
      for (size_t k = 0; k < i; k++) {
        sph_case_gauge_column(c, k, other, sizeof other);
        if (strcmp(mine, other) == 0)
          return sph_yaml_fail_at(&x->t, gl->items[i], ik,
                                  "expected a place of its own, got the column %s of "
                                  "output.gauges[%zu] (two gauges there read the same)",
                                  mine, k);
      }
    }
  }
  if (rc >= 0 && s && read_probes(x, s, c)) return -1;
  return rc < 0 ? -1 : 0;
}
