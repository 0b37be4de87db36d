/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * sphere_cover.c - whether a particle's sphere is covered by its
 * neighbours' balls (see sphere_cover.h for the rules and the argument).
 *
 * The arcs of a cap circle C_j: its points are
 *   v(phi) = c_j u_j + s_j (cos phi e1 + sin phi e2),  s_j = sin a_j,
 * with (e1, e2) an orthonormal pair normal to u_j fixed by u_j alone; cap k
 * holds v(phi) iff A cos(phi - psi) >= B with A = s_j |(e1.u_k, e2.u_k)|,
 * psi = atan2(e2.u_k, e1.u_k) and B = c_k - c_j (u_j.u_k): the whole circle
 * if B <= -A, nothing (or one point) if B >= A, else the closed arc
 * [psi - b, psi + b], cos b = B / A. Every number depends only on the pair
 * of caps, so the answer depends only on the set of caps, not their order.
 */
#include "config.h"

#include "physics/sphere_cover.h"

#include <math.h>

/* The interior certificate's covering radius rho (27.58 degrees, above the
 * 26 directions' 27.5693) as its cosine and sine. */
#define RHO_COS 0.8863652460618071  /* cos(27.58 deg) */
#define RHO_SIN 0.46298666349452466 /* sin(27.58 deg) */
/* The surface certificate's margin (as freesurface.c's ETA). */
#define ETA 1e-6

int sph_sphere_cap(const double d[3], double ri, double rj, sph_cap *cap) {
  const double dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (dist >= ri + rj) return SPH_DISC_NONE; /* apart, or tangent in one point */
  if (ri >= dist + rj) return SPH_DISC_NONE; /* inside the sphere (a duplicate too) */
  if (rj >= dist + ri) return SPH_DISC_FULL; /* contains the sphere */
  /* dist > 0 here; (ri - rj)(ri + rj) vanishes exactly for equal radii */
  const double c = 0.5 * (dist + (ri - rj) * (ri + rj) / dist) / ri;
  if (!(c < 1.0)) return SPH_DISC_NONE; /* a point at most */
  if (!(c > -1.0)) return SPH_DISC_FULL;
  for (int a = 0; a < 3; a++)
    cap->u[a] = d[a] / dist;
  cap->c = c;
  cap->s = sqrt((1.0 - c) * (1.0 + c));
  return SPH_DISC_ARC;
}

static double dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* An orthonormal pair (e1, e2) normal to the unit vector u: e1 = u x e_a
 * normalised, a the axis u is least along; e2 = u x e1. */
static void basis(const double u[3], double e1[3], double e2[3]) {
  int a = 0;
  for (int k = 1; k < 3; k++)
    if (fabs(u[k]) < fabs(u[a])) a = k;
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  double v[3] = {0.0, 0.0, 0.0}; /* u x e_a: (u_b e_c - u_c e_b) up to orientation */
  v[b] = u[c];
  v[c] = -u[b];
  const double n = sqrt(v[b] * v[b] + v[c] * v[c]);
  for (int k = 0; k < 3; k++)
    e1[k] = v[k] / n;
  e2[0] = u[1] * e1[2] - u[2] * e1[1];
  e2[1] = u[2] * e1[0] - u[0] * e1[2];
  e2[2] = u[0] * e1[1] - u[1] * e1[0];
}

int sph_sphere_caps_cover(const sph_cap *caps, size_t n, sph_arc *arcs) {
  if (n == 0) return 0;
  for (size_t j = 0; j < n; j++) {
    const sph_cap *cj = &caps[j];
    double e1[3], e2[3];
    basis(cj->u, e1, e2);
    const double sj = cj->s;
    size_t m = 0;
    int full = 0;
    for (size_t k = 0; k < n && !full; k++) {
      const sph_cap *ck = &caps[k];
      if (k == j ||
          (ck->c == cj->c && ck->u[0] == cj->u[0] && ck->u[1] == cj->u[1] && ck->u[2] == cj->u[2]))
        continue; /* itself, or a coincident cap: counts once */
      const double a1 = dot(e1, ck->u), a2 = dot(e2, ck->u);
      const double A = sj * sqrt(a1 * a1 + a2 * a2), B = ck->c - cj->c * dot(cj->u, ck->u);
      if (B <= -A) {
        full = 1; /* holds the whole circle */
      } else if (B < A) {
        const double b = acos(B / A), psi = atan2(a2, a1);
        arcs[m].lo = psi - b;
        arcs[m].hi = psi + b;
        m++;
      }
    }
    if (!full && !sph_freesurface_arcs_cover(arcs, m)) return 0;
  }
  return 1;
}

/* The 26 directions of the cube's faces, edges and corners: direction
 * (q0, q1, q2), q in {-1, 0, 1}, not all 0, has bit 9 (q0 + 1) + 3 (q1 + 1)
 * + (q2 + 1) (bit 13, the zero vector, is never set); its length is the
 * square root of the number of non-zero q. */
static const double inv_len[4] = {0.0, 1.0, 0.70710678118654752, 0.57735026918962576};

/* Whether the cap holds direction q (angle(u, r) <= a - rho, as cosines:
 * a - rho lies in [0, pi] once c < cos rho). */
static int holds(const sph_cap *cap, const int q[3]) {
  const int nz = (q[0] != 0) + (q[1] != 0) + (q[2] != 0);
  const double r = (q[0] * cap->u[0] + q[1] * cap->u[1] + q[2] * cap->u[2]) * inv_len[nz];
  return r >= cap->c * RHO_COS + cap->s * RHO_SIN;
}

unsigned long sph_sphere_dirs_held(const sph_cap *cap) {
  if (cap->c >= RHO_COS) return 0; /* narrower than rho */
  unsigned long held = 0;
  for (int b = 0; b < 27; b++) {
    const int q[3] = {b / 9 - 1, b / 3 % 3 - 1, b % 3 - 1};
    if (b != 13 && holds(cap, q)) held |= 1ul << b;
  }
  return held;
}

unsigned long sph_sphere_dir_near(const sph_cap *cap) {
  if (cap->c >= RHO_COS) return 0;
  /* the direction whose components follow u's signs where |u_a| is above
   * tan(22.5 degrees) of the largest (any direction would do: the test
   * below decides) */
  const double m = fmax(fabs(cap->u[0]), fmax(fabs(cap->u[1]), fabs(cap->u[2])));
  const double tau = 0.41421356237309505 * m;
  int q[3];
  for (int a = 0; a < 3; a++)
    q[a] = (cap->u[a] > tau) - (cap->u[a] < -tau);
  return holds(cap, q) ? 1ul << (9 * (q[0] + 1) + 3 * (q[1] + 1) + (q[2] + 1)) : 0ul;
}

int sph_sphere_dirs_cover(const sph_cap *caps, size_t n) {
  unsigned long held = 0;
  for (size_t k = 0; k < n && held != SPH_SPHERE_DIRS_ALL; k++)
    held |= sph_sphere_dirs_held(&caps[k]);
  return held == SPH_SPHERE_DIRS_ALL;
}

int sph_sphere_point_open(const double *d, const double *rj, size_t n, double ri,
                          const double q[3]) {
  for (size_t k = 0; k < n; k++) {
    const double e0 = q[0] - d[3 * k], e1 = q[1] - d[3 * k + 1], e2 = q[2] - d[3 * k + 2];
    if (!(e0 * e0 + e1 * e1 + e2 * e2 >= rj[k] * rj[k] + ETA * ri * (ri + rj[k]))) return 0;
  }
  return 1;
}
