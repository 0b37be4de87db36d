/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * obstacles.c - obstacle boxes from a snapshot's parameters, and their
 * faces as a mesh (see obstacles.h).
 */
#include "config.h"

#include "obstacles.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The range of key (e.g. "geometry.obstacles[0].x") in the listing. */
static int range_of(const char *parameters, const char *key, double *lo, double *hi) {
  const size_t n = strlen(key);
  for (const char *p = strstr(parameters, key); p; p = strstr(p + 1, key)) {
    if ((p != parameters && p[-1] != '\n') || strncmp(p + n, ": [", 3) != 0) continue;
    return sscanf(p + n + 3, "%lf , %lf ]", lo, hi) == 2 && *lo < *hi ? 0 : -1;
  }
  return -1;
}

/* The box of prefix.x, prefix.y and prefix.z. */
static int box_of(const char *parameters, const char *prefix, double box[6]) {
  static const char axes[3] = {'x', 'y', 'z'};
  for (int a = 0; a < 3; a++) {
    char key[80];
    snprintf(key, sizeof key, "%s.%c", prefix, axes[a]);
    if (range_of(parameters, key, &box[2 * a], &box[2 * a + 1]) != 0) return -1;
  }
  return 0;
}

int robstacles_parse(const char *parameters, double (*box)[6], int max) {
  int n = 0;
  for (; parameters && n < max; n++) {
    char prefix[64];
    snprintf(prefix, sizeof prefix, "geometry.obstacles[%d]", n);
    if (box_of(parameters, prefix, box[n]) != 0) break;
  }
  return n;
}

int robstacles_tank(const char *parameters, double box[6]) {
  return parameters ? box_of(parameters, "geometry.tank", box) : -1;
}

int robstacles_mesh(const double (*box)[6], int n, rmesh *m, sph_error *err) {
  memset(m, 0, sizeof *m);
  const size_t nv = 24 * (size_t)(n > 0 ? n : 0), nt = 12 * (size_t)(n > 0 ? n : 0);
  m->p = malloc((nv ? nv : 1) * 3 * sizeof *m->p);
  m->normal = malloc((nv ? nv : 1) * 3 * sizeof *m->normal);
  m->tri = malloc((nt ? nt : 1) * 3 * sizeof *m->tri);
  if (!m->p || !m->normal || !m->tri) {
    rmesh_free(m);
    return sph_error_set(err, "out of memory for %d obstacles", n);
  }
  for (int b = 0; b < n; b++)
    for (int face = 0; face < 6; face++) {
      /* the face normal to axis a at its low (side 0) or high end */
      const int a = face / 2, side = face % 2, u = (a + 1) % 3, v = (a + 2) % 3;
      const uint32_t first = (uint32_t)m->nv;
      for (int c = 0; c < 4; c++) {
        /* corners counter-clockwise about +a: (u, v) = 00, 10, 11, 01 */
        const int cu = c == 1 || c == 2, cv = c >= 2;
        float *p = m->p + 3 * m->nv, *nn = m->normal + 3 * m->nv;
        p[a] = (float)box[b][2 * a + side];
        p[u] = (float)box[b][2 * u + cu];
        p[v] = (float)box[b][2 * v + cv];
        nn[0] = nn[1] = nn[2] = 0.0f;
        nn[a] = side ? 1.0f : -1.0f;
        m->nv++;
      }
      static const int ccw[6] = {0, 1, 2, 0, 2, 3}, cw[6] = {0, 2, 1, 0, 3, 2};
      for (int k = 0; k < 6; k++)
        m->tri[3 * m->nt + k] = first + (uint32_t)(side ? ccw[k] : cw[k]);
      m->nt += 2;
    }
  return 0;
}
