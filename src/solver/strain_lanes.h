/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * strain_lanes.h - the strain-rate pass for one particle (paper A eq.
 * 13-14), four or eight neighbours at a time, in the arithmetic flavour FL
 * (src/core/lanes.h), with LOOP_ATTR its attributes: the lane form of
 * strain_one in src/solver/forces.c. An ordinary C body included once per
 * flavour by src/solver/interact.h, with the same macros as
 * interact_row.h (LW, LA, LAOP, LACC, LMASK, LSET, LHOT); it defines
 * strain_FL. No include guard on purpose.
 *
 * As the main pass's lane loop: the row is cut to the pairs inside the
 * support (cut_row), padded with its last pair, masked out; lane q sums
 * entries k = q, q + 4, ... and the lanes are added as (l0 + l1) + (l2 + l3),
 * the eight-lane flavour adding its lanes 0-3 before its lanes 4-7, so that
 * every flavour gives the same bits (tests/test_pair_terms.c). Fixed h only
 * (per-particle h runs strain_one).
 *
 * The sums, with V_j = m_j / rho_j and g = V_j grad_i W_ij, u = v_j - v_i
 * (V_j / r formed in one division: the bits differ from strain_one's):
 *   without the correction  2 u_x g_x, 2 u_y g_y, u_y g_x + u_x g_y, u . g;
 *   with it (Bonet and Lok 1999)  G = sum u (x) g and M = -sum (x_i - x_j) (x) g.
 * The velocities are the records' (sph_force_hot) or, with extrapolated
 * wall velocities or mirror particles, the arrays gvx, gvy.
 */

#define LT FL
#define LOP(name) SPH_PT_XGLUE(FL, name)
#define LTERM(name) SPH_PT_XGLUE(name, FL)

LOOP_ATTR void SPH_PT_XGLUE(strain,
                            FL)(const sph_force_hot *restrict hot, const sph_nlist *restrict l,
                                const sph_force_params *restrict fp, uint32_t *restrict nb,
                                uint32_t *restrict nbn, size_t i, const strain_opts *restrict o,
                                double *restrict exx, double *restrict exy, double *restrict eyy,
                                const unsigned F) {
  const size_t cnt = cut_row(hot, l, fp, i, nb, F);
  for (size_t k = cnt; k < cnt + SPH_KEEP_PAD - 1 && cnt > 0; k++)
    nb[k] = nb[cnt - 1]; /* padding lanes, for any lane loop that reads the row after */
  *nbn = (uint32_t)cnt;
  const double *restrict gvx = o->gvx, *restrict gvy = o->gvy;
  const int ghosts = gvx != NULL, correct = o->lxx != NULL;
  const sph_force_hot qi = hot[i];
  const double h0 = fp->h, inv_h0 = 1.0 / h0;
  const int wendland = fp->kernel == SPH_KERNEL_WENDLAND_C2;
  const double sigma0 = sph_kernel_sigma(fp->kernel, inv_h0);
  const LT xi = LOP(all)(qi.x), yi = LOP(all)(qi.y);
  const LT vxi = LOP(all)(ghosts ? gvx[i] : qi.vx), vyi = LOP(all)(ghosts ? gvy[i] : qi.vy);
  const LT inv_h = LOP(all)(inv_h0), one = LOP(all)(1.0), two = LOP(all)(2.0);
  const LT sigma = LOP(all)(sigma0), sigma_h = LOP(all)(sigma0 * inv_h0);
  const LT per = LOP(all)(fp->period), hper = LOP(all)(0.5 * fp->period);
  const LT nper = LOP(all)(-0.5 * fp->period);
#define E_LANE(q, a) ((double)(q))
  const LT lane = LSET(E_LANE, 0), n = LOP(all)((double)cnt);
#undef E_LANE
  const LA azero = LAOP(all)(0.0);
  LA sxx = azero, sxy = azero, syy = azero, div = azero; /* without the correction */
  LA gxx = azero, gxy = azero, gyx = azero, gyy = azero; /* with it: G and M */
  LA mxx = azero, mxy = azero, myy = azero;
  for (size_t k = 0; k < cnt; k += LW) {
    const uint32_t *restrict jk = nb + k; /* this iteration's neighbours */
#define E_HOT(q, field) hot[jk[q]].field
#define E_ARR(q, arr) arr[jk[q]]
    LHOT(g); /* the neighbours' packed records, g[H_field] */
    LT dx = LOP(sub)(xi, g[H_x]);
    if (F & F_PERIODIC) /* minimum image, as sep_x */
      dx = LOP(sel)(LOP(lt)(hper, dx), LOP(sub)(dx, per),
                    LOP(sel)(LOP(lt)(dx, nper), LOP(add)(dx, per), dx));
    const LT dy = LOP(sub)(yi, g[H_y]);
    const LT r2 = LOP(add)(LOP(mul)(dx, dx), LOP(mul)(dy, dy));
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
    if (correct) {
      LACC(gxx, LOP(mul)(ux, gx));
      LACC(gxy, LOP(mul)(ux, gy));
      LACC(gyx, LOP(mul)(uy, gx));
      LACC(gyy, LOP(mul)(uy, gy));
      LDEC(mxx, LOP(mul)(dx, gx));
      LDEC(mxy, LOP(mul)(dx, gy));
      LDEC(myy, LOP(mul)(dy, gy));
    } else {
      LACC(sxx, LOP(mul)(LOP(mul)(two, ux), gx));
      LACC(syy, LOP(mul)(LOP(mul)(two, uy), gy));
      LACC(sxy, LOP(add)(LOP(mul)(uy, gx), LOP(mul)(ux, gy)));
      LACC(div, LOP(add)(LOP(mul)(ux, gx), LOP(mul)(uy, gy)));
    }
#undef E_ARR
#undef E_HOT
  }
  double lv[4];
#define LANES_SUM(s) (LAOP(store)(lv, s), (lv[0] + lv[1]) + (lv[2] + lv[3]))
  double sums[4] = {0.0, 0.0, 0.0, 0.0}, gm[7] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  if (correct) {
    gm[0] = LANES_SUM(gxx), gm[1] = LANES_SUM(gxy), gm[2] = LANES_SUM(gyx);
    gm[3] = LANES_SUM(gyy), gm[4] = LANES_SUM(mxx), gm[5] = LANES_SUM(mxy);
    gm[6] = LANES_SUM(myy);
  } else {
    sums[0] = LANES_SUM(sxx), sums[1] = LANES_SUM(sxy), sums[2] = LANES_SUM(syy);
    sums[3] = LANES_SUM(div);
  }
#undef LANES_SUM
  strain_finish(o, i, sums, gm, exx, exy, eyy);
}

#undef LTERM
#undef LOP
#undef LT
