/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * mesh.c - closed triangle surfaces from mesh files (mesh.h), read with
 * the Open Asset Import Library (Assimp, its C interface): STL (ASCII and
 * binary), OBJ, PLY and the rest of its formats, one reader for all of
 * them, maintained and packaged by Debian (libassimp-dev).
 *
 * After reading, the vertices are welded by their exact coordinates (STL
 * stores each triangle's own three), every edge must join exactly two
 * triangles that run along it in opposite directions (closed, manifold,
 * consistently turned), and the volume must be positive (the vertices
 * anticlockwise seen from outside, STL's rule). The inside test casts a
 * ray up the z axis and adds, over the triangles it crosses above the
 * point, the sign of each one's normal z; the triangles are binned by
 * their xy extent so that a point looks at those of its bin only. On an
 * edge or a vertex of the triangles' xy projection, a point belongs to the
 * triangles it would be inside after an infinitesimal move right and a
 * smaller one up (each edge's function computed from its lower end, so
 * the triangles on its two sides see one value): each ray crosses a
 * closed surface's sheet once.
 */
#include "config.h"

#include "case/mesh.h"

#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

struct sph_mesh {
  size_t nv, nt;
  double *v;   /* 3 nv coordinates */
  uint32_t *t; /* 3 nt vertex indices, anticlockwise seen from outside */
  double lo[3], hi[3], volume;
  size_t bx, by; /* the xy bins */
  double w[2];   /* their widths */
  size_t *start; /* bin k's triangles: item[start[k] .. start[k + 1] - 1] */
  uint32_t *item;
};

void sph_mesh_free(sph_mesh *m) {
  if (!m) return;
  free(m->v);
  free(m->t);
  free(m->start);
  free(m->item);
  free(m);
}

void sph_mesh_bounds(const sph_mesh *m, double lo[3], double hi[3]) {
  memcpy(lo, m->lo, sizeof m->lo);
  memcpy(hi, m->hi, sizeof m->hi);
}
double sph_mesh_volume(const sph_mesh *m) { return m->volume; }
size_t sph_mesh_triangles(const sph_mesh *m) { return m->nt; }

/* ---- welding ---- */

typedef struct corner {
  double x[3];
  size_t at; /* its place in the triangles' corner list */
} corner;

static int corner_order(const void *pa, const void *pb) {
  const corner *a = pa, *b = pb;
  for (int d = 0; d < 3; d++)
    if (a->x[d] != b->x[d]) return a->x[d] < b->x[d] ? -1 : 1;
  return a->at < b->at ? -1 : a->at > b->at;
}

/* ---- edges ---- */

typedef struct edge {
  uint32_t lo, hi; /* its ends, lower index first */
  int dir;         /* +1 run from lo to hi by its triangle, -1 from hi to lo */
} edge;

static int edge_order(const void *pa, const void *pb) {
  const edge *a = pa, *b = pb;
  if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
  if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
  return a->dir - b->dir;
}

static int check_edges(const sph_mesh *m, char *why, size_t len) {
  edge *e = malloc(3 * m->nt * sizeof *e);
  if (!e) return snprintf(why, len, "out of memory"), -1;
  for (size_t k = 0; k < m->nt; k++)
    for (int c = 0; c < 3; c++) {
      const uint32_t u = m->t[3 * k + c], v = m->t[3 * k + (c + 1) % 3];
      e[3 * k + c] = (edge){u < v ? u : v, u < v ? v : u, u < v ? 1 : -1};
    }
  qsort(e, 3 * m->nt, sizeof *e, edge_order);
  int rc = 0;
  for (size_t i = 0; i < 3 * m->nt && !rc;) {
    size_t j = i;
    while (j < 3 * m->nt && e[j].lo == e[i].lo && e[j].hi == e[i].hi)
      j++;
    const double *a = m->v + 3 * e[i].lo, *b = m->v + 3 * e[i].hi;
    if (j - i != 2 || e[i].dir == e[i + 1].dir) {
      const char *what = j - i == 1  ? "belongs to one triangle only: the surface is open"
                         : j - i > 2 ? "is shared by more than two triangles"
                                     : "joins two triangles turned opposite ways";
      snprintf(why, len,
               "the edge from (%g, %g, %g) to (%g, %g, %g) %s (expected a closed surface, "
               "each triangle's vertices anticlockwise seen from outside)",
               a[0], a[1], a[2], b[0], b[1], b[2], what);
      rc = -1;
    }
    i = j;
  }
  free(e);
  return rc;
}

/* ---- reading ---- */

/* The triangles of the scene's meshes as corners (3 per triangle), scaled and moved. */
static int gather(const struct aiScene *sc, double scale, const double offset[3], corner **out,
                  size_t *nt, char *why, size_t len) {
  size_t n = 0;
  for (unsigned k = 0; k < sc->mNumMeshes; k++)
    n += sc->mMeshes[k]->mNumFaces;
  if (n == 0) return snprintf(why, len, "the file holds no triangles"), -1;
  if (n > UINT32_MAX / 3) return snprintf(why, len, "%zu triangles: too many", n), -1;
  corner *c = malloc(3 * n * sizeof *c);
  if (!c) return snprintf(why, len, "out of memory for %zu triangles", n), -1;
  size_t t = 0;
  for (unsigned k = 0; k < sc->mNumMeshes; k++) {
    const struct aiMesh *me = sc->mMeshes[k];
    for (unsigned f = 0; f < me->mNumFaces; f++) {
      const struct aiFace *fa = &me->mFaces[f];
      if (fa->mNumIndices != 3) {
        free(c);
        snprintf(why, len, "a face of %u vertices (expected triangles: a surface)",
                 fa->mNumIndices);
        return -1;
      }
      for (int q = 0; q < 3; q++) {
        const struct aiVector3D *p = &me->mVertices[fa->mIndices[q]];
        const double x[3] = {p->x, p->y, p->z};
        for (int d = 0; d < 3; d++)
          c[3 * t + q].x[d] = scale * x[d] + offset[d];
        c[3 * t + q].at = 3 * t + q;
      }
      t++;
    }
  }
  *out = c;
  *nt = t;
  return 0;
}

/* Welds the corners into vertices and triangles; drops triangles with a repeated vertex. */
static int weld(sph_mesh *m, corner *c, size_t nt, char *why, size_t len) {
  uint32_t *id = malloc(3 * nt * sizeof *id);
  m->v = malloc(9 * nt * sizeof *m->v);
  m->t = malloc(3 * nt * sizeof *m->t);
  if (!id || !m->v || !m->t) {
    free(id);
    return snprintf(why, len, "out of memory"), -1;
  }
  qsort(c, 3 * nt, sizeof *c, corner_order);
  size_t nv = 0;
  for (size_t i = 0; i < 3 * nt; i++) {
    if (i == 0 || memcmp(c[i].x, c[i - 1].x, sizeof c[i].x)) {
      memcpy(m->v + 3 * nv, c[i].x, sizeof c[i].x);
      nv++;
    }
    id[c[i].at] = (uint32_t)(nv - 1);
  }
  m->nv = nv;
  m->nt = 0;
  for (size_t k = 0; k < nt; k++) {
    const uint32_t a = id[3 * k], b = id[3 * k + 1], d = id[3 * k + 2];
    if (a == b || b == d || d == a) continue; /* no area: its edges pair with each other */
    m->t[3 * m->nt] = a, m->t[3 * m->nt + 1] = b, m->t[3 * m->nt + 2] = d;
    m->nt++;
  }
  free(id);
  if (m->nt == 0) return snprintf(why, len, "every triangle has two equal vertices"), -1;
  return 0;
}

static void measure(sph_mesh *m) {
  for (int d = 0; d < 3; d++)
    m->lo[d] = INFINITY, m->hi[d] = -INFINITY;
  for (size_t i = 0; i < m->nv; i++)
    for (int d = 0; d < 3; d++) {
      m->lo[d] = fmin(m->lo[d], m->v[3 * i + d]);
      m->hi[d] = fmax(m->hi[d], m->v[3 * i + d]);
    }
  double vol = 0.0; /* the divergence theorem: tetrahedra from the origin, 1/6 a . (b x c) */
  for (size_t k = 0; k < m->nt; k++) {
    const double *a = m->v + 3 * m->t[3 * k], *b = m->v + 3 * m->t[3 * k + 1],
                 *c = m->v + 3 * m->t[3 * k + 2];
    vol += a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
           a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  m->volume = vol / 6.0;
}

static size_t bin_of(const sph_mesh *m, int axis, double x) {
  const size_t n = axis ? m->by : m->bx;
  const double k = floor((x - m->lo[axis]) / m->w[axis]);
  return k < 0.0 ? 0 : k >= (double)n ? n - 1 : (size_t)k;
}

static int make_bins(sph_mesh *m, char *why, size_t len) {
  size_t side = (size_t)ceil(sqrt((double)m->nt));
  if (side > 2048) side = 2048;
  m->bx = m->by = side;
  for (int a = 0; a < 2; a++)
    m->w[a] = (m->hi[a] - m->lo[a]) / (double)side;
  m->start = calloc(side * side + 1, sizeof *m->start);
  if (!m->start) return snprintf(why, len, "out of memory"), -1;
  for (int pass = 0; pass < 2; pass++) {
    for (size_t k = 0; k < m->nt; k++) {
      double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
      for (int c = 0; c < 3; c++)
        for (int a = 0; a < 2; a++) {
          lo[a] = fmin(lo[a], m->v[3 * m->t[3 * k + c] + a]);
          hi[a] = fmax(hi[a], m->v[3 * m->t[3 * k + c] + a]);
        }
      for (size_t j = bin_of(m, 1, lo[1]); j <= bin_of(m, 1, hi[1]); j++)
        for (size_t i = bin_of(m, 0, lo[0]); i <= bin_of(m, 0, hi[0]); i++) {
          const size_t b = j * m->bx + i;
          if (pass == 0)
            m->start[b + 1]++;
          else
            m->item[m->start[b]++] = (uint32_t)k;
        }
    }
    if (pass == 0) {
      for (size_t b = 0; b < side * side; b++)
        m->start[b + 1] += m->start[b];
      if (!(m->item = malloc((m->start[side * side] + 1) * sizeof *m->item)))
        return snprintf(why, len, "out of memory"), -1;
    } else { /* the fill moved each start to the next bin's: move them back */
      for (size_t b = side * side; b > 0; b--)
        m->start[b] = m->start[b - 1];
      m->start[0] = 0;
    }
  }
  return 0;
}

int sph_mesh_read(const char *path, double scale, const double offset[3], sph_mesh **out, char *why,
                  size_t len) {
  *out = NULL;
  struct stat st;
  if (stat(path, &st) != 0) return snprintf(why, len, "cannot read %s", path), -1;
  if (st.st_size > SPH_MESH_MAX_BYTES)
    return snprintf(why, len, "%s is %lld bytes, more than the %ld read", path,
                    (long long)st.st_size, SPH_MESH_MAX_BYTES),
           -1;
  const struct aiScene *sc =
      aiImportFile(path, aiProcess_Triangulate | aiProcess_PreTransformVertices);
  if (!sc) return snprintf(why, len, "%s: %s", path, aiGetErrorString()), -1;
  corner *c = NULL;
  size_t nt = 0;
  sph_mesh *m = calloc(1, sizeof *m);
  int rc = m ? gather(sc, scale, offset, &c, &nt, why, len) : -1;
  aiReleaseImport(sc);
  if (!m) snprintf(why, len, "out of memory");
  if (!rc) rc = weld(m, c, nt, why, len);
  free(c);
  if (!rc) rc = check_edges(m, why, len);
  if (!rc) {
    measure(m);
    if (!(m->volume > 0.0)) {
      snprintf(why, len,
               "its volume is %g m3: the surface is turned inward or flat (expected each "
               "triangle's vertices anticlockwise seen from outside)",
               m->volume);
      rc = -1;
    }
  }
  if (!rc) rc = make_bins(m, why, len);
  if (rc) {
    sph_mesh_free(m);
    return -1;
  }
  *out = m;
  return 0;
}

/* ---- the inside ---- */

/* (v - u) x (p - u) in xy. */
static double orient(const double *u, const double *v, const double *p) {
  return (v[0] - u[0]) * (p[1] - u[1]) - (v[1] - u[1]) * (p[0] - u[0]);
}

/* The edge u->v's function at p, computed from its lower end (x, then y, then z) so that both
 * triangles of an edge see the same value, negated for the other direction. */
static double edge_fn(const double *u, const double *v, const double *p) {
  const int u_first = u[0] != v[0] ? u[0] < v[0] : u[1] != v[1] ? u[1] < v[1] : u[2] < v[2];
  return u_first ? orient(u, v, p) : -orient(v, u, p);
}

/* Whether a point on the anticlockwise edge u->v (in xy) belongs to its triangle: it would be
 * inside after a move right by e and up by a much smaller e'. */
static int owns(const double *u, const double *v) {
  return v[1] < u[1] || (v[1] == u[1] && v[0] > u[0]);
}

int sph_mesh_winding(const sph_mesh *m, const double x[3]) {
  if (!(x[0] >= m->lo[0] && x[0] <= m->hi[0] && x[1] >= m->lo[1] && x[1] <= m->hi[1] &&
        x[2] <= m->hi[2]))
    return 0;
  const size_t b = bin_of(m, 1, x[1]) * m->bx + bin_of(m, 0, x[0]);
  int wn = 0;
  for (size_t q = m->start[b]; q < m->start[b + 1]; q++) {
    const uint32_t *t = m->t + 3 * m->item[q];
    const double *a = m->v + 3 * t[0], *bb = m->v + 3 * t[1], *c = m->v + 3 * t[2];
    const double area = orient(a, bb, c);
    if (area == 0.0) continue; /* edge-on to the ray */
    const double s = area > 0.0 ? 1.0 : -1.0;
    const double *P[3] = {a, bb, c};
    double f[3];
    int in = 1;
    for (int e = 0; e < 3 && in; e++) {
      const double *u = P[e], *v = P[(e + 1) % 3];
      f[e] = s * edge_fn(u, v, x);
      in = f[e] > 0.0 || (f[e] == 0.0 && (s > 0 ? owns(u, v) : owns(v, u)));
    }
    if (!in) continue;
    /* the height of the triangle's plane above x: weights f (edge e faces vertex e + 2) */
    const double z = (f[1] * a[2] + f[2] * bb[2] + f[0] * c[2]) / (f[0] + f[1] + f[2]);
    if (z > x[2]) wn += area > 0.0 ? 1 : -1;
  }
  return wn;
}

/* The point of triangle (a, b, c) closest to p (Ericson 2005, Real-Time Collision Detection,
 * 5.1.5: by the Voronoi regions of its vertices, edges and face). */
static void closest_on_triangle(const double *p, const double *a, const double *b, const double *c,
                                double q[3]) {
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  for (int d = 0; d < 3; d++) {
    ab[d] = b[d] - a[d], ac[d] = c[d] - a[d], ap[d] = p[d] - a[d];
    bp[d] = p[d] - b[d], cp[d] = p[d] - c[d];
  }
#define DOT(u, v) ((u)[0] * (v)[0] + (u)[1] * (v)[1] + (u)[2] * (v)[2])
  const double d1 = DOT(ab, ap), d2 = DOT(ac, ap), d3 = DOT(ab, bp), d4 = DOT(ac, bp);
  const double d5 = DOT(ab, cp), d6 = DOT(ac, cp);
#undef DOT
  double v, w;
  if (d1 <= 0.0 && d2 <= 0.0) {
    memcpy(q, a, 3 * sizeof *q);
    return;
  }
  if (d3 >= 0.0 && d4 <= d3) {
    memcpy(q, b, 3 * sizeof *q);
    return;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    v = d1 / (d1 - d3);
    for (int d = 0; d < 3; d++)
      q[d] = a[d] + v * ab[d];
    return;
  }
  if (d6 >= 0.0 && d5 <= d6) {
    memcpy(q, c, 3 * sizeof *q);
    return;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    w = d2 / (d2 - d6);
    for (int d = 0; d < 3; d++)
      q[d] = a[d] + w * ac[d];
    return;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    for (int d = 0; d < 3; d++)
      q[d] = b[d] + w * (c[d] - b[d]);
    return;
  }
  const double den = 1.0 / (va + vb + vc);
  v = vb * den, w = vc * den;
  for (int d = 0; d < 3; d++)
    q[d] = a[d] + ab[d] * v + ac[d] * w;
}

double sph_mesh_nearest(const sph_mesh *m, const double x[3], double floor, double c[3],
                        double n[3]) {
  double best = INFINITY;
  for (size_t k = 0; k < m->nt; k++) {
    const double *a = m->v + 3 * m->t[3 * k], *b = m->v + 3 * m->t[3 * k + 1],
                 *cc = m->v + 3 * m->t[3 * k + 2];
    if (a[2] <= floor && b[2] <= floor && cc[2] <= floor) continue; /* on the floor */
    double q[3];
    closest_on_triangle(x, a, b, cc, q);
    const double d2 = (q[0] - x[0]) * (q[0] - x[0]) + (q[1] - x[1]) * (q[1] - x[1]) +
                      (q[2] - x[2]) * (q[2] - x[2]);
    if (!(d2 < best)) continue;
    best = d2;
    memcpy(c, q, 3 * sizeof *c);
    const double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
                 f[3] = {cc[0] - a[0], cc[1] - a[1], cc[2] - a[2]};
    n[0] = e[1] * f[2] - e[2] * f[1];
    n[1] = e[2] * f[0] - e[0] * f[2];
    n[2] = e[0] * f[1] - e[1] * f[0];
    const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int d = 0; d < 3; d++)
      n[d] = len > 0.0 ? n[d] / len : 0.0;
  }
  return sqrt(best);
}
