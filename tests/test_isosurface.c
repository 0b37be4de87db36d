/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_isosurface.c - the free surface of a 3-D snapshot: the kernel sum
 * on a lattice (render/interp3d.h) and marching cubes through tetrahedra
 * (render/isosurface.h), on analytic fields (issue 38, point 7).
 *
 * 1. A linear field s = 1/2 + (z0 - z) / step: every vertex lies on the
 *    plane z = z0 (to float rounding), every normal is (0, 0, 1), the
 *    mesh's area is the lattice's cross-section exactly (to 1e-6) and its
 *    triangles face up.
 * 2. The kernel sum of a block of particles on a cubic lattice (spacing
 *    dx, volume dx^3, h = 1.3 dx, both kernels with their 3-D
 *    normalisation) is 1 within 1 % inside it; its level 1/2 over the top
 *    face (3 h away from the sides) lies within half a cell of the plane
 *    half a spacing above the top layer, the normals there within 0.01 of
 *    straight up.
 * 3. A ball of particles (radius 10 dx, the same lattice): the level 1/2
 *    of its kernel sum at a cell of dx/2 is a closed surface (every edge in
 *    exactly two triangles, once each way: no cracks, one orientation)
 *    whose normals point away from the centre, whose volume and area are
 *    those of the sphere of the particles' volume, 4/3 pi R^3 = N dx^3,
 *    within 2 % for both kernels.
 * 4. The same inputs give the same vertices and triangles, bit for bit.
 * 5. A slice (render/slice.h) through that block, between two lattice
 *    layers: it keeps the five layers within 2h of the plane, its discs
 *    show one, its view is the tank's section; the 3-D interpolation on
 *    the plane reproduces a linear field within 1e-3 inside (a thirtieth
 *    of its change over one spacing), the kernel sum is 1 within 1 %
 *    inside and passes 1/2 within a quarter spacing of the top face (the
 *    plane half a spacing above the top layer).
 */
#include "config.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "interp.h"
#include "interp3d.h"
#include "isosurface.h"
#include "slice.h"
#include "snapdata.h"
#include "testutil.h"

/* A cloud of fluid particles and its arrays. */
typedef struct cloud {
  size_t n;
  double *x, *y, *z, *h, *vol;
  unsigned char *wall;
} cloud;

static void cloud_add(cloud *c, double x, double y, double z, double h, double vol) {
  c->x = realloc(c->x, (c->n + 1) * sizeof *c->x);
  c->y = realloc(c->y, (c->n + 1) * sizeof *c->y);
  c->z = realloc(c->z, (c->n + 1) * sizeof *c->z);
  c->h = realloc(c->h, (c->n + 1) * sizeof *c->h);
  c->vol = realloc(c->vol, (c->n + 1) * sizeof *c->vol);
  c->wall = realloc(c->wall, (c->n + 1) * sizeof *c->wall);
  c->x[c->n] = x, c->y[c->n] = y, c->z[c->n] = z, c->h[c->n] = h, c->vol[c->n] = vol;
  c->wall[c->n] = 0;
  c->n++;
}

static void cloud_free(cloud *c) {
  free(c->x), free(c->y), free(c->z), free(c->h), free(c->vol), free(c->wall);
  memset(c, 0, sizeof *c);
}

static rinterp3_in input(const cloud *c, int kernel) {
  return (rinterp3_in){c->n, c->x, c->y, c->z, c->h, c->vol, NULL, c->wall, kernel};
}

/* The level 1/2 of the cloud's kernel sum at the given cell; also the sum
 * at the lattice point nearest `probe` (if not NULL). */
static int surface(const cloud *c, int kernel, double cell, rmesh *m, const double probe[3],
                   double *at_probe) {
  const rinterp3_in in = input(c, kernel);
  rgrid3 g;
  sph_error err = {""};
  if (rgrid3_fit(&in, cell, &g, &err) != 0) return -1;
  double *s = malloc(rgrid3_points(&g) * sizeof *s);
  int rc = rinterp3_sum(&in, &g, s, NULL, &err);
  if (!rc && probe) {
    int q[3];
    for (int a = 0; a < 3; a++)
      q[a] = (int)lround((probe[a] - g.origin[a]) / g.step);
    *at_probe = s[((size_t)q[2] * g.n[1] + q[1]) * g.n[0] + q[0]];
  }
  if (!rc) rc = rmesh_isosurface(&g, s, NULL, 0.5, m, &err);
  if (rc) printf("\n    %s", err.msg);
  free(s);
  return rc;
}

static void test_linear_field(void) {
  rgrid3 g = {{9, 7, 6}, {-1.0, 2.0, 0.5}, 0.25};
  const size_t np = rgrid3_points(&g);
  double *s = malloc(np * sizeof *s);
  const double z0 = 0.5 + 0.3 * 0.25 + 0.25; /* between lattice layers 1 and 2 */
  for (int k = 0; k < g.n[2]; k++)
    for (int j = 0; j < g.n[1]; j++)
      for (int i = 0; i < g.n[0]; i++)
        s[((size_t)k * g.n[1] + j) * g.n[0] + i] = 0.5 + (z0 - (g.origin[2] + k * g.step)) / g.step;
  rmesh m;
  sph_error err;
  CU_ASSERT_FATAL(rmesh_isosurface(&g, s, NULL, 0.5, &m, &err) == 0);
  double worst = 0.0, worst_n = 0.0;
  for (size_t v = 0; v < m.nv; v++) {
    worst = fmax(worst, fabs(m.p[3 * v + 2] - z0));
    worst_n = fmax(worst_n, fabs(m.normal[3 * v + 2] - 1.0) + fabs(m.normal[3 * v]) +
                                fabs(m.normal[3 * v + 1]));
  }
  const double area = rmesh_area(&m), want = 8 * 0.25 * 6 * 0.25;
  printf("\n    %zu vertices, %zu triangles, off the plane %.2g m, normals off %.2g, area %.9g "
         "(%.9g)",
         m.nv, m.nt, worst, worst_n, area, want);
  CU_ASSERT(m.nt > 0 && worst < 1e-6 && worst_n < 1e-6);
  CU_ASSERT(fabs(area - want) < 1e-6);
  size_t up = 0;
  for (size_t t = 0; t < m.nt; t++) {
    const float *a = m.p + 3 * m.tri[3 * t], *b = m.p + 3 * m.tri[3 * t + 1],
                *c = m.p + 3 * m.tri[3 * t + 2];
    up += (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 0.0;
  }
  CU_ASSERT_EQUAL(up, m.nt);
  rmesh_free(&m);
  free(s);
}

static void test_flat_surface(void) {
  const double dx = 0.01, h = 1.3 * dx;
  const int nx = 30, ny = 30, nz = 10;
  cloud c = {0};
  for (int k = 0; k < nz; k++)
    for (int j = 0; j < ny; j++)
      for (int i = 0; i < nx; i++)
        cloud_add(&c, (i + 0.5) * dx, (j + 0.5) * dx, (k + 0.5) * dx, h, dx * dx * dx);
  const double plane = nz * dx, cell = 0.5 * dx; /* half a spacing above the top layer */
  const int kernels[2] = {RKERNEL_CUBIC, RKERNEL_WENDLAND_C2};
  for (int kk = 0; kk < 2; kk++) {
    rmesh m;
    double inside = 0.0;
    const double mid[3] = {0.5 * nx * dx, 0.5 * ny * dx, 0.5 * nz * dx};
    CU_ASSERT_FATAL(surface(&c, kernels[kk], cell, &m, mid, &inside) == 0);
    size_t on_top = 0;
    double worst = 0.0, worst_n = 0.0;
    for (size_t v = 0; v < m.nv; v++) {
      const float *p = m.p + 3 * v;
      if (p[0] < 3 * h || p[0] > nx * dx - 3 * h || p[1] < 3 * h || p[1] > ny * dx - 3 * h ||
          p[2] < plane - 2 * h)
        continue;
      on_top++;
      worst = fmax(worst, fabs(p[2] - plane));
      worst_n = fmax(worst_n, 1.0 - m.normal[3 * v + 2]);
    }
    printf("\n    kernel %d: sum inside %.5f; %zu vertices over the top, off the plane by %.3g "
           "cells at most, normals off by %.2g",
           kernels[kk], inside, on_top, worst / cell, worst_n);
    CU_ASSERT(fabs(inside - 1.0) < 0.01);
    CU_ASSERT(on_top > 1000);
    CU_ASSERT(worst <= 0.5 * cell);
    CU_ASSERT(worst_n < 0.01);
    rmesh_free(&m);
  }
  cloud_free(&c);
}

static int cmp_u64(const void *a, const void *b) {
  const uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return x < y ? -1 : x > y;
}

/* Whether every directed edge appears once and its reverse once. */
static int closed_and_oriented(const rmesh *m) {
  const size_t ne = 3 * m->nt;
  uint64_t *e = malloc(ne * sizeof *e);
  for (size_t t = 0; t < m->nt; t++)
    for (int v = 0; v < 3; v++)
      e[3 * t + v] = (uint64_t)m->tri[3 * t + v] << 32 | m->tri[3 * t + (v + 1) % 3];
  qsort(e, ne, sizeof *e, cmp_u64);
  int ok = 1;
  for (size_t k = 0; ok && k < ne; k++) {
    if (k + 1 < ne && e[k] == e[k + 1]) ok = 0; /* an edge twice the same way */
    const uint64_t rev = (e[k] & 0xffffffffu) << 32 | e[k] >> 32;
    if (!bsearch(&rev, e, ne, sizeof *e, cmp_u64)) ok = 0; /* a crack */
  }
  free(e);
  return ok;
}

static void test_ball(void) {
  const double dx = 0.01, h = 1.3 * dx, radius = 10 * dx;
  cloud c = {0};
  for (int k = -12; k <= 12; k++)
    for (int j = -12; j <= 12; j++)
      for (int i = -12; i <= 12; i++)
        if ((i * i + j * j + k * k) * dx * dx <= radius * radius)
          cloud_add(&c, i * dx, j * dx, k * dx, h, dx * dx * dx);
  const double r_eff = cbrt(3.0 * (double)c.n * dx * dx * dx / (4.0 * M_PI));
  const double volume = 4.0 / 3.0 * M_PI * pow(r_eff, 3), area = 4.0 * M_PI * r_eff * r_eff;
  const int kernels[2] = {RKERNEL_CUBIC, RKERNEL_WENDLAND_C2};
  for (int kk = 0; kk < 2; kk++) {
    rmesh m, again;
    CU_ASSERT_FATAL(surface(&c, kernels[kk], 0.5 * dx, &m, NULL, NULL) == 0);
    const double ev = rmesh_volume(&m) / volume - 1.0, ea = rmesh_area(&m) / area - 1.0;
    double least = 1.0;
    for (size_t v = 0; v < m.nv; v++) {
      const float *p = m.p + 3 * v, *n = m.normal + 3 * v;
      const double r = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      least = fmin(least, (p[0] * n[0] + p[1] * n[1] + p[2] * n[2]) / r);
    }
    const int closed = closed_and_oriented(&m);
    printf("\n    kernel %d: %zu particles (R = %.4f m), %zu triangles, volume %+.2f %%, area "
           "%+.2f %%, closed %d, least cos(normal, radius) %.3f",
           kernels[kk], c.n, r_eff, m.nt, 100 * ev, 100 * ea, closed, least);
    CU_ASSERT(fabs(ev) < 0.02 && fabs(ea) < 0.02);
    CU_ASSERT(closed);
    CU_ASSERT(least > 0.9);
    CU_ASSERT_FATAL(surface(&c, kernels[kk], 0.5 * dx, &again, NULL, NULL) == 0);
    CU_ASSERT(again.nv == m.nv && again.nt == m.nt &&
              memcmp(again.p, m.p, 3 * m.nv * sizeof *m.p) == 0 &&
              memcmp(again.normal, m.normal, 3 * m.nv * sizeof *m.p) == 0 &&
              memcmp(again.tri, m.tri, 3 * m.nt * sizeof *m.tri) == 0);
    rmesh_free(&again);
    rmesh_free(&m);
  }
  cloud_free(&c);
}

/* A block of particles with a linear field, cut by the plane y = 0.153
 * (between lattice layers): the slice keeps the particles within 2h of
 * it, discs show one layer, and the 3-D interpolation on the plane
 * reproduces the field and puts the kernel sum's level 1/2 on the top
 * face. */
static void test_slice(void) {
  const double dx = 0.01, h = 1.3 * dx;
  const int nx = 30, ny = 30, nz = 12;
  rsnap s;
  memset(&s, 0, sizeof s);
  const size_t n = (size_t)nx * ny * nz;
  s.path = strdup("block.h5");
  s.dim = 3;
  s.n = n;
  s.dx = dx;
  s.x = malloc(n * sizeof *s.x), s.y = malloc(n * sizeof *s.y), s.z = malloc(n * sizeof *s.z);
  s.h = malloc(n * sizeof *s.h), s.vol = malloc(n * sizeof *s.vol);
  s.val = malloc(n * sizeof *s.val), s.wall = calloc(n, 1);
  s.kernel = RKERNEL_CUBIC;
  const double box[6] = {0, nx * dx, 0, ny * dx, 0, 0.2};
  memcpy(s.box, box, sizeof box);
  size_t i = 0;
  for (int k = 0; k < nz; k++)
    for (int j = 0; j < ny; j++)
      for (int q = 0; q < nx; q++, i++) {
        s.x[i] = (q + 0.5) * dx, s.y[i] = (j + 0.5) * dx, s.z[i] = (k + 0.5) * dx;
        s.h[i] = h, s.vol[i] = dx * dx * dx;
        s.val[i] = 1.0 + 2.0 * s.x[i] - 3.0 * s.z[i]; /* a linear field */
      }
  const rslice sl = {1, 0.153, 0.0};
  sph_error err = {""};
  CU_ASSERT_FATAL(rslice_apply(&sl, &s, &err) == 0);
  size_t shown = 0;
  for (size_t p = 0; p < s.n; p++)
    shown += fabs(s.off[p]) <= s.slab;
  printf("\n    kept %zu particles within 2h of the plane, %zu in the slab of dx", s.n, shown);
  CU_ASSERT_EQUAL(s.n, (size_t)nx * nz * 5); /* |y - 0.153| <= 2.6 dx: five layers */
  CU_ASSERT_EQUAL(shown, (size_t)nx * nz);   /* one layer within dx/2 */
  CU_ASSERT(s.view[0] == 0.0 && s.view[1] == nx * dx && s.view[2] == 0.0 && s.view[3] == 0.2);
  /* the plane's points: x across the block, z from the floor to above it */
  const int gx = 60, gz = 40;
  const double step = 0.5 * dx;
  const rinterp_grid g = {gx, gz, 0.0, gz * step, step};
  double *f = malloc(gx * gz * sizeof *f), *sf = malloc(gx * gz * sizeof *sf),
         *sw = malloc(gx * gz * sizeof *sw);
  const rinterp_in in = {s.n, s.x, s.y, s.h, s.vol, s.val, s.wall, s.kernel, s.off};
  CU_ASSERT_FATAL(rinterp_field(&in, &g, f, sf, sw, &err) == 0);
  double worst = 0.0, sum_in = NAN, level = NAN;
  for (int r = 0; r < gz; r++)
    for (int c = 0; c < gx; c++) {
      const double px = (c + 0.5) * step, pz = gz * step - (r + 0.5) * step;
      const double want = 1.0 + 2.0 * px - 3.0 * pz;
      if (px > 2 * h && px < nx * dx - 2 * h && pz > 2 * h && pz < nz * dx - 2 * h)
        worst = fmax(worst, fabs(f[r * gx + c] - want));
      if (c == gx / 2 && isnan(sum_in) && pz < 0.5 * nz * dx) sum_in = sf[r * gx + c];
      /* going down the middle column, where the sum first reaches 1/2 */
      if (c == gx / 2 && r > 0 && isnan(level) && sf[r * gx + c] >= 0.5) {
        const double a = sf[(r - 1) * gx + c], b = sf[r * gx + c];
        level = pz + step * (b - 0.5) / (b - a);
      }
    }
  printf("; the field off by %.2g at most inside (its change over dx: %.2g); kernel sum %.4f "
         "inside, 1/2 at %.4f dx from the top face",
         worst, 3.0 * dx, sum_in, (level - nz * dx) / dx);
  CU_ASSERT(worst < 1e-3);
  CU_ASSERT(fabs(sum_in - 1.0) < 0.01);
  CU_ASSERT(fabs(level - nz * dx) < 0.25 * dx);
  free(f), free(sf), free(sw);
  rsnap_free(&s);
}

static void test_limits(void) {
  cloud c = {0};
  cloud_add(&c, 0.0, 0.0, 0.0, 1.0, 1.0);
  const rinterp3_in in = input(&c, RKERNEL_CUBIC);
  rgrid3 g;
  sph_error err = {""};
  CU_ASSERT(rgrid3_fit(&in, 1e-4, &g, &err) != 0); /* 4e4^3 points */
  printf("\n    %s", err.msg);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "give a larger cell"));
  c.wall[0] = 1;
  CU_ASSERT(rgrid3_fit(&in, 0.5, &g, &err) != 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "no fluid particles"));
  cloud_free(&c);
}

int main(void) {
  CU_TestInfo tests[] = {{"a linear field: the plane, exactly", test_linear_field},
                         {"a block: the kernel sum and the flat top", test_flat_surface},
                         {"a ball: closed, outward, its volume and area", test_ball},
                         {"a slice: the 3-D interpolation on a plane", test_slice},
                         {"lattice limits", test_limits},
                         CU_TEST_INFO_NULL};
  return sph_test_main("isosurface", tests);
}
