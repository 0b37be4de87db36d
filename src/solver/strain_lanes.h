/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * strain_lanes.h - the strain-rate pass for one particle (paper A eq.
 * 13-14), four or eight neighbours at a time, in the arithmetic flavour FL
 * (src/core/lanes.h), with LOOP_ATTR its attributes: the lane form of
 * strain_one in src/solver/forces.c. An ordinary C body included once per
 * flavour by src/solver/interact.h, with the same macros as
 * interact_row.h (LW, LA, LAOP, LACC, LMASK, LSET, LHOT, LCUT); it defines
 * strain_FL. No include guard on purpose.
 *
 * As the main pass's lane loop: the row is cut to the pairs inside the
 * support (LCUT), padded with its last pair, masked out; lane q sums
 * entries k = q, q + 4, ... and the lanes are added as (l0 + l1) + (l2 + l3),
 * the eight-lane flavour adding its lanes 0-3 before its lanes 4-7, so that
 * every flavour gives the same bits (tests/test_pair_terms.c). Fixed h only
 * (per-particle h runs strain_one).
 *
 * The sums, with V_j = m_j / rho_j and g = V_j grad_i W_ij, u = v_j - v_i
 * (V_j / r formed in one division: the bits differ from strain_one's):
 *   without the correction  2 u_x g_x, 2 u_y g_y, u_y g_x + u_x g_y, u . g;
 *   with it (Bonet and Lok 1999)  G = sum u (x) g and M = -sum (x_i - x_j) (x) g.
 * (in 3-D with the z terms after the others). The velocities are the
 * records' (sph_force_hot) or, with extrapolated wall velocities or mirror
 * particles, the arrays gv[axis].
 */

#define LT FL
#define LOP(name) SPH_PT_XGLUE(FL, name)
#define LTERM(name) SPH_PT_XGLUE(name, FL)

LOOP_ATTR void SPH_PT_XGLUE(strain,
                            FL)(const sph_force_hot *restrict hot, const sph_nlist *restrict l,
                                const sph_force_params *restrict fp, uint32_t *restrict nb,
                                uint32_t *restrict nbn, size_t i, const strain_opts *restrict o,
                                double *const *restrict eps, const unsigned F) {
  const size_t cnt = LCUT(hot, l, fp, i, nb, F);
  for (size_t k = cnt; k < cnt + SPH_KEEP_PAD - 1 && cnt > 0; k++)
    nb[k] = nb[cnt - 1]; /* padding lanes, for any lane loop that reads the row after */
  *nbn = (uint32_t)cnt;
  const int ghosts = o->gv != NULL, correct = o->l != NULL;
  const int gsums = !o->moment_only; /* with the correction: G too */
  const double *restrict gvx = ghosts ? o->gv[0] : NULL, *restrict gvy = ghosts ? o->gv[1] : NULL;
  SPH_IF3(const double *restrict gvz = ghosts ? o->gv[2] : NULL;)
  const sph_force_hot qi = hot[i];
  const double h0 = fp->h, inv_h0 = 1.0 / h0;
  const int wendland = fp->kernel == SPH_KERNEL_WENDLAND_C2;
  const double sigma0 = sph_kernel_sigma(fp->kernel, inv_h0);
  const LT xi = LOP(all)(qi.x), yi = LOP(all)(qi.y);
  const LT vxi = LOP(all)(ghosts ? gvx[i] : qi.vx), vyi = LOP(all)(ghosts ? gvy[i] : qi.vy);
  SPH_IF3(const LT zi = LOP(all)(qi.z), vzi = LOP(all)(ghosts ? gvz[i] : qi.vz);)
  const LT inv_h = LOP(all)(inv_h0), one = LOP(all)(1.0), two = LOP(all)(2.0);
  const LT sigma = LOP(all)(sigma0), sigma_h = LOP(all)(sigma0 * inv_h0);
  LANE_PERIODS(fp);
#define E_LANE(q, a) ((double)(q))
  const LT lane = LSET(E_LANE, 0), n = LOP(all)((double)cnt);
#undef E_LANE
  const LA azero = LAOP(all)(0.0);
  LA sxx = azero, sxy = azero, syy = azero, div = azero; /* without the correction */
  LA gxx = azero, gxy = azero, gyx = azero, gyy = azero; /* with it: G and M */
  LA mxx = azero, mxy = azero, myy = azero;
  SPH_IF3(LA sxz = azero, syz = azero, szz = azero; LA gxz = azero, gyz = azero, gzx = azero;
          LA gzy = azero, gzz = azero, mxz = azero, myz = azero, mzz = azero;)
  for (size_t k = 0; k < cnt; k += LW) {
    const uint32_t *restrict jk = nb + k; /* this iteration's neighbours */
#define E_HOT(q, field) hot[jk[q]].field
#define E_ARR(q, arr) arr[jk[q]]
    LHOT(g); /* the neighbours' packed records, g[H_field] */
    LT dx = LOP(sub)(xi, g[H_x]);
    if (F & F_PERIODIC) /* minimum image, as sep_x */
      dx = LANE_MIN_IMAGE(dx, per, hper, nper);
#if SPH_DIM == 2
    const LT dy = LOP(sub)(yi, g[H_y]);
    const LT r2 = LOP(add)(LOP(mul)(dx, dx), LOP(mul)(dy, dy));
#else
    LT dy = LOP(sub)(yi, g[H_y]), dz = LOP(sub)(zi, g[H_z]);
    if (F & F_PERIODIC) { /* y or z may be the axis that wraps */
      dy = LANE_MIN_IMAGE(dy, pery, hpery, npery);
      dz = LANE_MIN_IMAGE(dz, perz, hperz, nperz);
    }
    const LT r2 = LOP(add)(LOP(add)(LOP(mul)(dx, dx), LOP(mul)(dy, dy)), LOP(mul)(dz, dz));
#endif
    const LMASK in = LOP(lt)(LOP(add)(LOP(all)((double)k), lane), n);
    /* F_ij V_j in one division: the cubic spline's factor without its 1/r
     * (inv_r = 1) times m_j / (r rho_j); Wendland's F_ij has no 1/r */
    const LT r = LOP(sqrt)(r2);
    LT wij, f, vr;
    if (wendland) {
      LTERM(wendland_w_f)(r, one, inv_h, sigma, sigma_h, &wij, &f);
      vr = LOP(div)(g[H_m], g[H_rho]);
    } else {
      LTERM(cubic_w_f)(r, one, inv_h, sigma, sigma_h, &wij, &f);
      vr = LOP(div)(g[H_m], LOP(mul)(r, g[H_rho]));
    }
    (void)wij;
    f = LOP(and)(in, LOP(mul)(f, vr));
    const LT gx = LOP(mul)(f, dx), gy = LOP(mul)(f, dy); /* V_j grad_i W_ij */
    const LT vxj = ghosts ? LSET(E_ARR, gvx) : g[H_vx], vyj = ghosts ? LSET(E_ARR, gvy) : g[H_vy];
    const LT ux = LOP(sub)(vxj, vxi), uy = LOP(sub)(vyj, vyi); /* v_ji */
    SPH_IF3(const LT gz = LOP(mul)(f, dz); const LT vzj = ghosts ? LSET(E_ARR, gvz) : g[H_vz];
            const LT uz = LOP(sub)(vzj, vzi);)
    if (correct) {
      if (gsums) {
        LACC(gxx, LOP(mul)(ux, gx));
        LACC(gxy, LOP(mul)(ux, gy));
        LACC(gyx, LOP(mul)(uy, gx));
        LACC(gyy, LOP(mul)(uy, gy));
        SPH_IF3(LACC(gxz, LOP(mul)(ux, gz)); LACC(gyz, LOP(mul)(uy, gz));
                LACC(gzx, LOP(mul)(uz, gx)); LACC(gzy, LOP(mul)(uz, gy));
                LACC(gzz, LOP(mul)(uz, gz));)
      }
      LDEC(mxx, LOP(mul)(dx, gx));
      LDEC(mxy, LOP(mul)(dx, gy));
      LDEC(myy, LOP(mul)(dy, gy));
      SPH_IF3(LDEC(mxz, LOP(mul)(dx, gz)); LDEC(myz, LOP(mul)(dy, gz));
              LDEC(mzz, LOP(mul)(dz, gz));)
    } else {
      LACC(sxx, LOP(mul)(LOP(mul)(two, ux), gx));
      LACC(syy, LOP(mul)(LOP(mul)(two, uy), gy));
      LACC(sxy, LOP(add)(LOP(mul)(uy, gx), LOP(mul)(ux, gy)));
#if SPH_DIM == 2
      LACC(div, LOP(add)(LOP(mul)(ux, gx), LOP(mul)(uy, gy)));
#else
      LACC(szz, LOP(mul)(LOP(mul)(two, uz), gz));
      LACC(sxz, LOP(add)(LOP(mul)(uz, gx), LOP(mul)(ux, gz)));
      LACC(syz, LOP(add)(LOP(mul)(uz, gy), LOP(mul)(uy, gz)));
      LACC(div, LOP(add)(LOP(add)(LOP(mul)(ux, gx), LOP(mul)(uy, gy)), LOP(mul)(uz, gz)));
#endif
    }
#undef E_ARR
#undef E_HOT
  }
  double lv[4];
#define LANES_SUM(s) (LAOP(store)(lv, s), (lv[0] + lv[1]) + (lv[2] + lv[3]))
  double sums[STRAIN_SUMS] = {0.0}, gm[STRAIN_GM] = {0.0};
  if (correct) {
#if SPH_DIM == 2
    gm[0] = LANES_SUM(gxx), gm[1] = LANES_SUM(gxy), gm[2] = LANES_SUM(gyx);
    gm[3] = LANES_SUM(gyy), gm[4] = LANES_SUM(mxx), gm[5] = LANES_SUM(mxy);
    gm[6] = LANES_SUM(myy);
#else
    const LA gs[STRAIN_GM] = {gxx, gxy, gxz, gyx, gyy, gyz, gzx, gzy,
                              gzz, mxx, mxy, mxz, myy, myz, mzz};
    for (int k = 0; k < STRAIN_GM; k++)
      gm[k] = LANES_SUM(gs[k]);
#endif
  } else {
#if SPH_DIM == 2
    sums[0] = LANES_SUM(sxx), sums[1] = LANES_SUM(sxy), sums[2] = LANES_SUM(syy);
    sums[3] = LANES_SUM(div);
#else
    const LA ss[STRAIN_SUMS] = {sxx, sxy, sxz, syy, syz, szz, div};
    for (int k = 0; k < STRAIN_SUMS; k++)
      sums[k] = LANES_SUM(ss[k]);
#endif
  }
#undef LANES_SUM
  strain_finish(o, i, sums, gm, eps);
}

#undef LTERM
#undef LOP
#undef LT
