/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * wall_fit_body.h - the fit of wall_velocity.c (walls/wall_velocity.h) in
 * one lane flavour: included by wall_velocity.c once per flavour, with
 *
 *   FIT_FL     the flavour (v2 or v8z, core/lanes.h): take_FL must be
 *              declared, and FL's operations are used
 *   FIT_ATTR   the attributes of an inlined function of the flavour
 *   FIT_ROWS   the attributes of its row loops (static, and the flavour's
 *              target where it needs one)
 *
 * Defines cubic_w_FL, sep_FL, fit_at_FL, velocity_rows_FL and mdbc_rows_FL. The
 * flavours differ in how many candidates they test and weigh at once,
 * lane for lane the same operations; the sums then take them one by one
 * in the same order: every flavour gives the same bits.
 */

#define FIT_GLUE_(a, b) a##_##b
#define FIT_GLUE(a, b) FIT_GLUE_(a, b)
#define FL(op) FIT_GLUE(FIT_FL, op)     /* FL(add): v2_add, v8z_add, ... */
#define FN(name) FIT_GLUE(name, FIT_FL) /* FN(fit_at): fit_at_v2, ... */

/* The cubic spline's W(r, h) in the flavour's lanes: lane for lane the
 * operations of sph_cubic_w_dw (core/kernel_shape.h, sph_shape_cubic), so
 * its bits. */
FIT_ATTR FIT_FL FN(cubic_w)(FIT_FL r, FIT_FL h) {
  const FIT_FL inv_h = FL(div)(FL(all)(1.0), h), q = FL(mul)(r, inv_h);
  FIT_FL sigma = FL(mul)(FL(mul)(FL(all)(sph_kernel_c(SPH_SHAPE_CUBIC_SPLINE)), inv_h), inv_h);
  SPH_IF3(sigma = FL(mul)(sigma, inv_h);)
  const FIT_FL near =
      FL(mul)(sigma, FL(add)(FL(sub)(FL(all)(1.0), FL(mul)(FL(mul)(FL(all)(1.5), q), q)),
                             FL(mul)(FL(mul)(FL(mul)(FL(all)(0.75), q), q), q)));
  const FIT_FL t = FL(sub)(FL(all)(2.0), q);
  const FIT_FL far = FL(mul)(FL(mul)(FL(mul)(FL(mul)(sigma, FL(all)(0.25)), t), t), t);
  return FL(sel)(FL(lt)(q, FL(all)(1.0)), near,
                 FL(sel)(FL(lt)(q, FL(all)(2.0)), far, FL(all)(0.0)));
}

/* The separation x_a - x_j along one axis in the lanes, the nearest image
 * over the period per (per NULL: none taken; a period of 0 leaves it as
 * it is, bit for bit). */
FIT_ATTR FIT_FL FN(sep)(double x, FIT_FL xj, const double *per, int a) {
  const FIT_FL d = FL(sub)(FL(all)(x), xj);
  if (!per) return d;
  return SPH_LANE_MIN_IMAGE(FIT_FL, d, FL(all)(per[a]), FL(all)(0.5 * per[a]),
                            FL(all)(-0.5 * per[a]));
}

/* The linear moving-least-squares fit, at the point x, of nf fields f[k]
 * (per-particle arrays) over the fluid particles within reach of it:
 * f ~ c0 + c . (x_j - x), weights W(x - x_j, h_j) (exact for a linear
 * field, also where the kernel is cut by the wall or the surface). Fills
 * fit[FIT_N k ..] with (c0, c) per field; where the fit's moment matrix is
 * near singular (fewer than SPH_DIM + 1 independent neighbours) the
 * Shepard average sum W f / sum W with a zero gradient. fmax (NULL, or a
 * value set by the caller) is raised to the largest value of the first
 * field among those particles, and top set to the offset x_j - x of the
 * first particle in the sums' order that holds it. Returns 0 when no fluid
 * particle reaches the point, else 1.
 *
 * A cell's candidates go FIT_CHUNK at a time through take (in the
 * flavour's lanes, lane for lane the scalar operations), then into the
 * sums one by one in their order: the bits of one scalar loop over them.
 * Always inlined, so that each caller's nf is a constant and the sums
 * stay in registers. */
FIT_ATTR int FN(fit_at)(const layout *g, const sph_wall_velocity_work *w, const double x[SPH_DIM],
                        const double *const *f, int nf, double *fit, double *fmax,
                        double top[SPH_DIM]) {
  long cells[SPH_DIM][3];
  int nc[3] = {1, 1, 1};
  for (int a = SPH_DIM - 1; a >= 0; a--) /* (the order of 2-D's first reach test: y, then x) */
    if ((nc[a] = cells_near(g, a, x[a], cells[a])) == 0) return 0;
  /* the squared gap along each axis between x and each cell: a cell whose
   * nearest point is beyond the support holds no particle the sums below
   * would take, so it is not visited (the same sums, in the same order) */
  double gap2[3][3] = {{0.0}};
  for (int a = 0; a < SPH_DIM; a++)
    for (int k = 0; k < nc[a]; k++)
      gap2[a][k] = cell_gap2(g, a, x[a], cells[a][k]);
  const double s2 = g->support * g->support;
  double per[SPH_DIM] = {0.0}; /* the period along each axis (0: none) */
  per[g->paxis] = g->period;
  /* linear MLS moments: A = sum W e e^T, b = sum W f e, e = (1, x_j - x), in
   * scalars (registers) */
  double sw = 0.0, a01 = 0.0, a02 = 0.0, a11 = 0.0, a12 = 0.0, a22 = 0.0;
  double sf[SPH_FIT_MAX] = {0.0}, b1[SPH_FIT_MAX] = {0.0}, b2[SPH_FIT_MAX] = {0.0};
  SPH_IF3(double a03 = 0.0, a13 = 0.0, a23 = 0.0, a33 = 0.0, b3[SPH_FIT_MAX] = {0.0};)
  uint32_t qs[FIT_SLOTS];
  double e[SPH_DIM][FIT_SLOTS], ws[FIT_SLOTS];
  for (int kz = 0; kz < nc[2]; kz++)
    for (int ky = 0; ky < nc[1]; ky++)
      for (int kx = 0; kx < nc[0]; kx++) {
        if (gap2[0][kx] + gap2[1][ky] + gap2[2][kz] >= s2) continue;
        size_t cell = (size_t)(cells[1][ky] * g->n[0] + cells[0][kx]);
        SPH_IF3(cell += (size_t)(cells[2][kz] * g->n[0] * g->n[1]);)
        for (size_t q = w->start[cell], end = w->start[cell + 1]; q < end; q += FIT_CHUNK) {
          const size_t qe = end - q > FIT_CHUNK ? q + FIT_CHUNK : end;
          const int k = g->period > 0.0 ? FN(take)(w, x, per, q, qe, qs, e, ws)
                                        : FN(take)(w, x, NULL, q, qe, qs, e, ws); /* (no image) */
          for (int t = 0; t < k; t++) {
            const double wj = ws[t], ex = e[0][t], ey = e[1][t];
            SPH_IF3(const double ez = e[2][t];)
            sw += wj;
            a01 += wj * ex;
            a02 += wj * ey;
            a11 += wj * ex * ex;
            a12 += wj * ex * ey;
            a22 += wj * ey * ey;
            SPH_IF3(a03 += wj * ez; a13 += wj * ex * ez; a23 += wj * ey * ez; a33 += wj * ez * ez;)
            const size_t j = w->idx[qs[t]];
            if (fmax && f[0][j] > *fmax) {
              *fmax = f[0][j];
              top[0] = ex, top[1] = ey;
              SPH_IF3(top[2] = ez;)
            }
            for (int m = 0; m < nf; m++) {
              const double fj = f[m][j];
              sf[m] += wj * fj;
              b1[m] += wj * ex * fj;
              b2[m] += wj * ey * fj;
              SPH_IF3(b3[m] += wj * ez * fj;)
            }
          }
        }
      }
  if (!(sw > 0.0)) return 0;
  for (int m = 0; m < nf; m++) {
    fit[FIT_N * m] = sf[m] / sw;
    for (int r = 1; r < FIT_N; r++)
      fit[FIT_N * m + r] = 0.0;
  }
#if SPH_DIM == 2
  const double A[FIT_N][FIT_N] = {{sw, a01, a02}, {a01, a11, a12}, {a02, a12, a22}};
#else
  const double A[FIT_N][FIT_N] = {
      {sw, a01, a02, a03}, {a01, a11, a12, a13}, {a02, a12, a22, a23}, {a03, a13, a23, a33}};
#endif
  double b[SPH_FIT_MAX][FIT_N];
  for (int m = 0; m < nf; m++) {
    b[m][0] = sf[m], b[m][1] = b1[m], b[m][2] = b2[m];
    SPH_IF3(b[m][3] = b3[m];)
  }
  solve_fit(A, (const double(*)[FIT_N])b, nf, fit);
  return 1;
}

/* The ghost velocities of the no-slip wall particles (sph_wall_velocity). */
FIT_ROWS void FN(velocity_rows)(const sph_particles *p, const layout *g,
                                const sph_wall_velocity_work *w, double *const *gv) {
  const double *const fields[SPH_DIM] = {SPH_XYZ(p->vx, p->vy, p->vz)};
  const long nl = (long)p->n;
#pragma omp parallel for schedule(dynamic, 256) if (nl > SPH_OMP_MIN)
  for (long li = 0; li < nl; li++) {
    const size_t i = (size_t)li;
    if (!(p->flags[i] & SPH_FLAG_NO_SLIP) || p->kind[i] != SPH_KIND_WALL) continue;
    double fit[FIT_N * SPH_DIM], x[SPH_DIM];
    mirror_point(p, i, x);
    if (FN(fit_at)(g, w, x, fields, SPH_DIM, fit, NULL, NULL))
      for (int a = 0; a < SPH_DIM; a++)
        gv[a][i] = 2.0 * p->vel[a][i] - fit[FIT_N * a];
  }
}

/* The densities of the mdbc wall particles (sph_wall_mdbc_density); fluid
 * 0 when there is fluid to fit, else 1. */
FIT_ROWS void FN(mdbc_rows)(sph_particles *p, const layout *g, const sph_wall_velocity_work *w,
                            int fluid, double rho0, const double head[SPH_DIM]) {
  const double *const fields[1] = {p->rho};
  const long nl = (long)p->n;
#pragma omp parallel for schedule(dynamic, 256) if (nl > SPH_OMP_MIN)
  for (long li = 0; li < nl; li++) {
    const size_t i = (size_t)li;
    if (!(p->flags[i] & SPH_FLAG_MDBC) || p->kind[i] != SPH_KIND_WALL) continue;
    double fit[FIT_N], x[SPH_DIM], top = -INFINITY, at[SPH_DIM] = {0.0}, rho = rho0;
    mirror_point(p, i, x);
    if (fluid == 0 && FN(fit_at)(g, w, x, fields, 1, fit, &top, at)) {
      /* the fit at the wall particle: rho_g - m . grad rho_g */
#if SPH_DIM == 2
      rho = fit[0] - (fit[1] * p->mx[i] + fit[2] * p->my[i]);
#else
      rho = fit[0] - (fit[1] * p->mx[i] + fit[2] * p->my[i] + fit[3] * p->mz[i]);
#endif
      /* no density the fluid around does not have, but for the weight of the fluid between
       * its densest particle (x + at, x the mirror point) and the wall particle (x - m):
       * head . ((x - m) - (x + at)) */
      double lift = 0.0;
      for (int a = 0; a < SPH_DIM; a++)
        lift -= head[a] * (p->mirror_offset[a][i] + at[a]);
      if (lift > 0.0) top += lift;
      if (rho > top) rho = top;
    }
    p->rho[i] = rho > rho0 ? rho : rho0; /* a wall pushes, never pulls */
  }
}

#undef FN
#undef FL
#undef FIT_GLUE
#undef FIT_GLUE_
