/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * interact_row.h - the main pass for one particle i over its neighbour
 * row, written once for every arithmetic flavour FL of src/core/lanes.h:
 * v1 (the scalar loop, one pair at a time), v4e and v4x (four pairs at a
 * time) and v8z (eight), with LOOP_ATTR their attributes. An ordinary C
 * body included once per flavour by src/solver/interact.h (templates by
 * include, as SWIFT's runner_doiact_functions_hydro.h); it defines
 * interact_FL. No include guard on purpose. Which term applies to which
 * pair (fluid and wall rows, mirror, repulsive and free-slip neighbours,
 * the ledger's passive heat) is spelled out here and nowhere else; the
 * terms themselves are src/physics/pair_terms.h.
 *
 * The row: with per-particle h (the scalar loop only, F_VARH) the whole
 * neighbour row, each pair outside its own support skipped; otherwise the
 * row cut to the pairs inside the support (cut_row; with the stress terms
 * or the corrected gradient the strain-rate pass has cut it already and
 * kept it, w->keep), padded to
 * a multiple of the width with its last pair, masked out. Each of the
 * lanes takes entries k, k + 4, ... and keeps its own partial sums, added
 * as (l0 + l1) + (l2 + l3) at the end (the scalar loop: one sum, in row
 * order): a fixed order, whatever the machine's vector width. Each lane
 * does, pair for pair, the operations of the scalar loop. Mirror
 * particles (their no-slip velocity in the viscous terms) run the scalar
 * loop only.
 *
 * With the energy ledger (F_LEDGER) the loop also sums each particle's
 * half of the pairs' heat (a dynamic wall particle its half of the heat of
 * its pairs with fluid), the power of wall particles' forces on fluid and
 * the walls' force: the neighbour's kind is read as a mask (fm_j > 0:
 * fluid), a repulsive wall or mirror neighbour takes no heat (passive_heat;
 * kind and flag read only where such walls exist). On a free-slip wall the
 * pressure and artificial-viscosity force of a fluid-wall pair act along
 * the wall particle's normal (normal_part), and the artificial viscosity
 * reads the normal relative velocity (normal_vdotr); the wall flags are
 * read only where such walls exist. A masked term is +0 or -0, which
 * leaves a sum as it is (a sum that starts at +0 is never -0 under
 * round-to-nearest), so masking a pair and skipping it give the same bits.
 *
 * The eight-lane flavour (v8z, AVX-512) evaluates the pairs k .. k + 7 at
 * once and adds them into four-lane sums, first its lanes 0-3 (entries
 * k .. k + 3), then its lanes 4-7 (k + 4 .. k + 7): each four-lane sum sees
 * the same terms in the same order as in the four-lane loop, so the two
 * give the same bits (tests/test_pair_terms.c).
 *
 * Set by the includer: LW the lane count (1, 4 or 8), LA the type of the
 * sums with LAOP(name) its operations, LACC(s, t) adding the LW-lane terms
 * t into the sums s, LDEC(s, t) subtracting them, LAMAX(s, t) the same for
 * the max, LMASK the mask type, LSET(E, a) the vector of E(q, a) for
 * q = 0 .. LW - 1 (E_ARR(q, arr) gives arr[j] of the iteration's q-th
 * neighbour j), LHOT(g) (LW > 1) the declaration of g[8], the fields of
 * this iteration's neighbours' records (sph_force_hot) by place H_field,
 * LCUT the row cut (cut_row, or cut_row_v4x in the AVX2 and AVX-512
 * flavours: the same pairs, four entries at a time).
 * Fc, a literal at every call, is the term set the loop is compiled for,
 * or F_RUNTIME (interact.h, F_LITERAL): the bits it does not fix come
 * from the pass's term set.
 */

#define LT FL
#define LOP(name) SPH_PT_XGLUE(FL, name)
#define LTERM(name) SPH_PT_XGLUE(name, FL)
#define LVEC SPH_PT_XGLUE(vec, FL) /* vectors and symmetric tensors of the pair terms */
#define LSYM SPH_PT_XGLUE(sym, FL)

/* Returns sigma_i, the step rule's max_j |h v_ij.r_ij / r_ij^2| (0 for a
 * row that sums nothing). */
LOOP_ATTR double SPH_PT_XGLUE(interact, FL)(sph_particles *restrict p, const sph_nlist *restrict l,
                                            const sph_force_params *restrict fp,
                                            sph_force_work *restrict w, size_t i,
                                            const unsigned Fc) {
  const unsigned F = SPH_TERMS(Fc, F_LITERAL(Fc), w->terms);
  const sph_force_hot *restrict hot = w->hot;
  const double *restrict sxx = w->sxx, *restrict sxy = w->sxy, *restrict syy = w->syy;
  SPH_IF3(const double *restrict sxz = w->sxz, *restrict syz = w->syz, *restrict szz = w->szz;)
  const int32_t *restrict kind = p->kind;
  /* no rates: mirror particles, repulsive wall particles, adami wall particles (whose density
   * and pressure are the fluid's, walls/adami.h) */
  if (kind[i] == SPH_KIND_MIRROR || (p->flags[i] & (SPH_FLAG_REPULSIVE | SPH_FLAG_ADAMI))) {
    p->drho[i] = p->ax[i] = p->ay[i] = 0.0;
    SPH_IF3(p->az[i] = 0.0;)
    if (F & F_LEDGER) p->du[i] = w->wpow[i] = w->wfx[i] = w->wfy[i] = 0.0;
    SPH_IF3(if (F & F_LEDGER) w->wfz[i] = 0.0;)
    if ((F & F_DDIFF) && (F & F_LEDGER)) w->dd[i] = 0.0;
    return 0.0;
  }
  const uint32_t *restrict nb;
  size_t cnt;
  if (F & F_VARH) { /* (the scalar loop only) the whole row: the support is per pair */
    nb = sph_nlist_row(l, i, &cnt);
  } else if ((F & (F_STRESS | F_CGRAD)) && w->keep_valid) { /* the strain-rate pass's cut row,
                                                              padded */
    nb = w->keep + sph_nlist_slot(l, i) + SPH_KEEP_PAD * i;
    cnt = w->keepn[i];
  } else {
    uint32_t *restrict cut = w->rows + (size_t)sph_thread() * w->rows_stride;
    /* the cut compiled for both: periodic or not (a predicted branch per row) */
    cnt = (F & F_PERIODIC) ? LCUT(hot, l, fp, i, cut, F_PERIODIC) : LCUT(hot, l, fp, i, cut, 0);
    for (size_t k = cnt; k < cnt + LW - 1 && cnt > 0; k++)
      cut[k] = cut[cnt - 1]; /* padding lanes */
    nb = cut;
  }
  const sph_force_hot qi = hot[i];
  const int fluid = kind[i] == SPH_KIND_FLUID;
#if LW == 1
  const double *restrict h = p->h; /* per-particle h */
  const int mirror = fp->mirror;   /* mirror particles' no-slip velocity */
#endif
  const double h0 = fp->h, inv_h0 = 1.0 / h0;
  const int wendland = fp->kernel == SPH_KERNEL_WENDLAND_C2;
  const double sigma0 = sph_kernel_sigma(fp->kernel, inv_h0);
  const LT xi = LOP(all)(qi.x), yi = LOP(all)(qi.y), vxi = LOP(all)(qi.vx), vyi = LOP(all)(qi.vy);
  SPH_IF3(const LT zi = LOP(all)(qi.z), vzi = LOP(all)(qi.vz);)
  const LT rhoi = LOP(all)(qi.rho), pri = LOP(all)(qi.prho2), ci = LOP(all)(qi.cs);
  const LT hh = LOP(all)(h0), inv_h = LOP(all)(inv_h0), one = LOP(all)(1.0);
  const LT zero = LOP(all)(0.0);
  const LT sigma = LOP(all)(sigma0), sigma_h = LOP(all)(sigma0 * inv_h0);
  LANE_PERIODS(fp);
  const double eta = fp->eta * h0;
  const LT eta2 = LOP(all)(eta * eta), nalpha = LOP(all)(-fp->alpha), beta = LOP(all)(fp->beta);
  const LT nu4 = LOP(all)(4.0 * fp->mu / fp->eos.rho0);
  /* the Riemann pressure: p_i, rho0 c0 and eta / c0 */
  const int riem = (F & F_RIEMANN) != 0; /* (the constants only where it is on) */
  const LT pi = LOP(all)(riem ? qi.prho2 * qi.rho * qi.rho : 0.0);
  const LT rz0 = LOP(all)(riem ? fp->eos.rho0 * fp->eos.c0 : 0.0);
  const LT rkc = LOP(all)(riem ? fp->riemann_limiter / fp->eos.c0 : 0.0);
  const LT rinv_z0 = LOP(all)(riem ? 1.0 / (fp->eos.rho0 * fp->eos.c0) : 0.0);
  const LT hgx = LOP(all)(riem ? fp->eos.rho0 * fp->gx : 0.0);
  const LT hgy = LOP(all)(riem ? fp->eos.rho0 * fp->gy : 0.0);
  SPH_IF3(const LT hgz = LOP(all)(riem ? fp->eos.rho0 * fp->gz : 0.0);)
#if LW > 1
#define E_LANE(q, a) ((double)(q))
  const LT lane = LSET(E_LANE, 0), n = LOP(all)((double)cnt);
#undef E_LANE
#endif
  const LA azero = LAOP(all)(0.0);
  LA drho = azero, ax = azero, ay = azero, xs = azero, ys = azero, sig = azero, dd = azero;
  LA du = azero, wpow = azero, wfx = azero, wfy = azero; /* energy and momentum ledger */
  LA rd = azero;                                         /* the Riemann continuity term */
  SPH_IF3(LA az = azero, zs = azero, wfz = azero;)
  const uint8_t *restrict flags = p->flags;
  /* neighbours that take no heat: repulsive wall particles, mirror particles and adami wall
   * particles */
  const int passive = (F & F_LEDGER) && (fp->repulsive || fp->mirror || fp->adami);
  /* adami walls in the viscous terms of a fluid row: a wall neighbour's no-slip velocity
   * (w->gv), none on a free-slip one (walls/adami.h) */
  const int adami_v = fp->adami && fluid && (F & (F_AV | F_MORRIS | F_STRESS));
  const double *const *restrict agv = (const double *const *)w->gv;
  /* free-slip walls: a predicted branch per iteration (i's own flag for a wall i) */
  const int slip = fp->free_slip;
  const int slip_i = slip && kind[i] == SPH_KIND_WALL && (flags[i] & SPH_FLAG_FREE_SLIP);
  /* the Riemann pressure's closing speed on walls with a normal (mdbc, no-slip and free-slip
   * walls: SPH_WALL_NORMAL): the normal part of v_ij, so that the wall's dissipation stops the
   * fluid going through it but does not brake it along it (no-slip is the viscous terms') */
  const int rnorm = (F & F_RIEMANN) && sph_force_wall_normals(fp) &&
                    (kind[i] != SPH_KIND_FLUID || w->nwall[i]); /* a row that meets one */
  const int rnorm_i = rnorm && kind[i] == SPH_KIND_WALL && (flags[i] & SPH_WALL_NORMAL);
  const double *restrict ddcx = w->ddcx, *restrict ddcy = w->ddcy, *restrict ddm = w->ddm;
  SPH_IF3(const double *restrict ddcz = w->ddcz;)
  const double *restrict fm = w->fm; /* m_j of fluid j, 0 for the others */
  /* then ddm = fm, which diffusion.c does not fill: only fluid diffuses, all of it */
  const int mdd_is_mx = sph_diffusion_mass_is_fm(fp, (F & F_XSPH) != 0);
  const int diffuses = (F & F_DDIFF) && (mdd_is_mx ? fm : ddm)[i] != 0.0; /* diffusion.h */
  /* c_j = c_i at every particle but with antuono (diffusion.c: then w->ddc0): the same sums
   * without reading c_j */
  const int dd_uniform = fp->diffusion != SPH_DIFFUSION_ANTUONO;
  const LT cxi = LOP(all)((F & F_DDIFF) ? (dd_uniform ? w->ddc0[0] : ddcx[i]) : 0.0);
  const LT cyi = LOP(all)((F & F_DDIFF) ? (dd_uniform ? w->ddc0[1] : ddcy[i]) : 0.0);
  SPH_IF3(const LT czi = LOP(all)((F & F_DDIFF) ? (dd_uniform ? w->ddc0[2] : ddcz[i]) : 0.0);)
  const LT cxx = LOP(add)(cxi, cxi), cyy = LOP(add)(cyi, cyi);
  SPH_IF3(const LT czz = LOP(add)(czi, czi);)
  for (size_t k = 0; k < cnt; k += LW) {
    const uint32_t *restrict jk = nb + k; /* this iteration's neighbours */
#define E_HOT(q, field) hot[jk[q]].field
#define E_ARR(q, arr) arr[jk[q]]
#if LW == 1
    const sph_force_hot *restrict qj = &hot[jk[0]]; /* read field by field, as needed */
#define GATHER(field) qj->field
#else
    LHOT(g); /* the neighbours' packed records, g[H_field] */
#define GATHER(field) g[H_##field]
#endif
    LT dx = LOP(sub)(xi, GATHER(x));
    if (F & F_PERIODIC) /* minimum image, as sep_x */
      dx = LANE_MIN_IMAGE(dx, per, hper, nper);
#if SPH_DIM == 2
    const LT dy = LOP(sub)(yi, GATHER(y));
    const LT r2 = LOP(add)(LOP(mul)(dx, dx), LOP(mul)(dy, dy));
#else
    LT dy = LOP(sub)(yi, GATHER(y)), dz = LOP(sub)(zi, GATHER(z));
    if (F & F_PERIODIC) { /* y or z may be the axis that wraps */
      dy = LANE_MIN_IMAGE(dy, pery, hpery, npery);
      dz = LANE_MIN_IMAGE(dz, perz, hperz, nperz);
    }
    const LT r2 = LOP(add)(LOP(add)(LOP(mul)(dx, dx), LOP(mul)(dy, dy)), LOP(mul)(dz, dz));
#endif
    /* the pair's smoothing length and what follows from it */
    LT hij = hh, inv_hij = inv_h, sig_ij = sigma, sig_h_ij = sigma_h, eta2_ij = eta2;
#if LW == 1
    if (F & F_VARH) { /* per-particle h: h_ij the pair's mean; outside its support, skip */
      const double hm = 0.5 * (h[i] + h[jk[0]]);
      if (r2 >= 4.0 * hm * hm || r2 == 0.0) continue;
      const double e = fp->eta * hm;
      hij = hm;
      inv_hij = 1.0 / hm;
      sig_ij = sph_kernel_sigma(fp->kernel, inv_hij);
      sig_h_ij = sig_ij * inv_hij;
      eta2_ij = e * e;
    }
#endif
    /* the padding lanes past the row's end repeat its last pair, masked out */
#if LW == 1
    const LMASK in = 1; /* no padding */
#else
    const LMASK in = LOP(lt)(LOP(add)(LOP(all)((double)k), lane), n);
#endif
    /* 1/r2 and sqrt(r2) side by side: a shorter chain than 1/sqrt(r2) */
    const LT inv_r2 = LOP(div)(one, r2), r = LOP(sqrt)(r2), inv_r = LOP(mul)(r, inv_r2);
    LT wij, f;
    if (wendland) /* the same for every pair: a branch the processor predicts */
      LTERM(wendland_w_f)(r, inv_r, inv_hij, sig_ij, sig_h_ij, &wij, &f);
    else
      LTERM(cubic_w_f)(r, inv_r, inv_hij, sig_ij, sig_h_ij, &wij, &f);
    wij = LOP(and)(in, wij);
    f = LOP(and)(in, f);
    const LT gx = LOP(mul)(f, dx), gy = LOP(mul)(f, dy);
    const LT dvx = LOP(sub)(vxi, GATHER(vx)), dvy = LOP(sub)(vyi, GATHER(vy));
    SPH_IF3(const LT gz = LOP(mul)(f, dz), dvz = LOP(sub)(vzi, GATHER(vz));)
    const LT mj = GATHER(m);
    const LVEC rv = {{SPH_XYZ(dx, dy, dz)}}, gw = {{SPH_XYZ(gx, gy, gz)}}; /* r_ij, grad_i W_ij */
    const LVEC dv = {{SPH_XYZ(dvx, dvy, dvz)}};                            /* v_ij */
    /* the gradient of the pressure, its Pi_ij and the continuity: with F_CGRAD the pair's
     * corrected one, L_ij grad_i W_ij (forces.h); the viscous terms keep grad_i W_ij */
    LVEC cg = gw;
    if (F & F_CGRAD) {
#define E_L(q, k) w->l[k][jk[q]]
#if SPH_DIM == 2
      const LSYM li = {{LOP(all)(w->lxx[i]), LOP(all)(w->lxy[i]), LOP(all)(w->lyy[i])}};
      const LSYM lj = {{LSET(E_L, SPH_XX), LSET(E_L, SPH_XY), LSET(E_L, SPH_YY)}};
#else
      const LSYM li = {{LOP(all)(w->lxx[i]), LOP(all)(w->lxy[i]), LOP(all)(w->lxz[i]),
                        LOP(all)(w->lyy[i]), LOP(all)(w->lyz[i]), LOP(all)(w->lzz[i])}};
      const LSYM lj = {{LSET(E_L, SPH_XX), LSET(E_L, SPH_XY), LSET(E_L, SPH_XZ), LSET(E_L, SPH_YY),
                        LSET(E_L, SPH_YZ), LSET(E_L, SPH_ZZ)}};
#endif
#undef E_L
      cg = LTERM(corrected_gradient)(li, lj, gw);
    }
    if (fluid || !(fp->moving_walls || fp->mirror)) { /* walls at rest: their pairs add +-0 */
      LACC(drho, LTERM(continuity)(mj, dv, cg));
    } else { /* a wall particle's density follows its fluid neighbours only: the walls
              * next to it are the same body, or another wall moving past it (a flap
              * at its hinge compressed its own corner to 1.3 rho0) */
      const LMASK fj = LOP(lt)(zero, LSET(E_ARR, fm));
      LACC(drho, LOP(and)(fj, LTERM(continuity)(mj, dv, cg)));
    }
#if SPH_DIM == 2
    const LT vdotr = LOP(add)(LOP(mul)(dvx, dx), LOP(mul)(dvy, dy));
#else
    const LT vdotr = LOP(add)(LOP(add)(LOP(mul)(dvx, dx), LOP(mul)(dvy, dy)), LOP(mul)(dvz, dz));
#endif
    LAMAX(sig, LOP(and)(in, LTERM(signal)(hij, vdotr, inv_r2)));
    if ((F & F_DDIFF) && diffuses) { /* over the neighbours that diffuse (diffusion.h) */
      const LT rhoj = GATHER(rho);
      const LT cx = dd_uniform ? cxx : LOP(add)(cxi, LSET(E_ARR, ddcx));
      const LT cy = dd_uniform ? cyy : LOP(add)(cyi, LSET(E_ARR, ddcy));
      SPH_IF3(const LT cz = dd_uniform ? czz : LOP(add)(czi, LSET(E_ARR, ddcz));)
      const LVEC c = {{SPH_XYZ(cx, cy, cz)}};
      const LT psi = LTERM(diffusion_psi)(rhoi, rhoj, rv, c);
      /* the masses they diffuse with: a wall particle's row its fluid
       * neighbours' only; without mdbc and diffusing walls ddm = fm */
#define E_WDD(q, a) (kind[jk[q]] == SPH_KIND_FLUID ? a[jk[q]] : 0.0)
      const LT mdd = !fluid ? LSET(E_WDD, ddm) : mdd_is_mx ? LSET(E_ARR, fm) : LSET(E_ARR, ddm);
#undef E_WDD
      const LT d = LTERM(diffusion)(psi, f, mdd, rhoj);
      LACC(dd, (F & F_VARH) ? LOP(mul)(hij, d) : d); /* per-particle h: h_ij in the sum */
    }
    if (!fluid && !(F & F_LEDGER)) continue; /* a wall particle needs no other pair terms */
    /* with the ledger: m_j of fluid neighbours (0 for walls) as their kind */
    const LT fmj = (F & (F_XSPH | F_LEDGER | F_RIEMANN)) ? LSET(E_ARR, fm) : zero;
    const LMASK fluid_j = LOP(lt)(zero, fmj);
    /* the relative velocity of the viscous terms: a mirror particle's is its
     * no-slip velocity (boundary.h; the scalar loop only), the continuity's
     * its reflected one */
    LT vvx = dvx, vvy = dvy, vvdotr = vdotr;
    SPH_IF3(LT vvz = dvz;)
#if LW == 1
    if (mirror && kind[jk[0]] == SPH_KIND_MIRROR) {
      vvx = vxi - p->vxh[jk[0]];
      vvy = vyi - p->vyh[jk[0]];
#if SPH_DIM == 2
      vvdotr = vvx * dx + vvy * dy;
#else
      vvz = vzi - p->vzh[jk[0]];
      vvdotr = vvx * dx + vvy * dy + vvz * dz;
#endif
    }
#endif
    /* an adami wall neighbour: the viscous terms read its no-slip velocity, and none of them
     * acts on a free-slip one (vis: the lanes they act on) */
    LMASK vis = LOP(lt)(zero, one);
    if (adami_v) {
#define E_AF(q, f) ((kind[jk[q]] == SPH_KIND_WALL && (flags[jk[q]] & (f))) ? 1.0 : 0.0)
#define E_AGV(q, a)                                                                                \
  ((kind[jk[q]] == SPH_KIND_WALL && (flags[jk[q]] & SPH_FLAG_ADAMI)) ? agv[a][jk[q]] : 0.0)
      const LMASK ad = LOP(lt)(zero, LSET(E_AF, SPH_FLAG_ADAMI));
      vis = LOP(lt)(zero, LOP(sub)(one, LSET(E_AF, SPH_FLAG_INVISCID)));
      vvx = LOP(sel)(ad, LOP(sub)(vxi, LSET(E_AGV, 0)), vvx);
      vvy = LOP(sel)(ad, LOP(sub)(vyi, LSET(E_AGV, 1)), vvy);
#if SPH_DIM == 2
      const LT avdotr = LOP(add)(LOP(mul)(vvx, dx), LOP(mul)(vvy, dy));
#else
      vvz = LOP(sel)(ad, LOP(sub)(vzi, LSET(E_AGV, 2)), vvz);
      const LT avdotr = LOP(add)(LOP(add)(LOP(mul)(vvx, dx), LOP(mul)(vvy, dy)), LOP(mul)(vvz, dz));
#endif
      vvdotr = LOP(sel)(ad, avdotr, vvdotr);
#undef E_AGV
#undef E_AF
    }
    LT inv_rb = zero;
    if (F & (F_AV | F_XSPH)) inv_rb = LTERM(inv_rho_mean)(rhoi, GATHER(rho));
    /* a fluid-wall pair on a free-slip wall: the pressure and Pi_ij along the
     * wall particle's normal (normal_part), Pi_ij of the normal relative
     * velocity (normal_vdotr); fs the lanes of such pairs. With the Riemann
     * pressure, the closing speed of a pair with a wall particle that has a
     * normal is the normal one too (rnorm: the lanes fn) */
    LT pgx = cg.c[0], pgy = cg.c[1], avr = vvdotr, rvr = vdotr;
    SPH_IF3(LT pgz = cg.c[2];)
    if ((slip || rnorm) && (fluid || slip_i || rnorm_i)) {
      LT wmx, wmy;
      SPH_IF3(LT wmz;)
      LMASK fs, fn;
      if (fluid) { /* the pair's wall particle is j (offsets of 1 where unused: finite) */
#define E_FS(q, a) ((kind[jk[q]] == SPH_KIND_WALL && (flags[jk[q]] & (a))) ? 1.0 : 0.0)
#define E_M(q, arr) (E_FS(q, SPH_WALL_NORMAL) != 0.0 ? arr[jk[q]] : 1.0)
        fs = LOP(lt)(zero, LSET(E_FS, SPH_FLAG_FREE_SLIP));
        fn = rnorm ? LOP(lt)(zero, LSET(E_FS, SPH_WALL_NORMAL)) : fs;
        wmx = LSET(E_M, p->mx);
        wmy = LSET(E_M, p->my);
        SPH_IF3(wmz = LSET(E_M, p->mz);)
#undef E_M
#undef E_FS
      } else { /* i is the pair's wall particle */
        fs = LOP(lt)(zero, LOP(all)(slip_i ? 1.0 : 0.0));
        fn = LOP(lt)(zero, LOP(all)(rnorm_i ? 1.0 : 0.0));
        wmx = LOP(all)(p->mx[i]);
        wmy = LOP(all)(p->my[i]);
        SPH_IF3(wmz = LOP(all)(p->mz[i]);)
      }
      const LVEC wm = {{SPH_XYZ(wmx, wmy, wmz)}};
      if (slip) {
        const LVEC ng = LTERM(normal_part)(cg, wm);
        pgx = LOP(sel)(fs, ng.c[0], cg.c[0]);
        pgy = LOP(sel)(fs, ng.c[1], cg.c[1]);
        SPH_IF3(pgz = LOP(sel)(fs, ng.c[2], cg.c[2]);)
        const LVEC vv = {{SPH_XYZ(vvx, vvy, vvz)}};
        if (F & F_AV) avr = LOP(sel)(fs, LTERM(normal_vdotr)(vv, rv, wm), vvdotr);
      }
      if (rnorm) rvr = LOP(sel)(fn, LTERM(normal_vdotr)(dv, rv, wm), vdotr);
    }
    LT pij;
    if (F & F_RIEMANN) { /* the interface pressure; the closing speed from v_ij (a
                          * mirror's reflected velocity, a wall's normal part) */
      const LT rhoj = GATHER(rho), pj = LOP(mul)(LOP(mul)(GATHER(prho2), rhoj), rhoj);
      const LT close = LOP(neg)(LOP(mul)(rvr, inv_r));
      pij = LTERM(riemann_pressure)(pi, pj, rhoi, rhoj, close, rz0, rkc);
      if (fluid) { /* its continuity term, between fluid particles only */
#if SPH_DIM == 2
        const LT jump = LOP(sub)(LOP(sub)(pi, pj), LOP(add)(LOP(mul)(hgx, dx), LOP(mul)(hgy, dy)));
#else
        const LT hg = LOP(add)(LOP(add)(LOP(mul)(hgx, dx), LOP(mul)(hgy, dy)), LOP(mul)(hgz, dz));
        const LT jump = LOP(sub)(LOP(sub)(pi, pj), hg);
#endif
        LACC(rd, LOP(and)(fluid_j, LTERM(riemann_density)(rhoi, mj, rhoj, jump, f, r, rinv_z0)));
      }
    } else {
      pij = LOP(add)(pri, GATHER(prho2));
    }
    if (F & F_AV) {
      const LT av =
          LTERM(artificial_viscosity)(avr, hij, r2, eta2_ij, ci, GATHER(cs), nalpha, beta, inv_rb);
      pij = LOP(add)(pij, adami_v ? LOP(and)(vis, av) : av);
    }
    const LT mp = LOP(mul)(mj, pij);
    const LVEC pg = {{SPH_XYZ(pgx, pgy, pgz)}}, pa = LTERM(pressure_force)(mp, pg);
    LT pax = pa.c[0], pay = pa.c[1];
    SPH_IF3(LT paz = pa.c[2];)
    LT heat = zero; /* this particle's half of the pair's heat (energy ledger) */
    if (F & F_LEDGER) heat = LTERM(pressure_heat)(mp, dv, pg);
    if (F & F_STRESS) {
      const LT txx = LOP(add)(LOP(all)(sxx[i]), LSET(E_ARR, sxx));
      const LT txy = LOP(add)(LOP(all)(sxy[i]), LSET(E_ARR, sxy));
      const LT tyy = LOP(add)(LOP(all)(syy[i]), LSET(E_ARR, syy));
#if SPH_DIM == 2
      const LSYM t = {{txx, txy, tyy}};
#else
      const LT txz = LOP(add)(LOP(all)(sxz[i]), LSET(E_ARR, sxz));
      const LT tyz = LOP(add)(LOP(all)(syz[i]), LSET(E_ARR, syz));
      const LT tzz = LOP(add)(LOP(all)(szz[i]), LSET(E_ARR, szz));
      const LSYM t = {{txx, txy, txz, tyy, tyz, tzz}};
#endif
      LVEC sv = LTERM(stress_force)(mj, t, gw);
      if (adami_v)
        sv = (LVEC){
            {SPH_XYZ(LOP(and)(vis, sv.c[0]), LOP(and)(vis, sv.c[1]), LOP(and)(vis, sv.c[2]))}};
      pax = LOP(add)(pax, sv.c[0]);
      pay = LOP(add)(pay, sv.c[1]);
      SPH_IF3(paz = LOP(add)(paz, sv.c[2]);)
      if (F & F_LEDGER) heat = LOP(sub)(heat, LTERM(stress_heat)(mj, t, dv, gw));
    }
    if (F & F_MORRIS) {
      LT c = LTERM(morris_factor)(mj, nu4, f, r2, rhoi, GATHER(rho), eta2_ij);
      if (adami_v) c = LOP(and)(vis, c);
      pax = LOP(add)(pax, LOP(mul)(c, vvx));
      pay = LOP(add)(pay, LOP(mul)(c, vvy));
      SPH_IF3(paz = LOP(add)(paz, LOP(mul)(c, vvz));)
      if (F & F_LEDGER) heat = LOP(sub)(heat, LTERM(morris_heat)(c, dv));
    }
    if (F & F_LEDGER) {
      LT vwx = GATHER(vx), vwy = GATHER(vy); /* a wall neighbour's velocity */
      SPH_IF3(LT vwz = GATHER(vz);)
      if (passive) { /* a repulsive wall or mirror neighbour: i takes the whole heat */
#define E_PAS(q, a)                                                                                \
  ((kind[jk[q]] == SPH_KIND_MIRROR || (flags[jk[q]] & (SPH_FLAG_REPULSIVE | SPH_FLAG_ADAMI)))      \
       ? 1.0                                                                                       \
       : 0.0)
#define E_WV(q, a) (kind[jk[q]] == SPH_KIND_WALL ? hot[jk[q]].a : 0.0) /* a mirror's: at rest */
        const LMASK pas = LOP(lt)(zero, LSET(E_PAS, 0));
        vwx = LSET(E_WV, vx);
        vwy = LSET(E_WV, vy);
        SPH_IF3(vwz = LSET(E_WV, vz);)
#undef E_WV
#undef E_PAS
        const LVEC a = {{SPH_XYZ(pax, pay, paz)}}, vi = {{SPH_XYZ(vxi, vyi, vzi)}};
        const LVEC vw = {{SPH_XYZ(vwx, vwy, vwz)}};
        heat = LOP(sel)(pas, LTERM(passive_heat)(a, vi, vw), heat);
      }
      /* a wall particle: its half of the heat of its pairs with fluid only */
      LACC(du, fluid ? heat : LOP(and)(fluid_j, heat));
      if (!fluid) continue;
      /* the power of wall particles' forces on i, per unit mass of i, and
       * the force of walls and mirror particles: external to the fluid */
      const LT wx = LOP(sel)(fluid_j, zero, pax), wy = LOP(sel)(fluid_j, zero, pay);
      SPH_IF3(const LT wz = LOP(sel)(fluid_j, zero, paz);)
      const LVEC wa = {{SPH_XYZ(wx, wy, wz)}}, vw = {{SPH_XYZ(vwx, vwy, vwz)}};
      LACC(wpow, LTERM(wall_power)(wa, vw));
      LACC(wfx, wx);
      LACC(wfy, wy);
      SPH_IF3(LACC(wfz, wz);)
    }
    LACC(ax, pax);
    LACC(ay, pay);
    SPH_IF3(LACC(az, paz);)
    const LT mx = fmj; /* m_j of fluid neighbours, 0 for the others */
    if (F & F_XSPH) {  /* over fluid neighbours */
      const LT c = LTERM(xsph_factor)(mx, inv_rb, wij);
      LDEC(xs, LOP(mul)(c, dvx));
      LDEC(ys, LOP(mul)(c, dvy));
      SPH_IF3(LDEC(zs, LOP(mul)(c, dvz));)
    }
#undef GATHER
#undef E_ARR
#undef E_HOT
  }
  /* the lanes' sums, (l0 + l1) + (l2 + l3); the scalar loop's own */
#if LW == 1
#define LSUM(v) (v)
#define LMAXALL(v) (v)
#else
#define LSUM(v) (LAOP(store)(lv, v), (lv[0] + lv[1]) + (lv[2] + lv[3]))
#define LMAXALL(v) (LAOP(store)(lv, v), lanes_max4(lv))
#endif
  double lv[4];
  (void)lv;
  p->drho[i] = LSUM(drho);
  double dds = 0.0; /* the density's dissipative rates, added last */
  if (F & F_DDIFF) dds = LSUM(dd) * diffusion_scale(fp, F);
  if (F & F_RIEMANN) dds += LSUM(rd);
  if (F & (F_DDIFF | F_RIEMANN)) {
    p->drho[i] += dds;
    if (F & F_LEDGER) w->dd[i] = dds;
  }
  if (F & F_LEDGER) {
    p->du[i] = LSUM(du);
    w->wpow[i] = LSUM(wpow);
    w->wfx[i] = LSUM(wfx);
    w->wfy[i] = LSUM(wfy);
    SPH_IF3(w->wfz[i] = LSUM(wfz);)
  }
  const double sigma_i = LMAXALL(sig);
  if (fluid) {
    p->ax[i] = LSUM(ax) + fp->gx;
    p->ay[i] = LSUM(ay) + fp->gy;
    SPH_IF3(p->az[i] = LSUM(az) + fp->gz;)
    if (F & F_XSPH) {
      p->xsx[i] = fp->xsph * LSUM(xs);
      p->xsy[i] = fp->xsph * LSUM(ys);
      SPH_IF3(p->xsz[i] = fp->xsph * LSUM(zs);)
    }
  } else {
    p->ax[i] = p->ay[i] = 0.0;
    SPH_IF3(p->az[i] = 0.0;)
  }
  return sigma_i;
}

#undef LMAXALL
#undef LSUM
#undef LSYM
#undef LVEC
#undef LTERM
#undef LOP
#undef LT
