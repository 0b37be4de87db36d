/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * isosurface.c - marching cubes through tetrahedra (see isosurface.h).
 *
 * An edge of the lattice starts at a point and goes along one of seven
 * directions, named by the mask of the axes it advances (1 x, 2 y, 3 xy,
 * 4 z, 5 xz, 6 yz, 7 xyz). The vertices of the edges that start in a
 * layer k of the lattice are made together, in lattice order, and their
 * indices kept per layer; the cubes between layers k and k + 1 need only
 * those two layers, so two layers' tables are all the memory besides the
 * mesh.
 */
#include "config.h"

#include "isosurface.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NONE UINT32_MAX
#define MAX_VERTICES ((size_t)UINT32_MAX - 1)

typedef struct builder {
  const rgrid3 *g;
  const double *s, *f;
  double level;
  rmesh *m;
  size_t cap_v, cap_t;
  sph_error *err;
} builder;

static size_t at(const rgrid3 *g, int i, int j, int k) {
  return ((size_t)k * (size_t)g->n[1] + (size_t)j) * (size_t)g->n[0] + (size_t)i;
}

/* The field's gradient at point (i, j, k): central differences, one-sided
 * on the lattice's faces. */
static void gradient(const builder *b, int i, int j, int k, double grad[3]) {
  const int q[3] = {i, j, k};
  for (int a = 0; a < 3; a++) {
    int lo[3] = {i, j, k}, hi[3] = {i, j, k};
    if (q[a] > 0) lo[a]--;
    if (q[a] < b->g->n[a] - 1) hi[a]++;
    const double span = (hi[a] - lo[a]) * b->g->step;
    grad[a] =
        span > 0.0
            ? (b->s[at(b->g, hi[0], hi[1], hi[2])] - b->s[at(b->g, lo[0], lo[1], lo[2])]) / span
            : 0.0;
  }
}

static int grow(builder *b, size_t more_v, size_t more_t) {
  rmesh *m = b->m;
  if (m->nv + more_v > b->cap_v) {
    if (m->nv + more_v > MAX_VERTICES)
      return sph_error_set(b->err, "surface: more than %zu vertices", MAX_VERTICES);
    size_t cap = b->cap_v ? 2 * b->cap_v : 4096;
    while (cap < m->nv + more_v)
      cap *= 2;
    float *p = realloc(m->p, 3 * cap * sizeof *p);
    if (p) m->p = p;
    float *nrm = p ? realloc(m->normal, 3 * cap * sizeof *nrm) : NULL;
    if (nrm) m->normal = nrm;
    float *val = m->val;
    if (nrm && b->f && (val = realloc(m->val, cap * sizeof *val))) m->val = val;
    if (!p || !nrm || (b->f && !val))
      return sph_error_set(b->err, "surface: out of memory for %zu vertices", cap);
    b->cap_v = cap;
  }
  if (m->nt + more_t > b->cap_t) {
    size_t cap = b->cap_t ? 2 * b->cap_t : 8192;
    while (cap < m->nt + more_t)
      cap *= 2;
    uint32_t *t = realloc(m->tri, 3 * cap * sizeof *t);
    if (!t) return sph_error_set(b->err, "surface: out of memory for %zu triangles", cap);
    m->tri = t;
    b->cap_t = cap;
  }
  return 0;
}

/* The vertex where edge (i, j, k) + mask crosses the level; its index. */
static int add_vertex(builder *b, int i, int j, int k, int mask, uint32_t *index) {
  const rgrid3 *g = b->g;
  const int i1 = i + (mask & 1), j1 = j + ((mask >> 1) & 1), k1 = k + ((mask >> 2) & 1);
  const size_t qa = at(g, i, j, k), qb = at(g, i1, j1, k1);
  const double va = b->s[qa], vb = b->s[qb];
  if ((va >= b->level) == (vb >= b->level)) {
    *index = NONE;
    return 0;
  }
  if (grow(b, 1, 0) != 0) return -1;
  rmesh *m = b->m;
  const double t = (b->level - va) / (vb - va);
  const int ia[3] = {i, j, k}, ib[3] = {i1, j1, k1};
  double ga[3], gb[3], n[3], len = 0.0;
  gradient(b, i, j, k, ga);
  gradient(b, i1, j1, k1, gb);
  for (int a = 0; a < 3; a++) {
    const double pa = g->origin[a] + ia[a] * g->step, pb = g->origin[a] + ib[a] * g->step;
    m->p[3 * m->nv + a] = (float)(pa + t * (pb - pa));
    n[a] = -(ga[a] + t * (gb[a] - ga[a]));
    len += n[a] * n[a];
  }
  len = sqrt(len);
  for (int a = 0; a < 3; a++) {
    if (len > 0.0) /* a flat field: out of the inside along the edge */
      n[a] /= len;
    else
      n[a] = (va >= b->level ? 1.0 : -1.0) * (ib[a] - ia[a]);
    m->normal[3 * m->nv + a] = (float)n[a];
  }
  if (b->f) {
    const double fa = b->f[qa], fb = b->f[qb];
    const double v = isnan(fa) ? fb : isnan(fb) ? fa : fa + t * (fb - fa);
    m->val[m->nv] = (float)v;
  }
  *index = (uint32_t)m->nv++;
  return 0;
}

/* Makes the vertices of the edges starting in layer k into table e
 * (7 per point of the layer). */
static int make_layer(builder *b, int k, uint32_t *e) {
  const rgrid3 *g = b->g;
  for (int j = 0; j < g->n[1]; j++)
    for (int i = 0; i < g->n[0]; i++)
      for (int mask = 1; mask <= 7; mask++) {
        uint32_t *slot = &e[((size_t)j * g->n[0] + i) * 7 + (mask - 1)];
        *slot = NONE;
        if (i + (mask & 1) >= g->n[0] || j + ((mask >> 1) & 1) >= g->n[1] ||
            k + ((mask >> 2) & 1) >= g->n[2])
          continue;
        if (add_vertex(b, i, j, k, mask, slot) != 0) return -1;
      }
  return 0;
}

/* Adds triangle (a, b, c), wound so that its normal points along out;
 * a triangle of no area (vertices on lattice points) is left out. */
static void add_triangle(builder *b, uint32_t v0, uint32_t v1, uint32_t v2, const double out[3]) {
  rmesh *m = b->m;
  const float *p0 = m->p + 3 * (size_t)v0, *p1 = m->p + 3 * (size_t)v1, *p2 = m->p + 3 * (size_t)v2;
  const double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  const double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
  const double d = n[0] * out[0] + n[1] * out[1] + n[2] * out[2];
  if (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0) return;
  uint32_t *t = m->tri + 3 * m->nt++;
  t[0] = v0;
  t[1] = d >= 0.0 ? v1 : v2;
  t[2] = d >= 0.0 ? v2 : v1;
}

/* The cubes between layers k (table lo) and k + 1 (table hi). */
static int march_layer(builder *b, int k, const uint32_t *lo, const uint32_t *hi) {
  static const int order[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const rgrid3 *g = b->g;
  for (int j = 0; j + 1 < g->n[1]; j++)
    for (int i = 0; i + 1 < g->n[0]; i++) {
      int inside[8], count = 0;
      for (int c = 0; c < 8; c++) {
        inside[c] = b->s[at(g, i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1))] >= b->level;
        count += inside[c];
      }
      if (count == 0 || count == 8) continue;
      if (grow(b, 0, 12) != 0) return -1;
      for (int t = 0; t < 6; t++) {
        const int corner[4] = {0, 1 << order[t][0], (1 << order[t][0]) | (1 << order[t][1]), 7};
        /* the vertex on the edge between corners u and w of the tetrahedron */
#define EDGE(u, w)                                                                                 \
  ((((u) >> 2) & 1 ? hi : lo)[((size_t)(j + (((u) >> 1) & 1)) * g->n[0] + (i + ((u)&1))) * 7 +     \
                              (size_t)(((u) ^ (w)) - 1)])
        int in[4], out[4], n_in = 0, n_out = 0;
        for (int v = 0; v < 4; v++) {
          if (inside[corner[v]])
            in[n_in++] = corner[v];
          else
            out[n_out++] = corner[v];
        }
        if (n_in == 0 || n_out == 0) continue;
        double dir[3] = {0.0, 0.0, 0.0}; /* from the inside corners to the outside ones */
        for (int a = 0; a < 3; a++) {
          for (int v = 0; v < n_out; v++)
            dir[a] += ((out[v] >> a) & 1) / (double)n_out;
          for (int v = 0; v < n_in; v++)
            dir[a] -= ((in[v] >> a) & 1) / (double)n_in;
        }
        /* edges join corners u < w with u's axes a subset of w's */
#define E(a, c) ((a) < (c) ? EDGE(a, c) : EDGE(c, a))
        if (n_in == 1 || n_out == 1) {
          const int lone = n_in == 1 ? in[0] : out[0];
          const int *rest = n_in == 1 ? out : in;
          add_triangle(b, E(lone, rest[0]), E(lone, rest[1]), E(lone, rest[2]), dir);
        } else {
          const uint32_t ac = E(in[0], out[0]), ad = E(in[0], out[1]);
          const uint32_t bd = E(in[1], out[1]), bc = E(in[1], out[0]);
          add_triangle(b, ac, ad, bd, dir);
          add_triangle(b, ac, bd, bc, dir);
        }
#undef E
#undef EDGE
      }
    }
  return 0;
}

int rmesh_isosurface(const rgrid3 *g, const double *s, const double *f, double level, rmesh *m,
                     sph_error *err) {
  memset(m, 0, sizeof *m);
  builder b = {.g = g, .s = s, .f = f, .level = level, .m = m, .err = err};
  const size_t layer = (size_t)g->n[0] * (size_t)g->n[1] * 7;
  uint32_t *e[2] = {malloc(layer * sizeof **e), malloc(layer * sizeof **e)};
  int rc = 0;
  if (!e[0] || !e[1]) rc = sph_error_set(err, "surface: out of memory for the edge tables");
  if (!rc && g->n[2] > 0) rc = make_layer(&b, 0, e[0]);
  for (int k = 0; !rc && k + 1 < g->n[2]; k++) {
    rc = make_layer(&b, k + 1, e[(k + 1) & 1]);
    if (!rc) rc = march_layer(&b, k, e[k & 1], e[(k + 1) & 1]);
  }
  free(e[0]);
  free(e[1]);
  if (rc) rmesh_free(m);
  return rc;
}

void rmesh_free(rmesh *m) {
  if (!m) return;
  free(m->p);
  free(m->normal);
  free(m->val);
  free(m->tri);
  memset(m, 0, sizeof *m);
}

/* Sums over the triangles of p0 . (p1 x p2) / 6 (volume) or |..| / 2 (area). */
static double sum_triangles(const rmesh *m, int volume) {
  double sum = 0.0;
  for (size_t t = 0; t < m->nt; t++) {
    double p[3][3];
    for (int v = 0; v < 3; v++)
      for (int a = 0; a < 3; a++)
        p[v][a] = m->p[3 * (size_t)m->tri[3 * t + v] + a];
    if (volume) {
      sum += (p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) +
              p[0][1] * (p[1][2] * p[2][0] - p[1][0] * p[2][2]) +
              p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0])) /
             6.0;
    } else {
      double e1[3], e2[3];
      for (int a = 0; a < 3; a++) {
        e1[a] = p[1][a] - p[0][a];
        e2[a] = p[2][a] - p[0][a];
      }
      const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                           e1[0] * e2[1] - e1[1] * e2[0]};
      sum += 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
  }
  return sum;
}

double rmesh_volume(const rmesh *m) { return sum_triangles(m, 1); }
double rmesh_area(const rmesh *m) { return sum_triangles(m, 0); }
