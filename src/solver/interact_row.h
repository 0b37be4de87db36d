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
 * A fluid particle's row is fluid_row_FL (compiled for each term set), a
 * wall particle's wall_row_FL (one function a flavour, the term set at run
 * time); both are row_FL, whose named steps (each a function of its own,
 * inlined) go by pair kind:
 *   row_entries_FL       the row's neighbours (cut to the support, padded)
 *   row_begin_FL         what every pair of the row reads (LROW)
 *   pair_density_FL      every pair: the separation and kernel, and what
 *                        every particle takes from a pair, fluid or wall:
 *                        continuity, signal, density diffusion
 *   pair_viscous_velocity_FL   a pair with a wall particle: the relative
 *                        velocity the viscous terms read (mirror and adami
 *                        walls' no-slip velocity)
 *   pair_wall_normals_FL a pair with a wall particle: the pressure's
 *                        gradient and the closing speeds on free-slip walls
 *                        and walls with a normal
 *   pair_momentum_FL     every pair of a fluid row: the force on i,
 *                        pressure (Riemann or not), artificial viscosity,
 *                        stress, Morris (a wall row: its heat, ledger only)
 *   pair_fluid_fluid_FL  two fluid particles: the Riemann pressure's
 *                        continuity term, XSPH
 *   pair_ledger_FL       the energy ledger's heat, wall power and force
 *   row_end_FL           the sums written out; sigma_i
 * A wall row runs only pair_density_FL unless the ledger is on. The lanes
 * of one iteration hold neighbours of any kind, so a step of some kinds
 * masks the others. A new pair term goes into the step of the pairs it
 * acts on.
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
 * flavours: the same pairs, four entries at a time), LOOP_ATTR the
 * flavour's attributes for inlined steps and LOOP_SHARED for a function
 * the loops share (noipa: neither inlined nor cloned per term set).
 * Fc, a literal at every call, is the term set the loop is compiled for,
 * or F_RUNTIME (interact.h, F_LITERAL): the bits it does not fix come
 * from the pass's term set.
 */

#define LT FL
#define LOP(name) SPH_PT_XGLUE(FL, name)
#define LTERM(name) SPH_PT_XGLUE(name, FL)
#define LVEC SPH_PT_XGLUE(vec, FL) /* vectors and symmetric tensors of the pair terms */
#define LSYM SPH_PT_XGLUE(sym, FL)
#define LROW SPH_PT_XGLUE(row_of, FL)     /* what every pair of a row reads */
#define LSUMS SPH_PT_XGLUE(row_sums, FL)  /* the row's sums */
#define LPAIR SPH_PT_XGLUE(pair_of, FL)   /* one iteration's pairs: their geometry and kernel */
#define LVIS SPH_PT_XGLUE(pair_vis, FL)   /* the velocity the viscous terms read */
#define LNORM SPH_PT_XGLUE(pair_norm, FL) /* the pressure's gradient and the closing speeds */
/* The iteration's neighbours' packed records (sph_force_hot): the scalar
 * loop reads them field by field, the lane loops from g[H_field] (LHOT). */
#if LW == 1
#define LNB const sph_force_hot *restrict
#define GATHER(field) nbr->field
#else
#define LNB const LT *restrict
#define GATHER(field) nbr[H_##field]
#endif
#define E_HOT(q, field) hot[jk[q]].field
#define E_ARR(q, arr) arr[jk[q]]

typedef struct LROW {
  unsigned F;
  sph_particles *restrict p;
  const sph_force_params *restrict fp;
  sph_force_work *restrict w;
  size_t i;
  const sph_force_hot *restrict hot;
  const int32_t *restrict kind;
  const uint8_t *restrict flags;
  int fluid, wendland, passive, adami_v, slip, slip_i, rnorm, rnorm_i;
  int mdd_is_mx, diffuses, dd_uniform;
  int phased;                     /* two phases (physics.air): pair_phases */
  const uint8_t *restrict phase;  /* with them, each fluid particle's */
  const uint8_t *restrict wphase; /* and each adami wall particle's (walls/adami.h) */
  double zi_s;                    /* i's impedance rho0 c0 */
  double mui_s;                   /* and its dynamic viscosity */
#if LW == 1
  int mirror; /* mirror particles' no-slip velocity */
#endif
  LT xi, yi, vxi, vyi, rhoi, pri, ci, hh, inv_h, one, zero, sigma, sigma_h;
  LT eta2, nalpha, beta, nu4, pi, rz0, rkc, rinv_z0, hgx, hgy, cxi, cyi, cxx, cyy;
  LT per, hper, nper;
#if SPH_DIM == 3
  LT zi, vzi, hgz, czi, czz, pery, hpery, npery, perz, hperz, nperz;
#endif
#if LW > 1
  LT lane, n;
#endif
} LROW;

typedef struct LSUMS {
  LA drho, ax, ay, xs, ys, sig, dd;
  LA du, wpow, wfx, wfy; /* energy and momentum ledger */
  LA rd;                 /* the Riemann continuity term */
#if SPH_DIM == 3
  LA az, zs, wfz;
#endif
} LSUMS;

typedef struct LPAIR {
  LT dx, dy, r2, r, inv_r, inv_r2, hij, eta2_ij, wij, f, dvx, dvy, mj, vdotr;
  LT wi, wj, zij; /* two phases: phase_weights (pair_phases) */
  LT wc;          /* and the continuity's weight: wi, 1 with a wall particle */
  LT mu2;         /* and 2 mu_ij (phase_viscosity) with Morris' viscosity */
  LT ow;          /* and 1 where the neighbour is a wall particle of the other phase, else 0 */
#if SPH_DIM == 3
  LT dz, dvz;
#endif
  LVEC rv, gw, dv, cg; /* r_ij, grad_i W_ij, v_ij, the pressure's gradient */
} LPAIR;

typedef struct LVIS {
  LT vvx, vvy, vvdotr;
#if SPH_DIM == 3
  LT vvz;
#endif
  LMASK vis; /* the lanes the viscous terms act on */
} LVIS;

typedef struct LNORM {
  LT pgx, pgy, avr, rvr;
#if SPH_DIM == 3
  LT pgz;
#endif
} LNORM;

/* The row of particle i: its neighbours (*cnt of them, padded to a
 * multiple of LW with the last). */
LOOP_ATTR const uint32_t *SPH_PT_XGLUE(row_entries, FL)(const sph_nlist *restrict l,
                                                        const sph_force_params *restrict fp,
                                                        const sph_force_work *restrict w, size_t i,
                                                        unsigned F, size_t *cnt) {
  const sph_force_hot *restrict hot = w->hot;
  if (F & F_VARH) /* (the scalar loop only) the whole row: the support is per pair */
    return sph_nlist_row(l, i, cnt);
  if ((F & (F_STRESS | F_CGRAD)) && w->keep_valid) { /* the strain-rate pass's cut row, padded */
    *cnt = w->keepn[i];
    return w->keep + sph_nlist_slot(l, i) + SPH_KEEP_PAD * i;
  }
  uint32_t *restrict cut = w->rows + (size_t)sph_thread() * w->rows_stride;
  /* the cut compiled for both: periodic or not (a predicted branch per row) */
  const size_t n =
      (F & F_PERIODIC) ? LCUT(hot, l, fp, i, cut, F_PERIODIC) : LCUT(hot, l, fp, i, cut, 0);
  for (size_t k = n; k < n + LW - 1 && n > 0; k++)
    cut[k] = cut[n - 1]; /* padding lanes */
  *cnt = n;
  return cut;
}

/* What every pair of particle i's row reads: i's fields, the case's
 * constants as vectors, and which wall treatments the row meets. */
LOOP_ATTR void SPH_PT_XGLUE(row_begin, FL)(LROW *restrict o, sph_particles *restrict p,
                                           const sph_force_params *restrict fp,
                                           sph_force_work *restrict w, size_t i, unsigned F,
                                           size_t cnt) {
  (void)cnt;
  const sph_force_hot *restrict hot = w->hot;
  const int32_t *restrict kind = p->kind;
  const uint8_t *restrict flags = p->flags;
  const sph_force_hot qi = hot[i];
  o->F = F, o->p = p, o->fp = fp, o->w = w, o->i = i, o->hot = hot, o->kind = kind;
  o->flags = flags;
  const int fluid = o->fluid = kind[i] == SPH_KIND_FLUID;
#if LW == 1
  o->mirror = fp->mirror;
#endif
  const double h0 = fp->h, inv_h0 = 1.0 / h0;
  o->wendland = fp->kernel == SPH_KERNEL_WENDLAND_C2;
  const double sigma0 = sph_kernel_sigma(fp->kernel, inv_h0);
  o->xi = LOP(all)(qi.x), o->yi = LOP(all)(qi.y), o->vxi = LOP(all)(qi.vx);
  o->vyi = LOP(all)(qi.vy);
  SPH_IF3(o->zi = LOP(all)(qi.z), o->vzi = LOP(all)(qi.vz);)
  o->rhoi = LOP(all)(qi.rho), o->pri = LOP(all)(qi.prho2), o->ci = LOP(all)(qi.cs);
  o->hh = LOP(all)(h0), o->inv_h = LOP(all)(inv_h0), o->one = LOP(all)(1.0);
  o->zero = LOP(all)(0.0);
  o->sigma = LOP(all)(sigma0), o->sigma_h = LOP(all)(sigma0 * inv_h0);
  {
    LANE_PERIODS(fp);
    o->per = per, o->hper = hper, o->nper = nper;
    SPH_IF3(o->pery = pery, o->hpery = hpery, o->npery = npery;)
    SPH_IF3(o->perz = perz, o->hperz = hperz, o->nperz = nperz;)
  }
  const double eta = fp->eta * h0;
  o->eta2 = LOP(all)(eta * eta), o->nalpha = LOP(all)(-fp->alpha), o->beta = LOP(all)(fp->beta);
  o->nu4 = LOP(all)(4.0 * fp->mu / fp->eos.rho0);
  /* the Riemann pressure: p_i, rho0 c0 and eta / c0, and the density term's rho0 g and
   * 1 / (rho0 c0), of i's material (two phases: its phase's; a wall particle's is phase 0's) */
  const int riem = (F & F_RIEMANN) != 0; /* (the constants only where it is on) */
  o->phased = riem && (F & F_PHASES);    /* (0 in every compiled set: interact.h) */
  o->phase = p->phase;
  o->wphase = p->wphase;
  const sph_eos *ei = o->phased ? &fp->phase_eos[p->phase[i]] : &fp->eos;
  o->zi_s = ei->rho0 * ei->c0;
  o->mui_s = o->phased ? fp->phase_mu[p->phase[i]] : fp->mu;
  o->pi = LOP(all)(riem ? qi.prho2 * qi.rho * qi.rho : 0.0);
  o->rz0 = LOP(all)(riem ? o->zi_s : 0.0);
  o->rkc = LOP(all)(riem ? fp->riemann_limiter / fp->eos.c0 : 0.0);
  o->rinv_z0 = LOP(all)(riem ? 1.0 / o->zi_s : 0.0);
  o->hgx = LOP(all)(riem ? ei->rho0 * fp->gx : 0.0);
  o->hgy = LOP(all)(riem ? ei->rho0 * fp->gy : 0.0);
  SPH_IF3(o->hgz = LOP(all)(riem ? ei->rho0 * fp->gz : 0.0);)
#if LW > 1
#define E_LANE(q, a) ((double)(q))
  o->lane = LSET(E_LANE, 0), o->n = LOP(all)((double)cnt);
#undef E_LANE
#endif
  /* neighbours that take no heat: repulsive wall particles, mirror particles and adami wall
   * particles */
  o->passive = (F & F_LEDGER) && (fp->repulsive || fp->mirror || fp->adami);
  /* adami walls in the viscous terms of a fluid row: a wall neighbour's no-slip velocity
   * (w->gv), none on a free-slip one (walls/adami.h) */
  o->adami_v = fp->adami && fluid && (F & (F_AV | F_MORRIS | F_STRESS));
  /* free-slip walls: a predicted branch per iteration (i's own flag for a wall i) */
  o->slip = fp->free_slip;
  o->slip_i = o->slip && kind[i] == SPH_KIND_WALL && (flags[i] & SPH_FLAG_FREE_SLIP);
  /* the Riemann pressure's closing speed on walls with a normal (mdbc, no-slip and free-slip
   * walls: SPH_WALL_NORMAL): the normal part of v_ij, so that the wall's dissipation stops the
   * fluid going through it but does not brake it along it (no-slip is the viscous terms') */
  o->rnorm = (F & F_RIEMANN) && sph_force_wall_normals(fp) &&
             (kind[i] != SPH_KIND_FLUID || w->nwall[i]); /* a row that meets one */
  o->rnorm_i = o->rnorm && kind[i] == SPH_KIND_WALL && (flags[i] & SPH_WALL_NORMAL);
  /* then ddm = fm, which diffusion.c does not fill: only fluid diffuses, all of it */
  o->mdd_is_mx = sph_diffusion_mass_is_fm(fp, (F & F_XSPH) != 0);
  o->diffuses = (F & F_DDIFF) && (o->mdd_is_mx ? w->fm : w->ddm)[i] != 0.0; /* diffusion.h */
  /* c_j = c_i at every particle but with antuono (diffusion.c: then w->ddc0): the same sums
   * without reading c_j */
  const int dd_uniform = o->dd_uniform = fp->diffusion != SPH_DIFFUSION_ANTUONO;
  o->cxi = LOP(all)((F & F_DDIFF) ? (dd_uniform ? w->ddc0[0] : w->ddcx[i]) : 0.0);
  o->cyi = LOP(all)((F & F_DDIFF) ? (dd_uniform ? w->ddc0[1] : w->ddcy[i]) : 0.0);
  SPH_IF3(o->czi = LOP(all)((F & F_DDIFF) ? (dd_uniform ? w->ddc0[2] : w->ddcz[i]) : 0.0);)
  o->cxx = LOP(add)(o->cxi, o->cxi), o->cyy = LOP(add)(o->cyi, o->cyi);
  SPH_IF3(o->czz = LOP(add)(o->czi, o->czi);)
}

/* Two phases (physics.air): the pair's weights between i's material and
 * each neighbour's (phase_weights) and, with Morris' viscosity, its 2 mu_ij
 * (phase_viscosity); a wall neighbour is of its mirror phase, the fluid's
 * beside it, whose pressure it carries (walls/adami.h). With a wall particle
 * the continuity keeps one phase's form (wc = 1): the wall's velocity is its
 * own, not its mirror phase's. */
LOOP_ATTR void SPH_PT_XGLUE(pair_phases, FL)(const LROW *restrict R, LPAIR *restrict G,
                                             const uint32_t *restrict jk) {
  const int32_t *restrict kind = R->kind;
  const uint8_t *restrict ph = R->phase, *restrict wph = R->wphase;
  const double *restrict z = R->fp->phase_z;
#define E_PH(q, tab) (kind[jk[q]] == SPH_KIND_FLUID ? tab[ph[jk[q]]] : tab[wph[jk[q]]])
  const LT zj = LSET(E_PH, z);
  LTERM(phase_weights)(LOP(all)(R->zi_s), zj, &G->wi, &G->wj, &G->zij);
#define E_FL(q, a) (kind[jk[q]] == SPH_KIND_FLUID ? 1.0 : 0.0)
  G->wc = LOP(sel)(LOP(lt)(R->zero, LSET(E_FL, 0)), G->wi, R->one);
#undef E_FL
  const uint8_t phi = ph[R->i];
#define E_OW(q, a) (kind[jk[q]] != SPH_KIND_FLUID && wph[jk[q]] != phi ? 1.0 : 0.0)
  G->ow = LSET(E_OW, 0);
#undef E_OW
  if (R->F & F_MORRIS) {
    const double *restrict mu = R->fp->phase_mu;
    G->mu2 = LTERM(phase_viscosity)(LOP(all)(R->mui_s), LSET(E_PH, mu));
  } else {
    G->mu2 = R->zero;
  }
#undef E_PH
}

/* The pair's hydrostatic jump rho0_i g . r_ij (r_ij = x_i - x_j, rho0 of
 * i's material: row_begin's hgx, hgy, hgz), which the Riemann density term
 * takes out of p_i - p_j and the two-phase wall floor adds to p_i. */
LOOP_ATTR LT SPH_PT_XGLUE(pair_head, FL)(const LROW *restrict R, const LPAIR *restrict G) {
#if SPH_DIM == 2
  return LOP(add)(LOP(mul)(R->hgx, G->dx), LOP(mul)(R->hgy, G->dy));
#else
  return LOP(add)(LOP(add)(LOP(mul)(R->hgx, G->dx), LOP(mul)(R->hgy, G->dy)),
                  LOP(mul)(R->hgz, G->dz));
#endif
}

/* One iteration's pairs (i with the neighbours jk[0 .. LW-1], the k-th
 * entries of the row): their separation, kernel and gradient, and what
 * every particle takes from them, fluid or wall: the continuity, the step
 * rule's signal and the density diffusion. Returns 0 where the pair is
 * outside its own support (per-particle h): nothing summed. */
LOOP_ATTR int SPH_PT_XGLUE(pair_density, FL)(const LROW *restrict R, LSUMS *restrict S,
                                             LPAIR *restrict G, const uint32_t *restrict jk,
                                             size_t k, LNB nbr) {
  const unsigned F = R->F;
  const sph_force_work *restrict w = R->w;
  const int32_t *restrict kind = R->kind;
  const int fluid = R->fluid;
  const size_t i = R->i;
  const LT zero = R->zero, xi = R->xi, yi = R->yi;
  (void)k;
  LT dx = LOP(sub)(xi, GATHER(x));
  if (F & F_PERIODIC) /* minimum image, as sep_x */
    dx = LANE_MIN_IMAGE(dx, R->per, R->hper, R->nper);
#if SPH_DIM == 2
  const LT dy = LOP(sub)(yi, GATHER(y));
  const LT r2 = LOP(add)(LOP(mul)(dx, dx), LOP(mul)(dy, dy));
#else
  LT dy = LOP(sub)(yi, GATHER(y)), dz = LOP(sub)(R->zi, GATHER(z));
  if (F & F_PERIODIC) { /* y or z may be the axis that wraps */
    dy = LANE_MIN_IMAGE(dy, R->pery, R->hpery, R->npery);
    dz = LANE_MIN_IMAGE(dz, R->perz, R->hperz, R->nperz);
  }
  const LT r2 = LOP(add)(LOP(add)(LOP(mul)(dx, dx), LOP(mul)(dy, dy)), LOP(mul)(dz, dz));
#endif
  /* the pair's smoothing length and what follows from it */
  LT hij = R->hh, inv_hij = R->inv_h, sig_ij = R->sigma, sig_h_ij = R->sigma_h;
  LT eta2_ij = R->eta2;
#if LW == 1
  if (F & F_VARH) { /* per-particle h: h_ij the pair's mean; outside its support, skip */
    const sph_force_params *restrict fp = R->fp;
    const double hm = 0.5 * (R->p->h[i] + R->p->h[jk[0]]);
    if (r2 >= 4.0 * hm * hm || r2 == 0.0) return 0;
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
  const LMASK in = LOP(lt)(LOP(add)(LOP(all)((double)k), R->lane), R->n);
#endif
  /* 1/r2 and sqrt(r2) side by side: a shorter chain than 1/sqrt(r2) */
  const LT inv_r2 = LOP(div)(R->one, r2), r = LOP(sqrt)(r2), inv_r = LOP(mul)(r, inv_r2);
  LT wij, f;
  if (R->wendland) /* the same for every pair: a branch the processor predicts */
    LTERM(wendland_w_f)(r, inv_r, inv_hij, sig_ij, sig_h_ij, &wij, &f);
  else
    LTERM(cubic_w_f)(r, inv_r, inv_hij, sig_ij, sig_h_ij, &wij, &f);
  wij = LOP(and)(in, wij);
  f = LOP(and)(in, f);
  const LT gx = LOP(mul)(f, dx), gy = LOP(mul)(f, dy);
  const LT dvx = LOP(sub)(R->vxi, GATHER(vx)), dvy = LOP(sub)(R->vyi, GATHER(vy));
  SPH_IF3(const LT gz = LOP(mul)(f, dz), dvz = LOP(sub)(R->vzi, GATHER(vz));)
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
  /* two phases: the volume form, weighted (pair_phases) */
  if (R->phased)
    SPH_PT_XGLUE(pair_phases, FL)(R, G, jk);
  else /* (read only with two phases) */
    G->wi = G->wj = G->zij = G->wc = G->mu2 = G->ow = zero;
  const LT mc = R->phased ? LTERM(phase_continuity_mass)(R->rhoi, mj, GATHER(rho), G->wc) : mj;
  if (fluid || !(R->fp->moving_walls || R->fp->mirror)) { /* walls at rest: their pairs add +-0 */
    LACC(S->drho, LTERM(continuity)(mc, dv, cg));
  } else { /* a wall particle's density follows its fluid neighbours only: the walls
            * next to it are the same body, or another wall moving past it (a flap
            * at its hinge compressed its own corner to 1.3 rho0) */
    const LMASK fj = LOP(lt)(zero, LSET(E_ARR, w->fm));
    LACC(S->drho, LOP(and)(fj, LTERM(continuity)(mc, dv, cg)));
  }
#if SPH_DIM == 2
  const LT vdotr = LOP(add)(LOP(mul)(dvx, dx), LOP(mul)(dvy, dy));
#else
  const LT vdotr = LOP(add)(LOP(add)(LOP(mul)(dvx, dx), LOP(mul)(dvy, dy)), LOP(mul)(dvz, dz));
#endif
  LAMAX(S->sig, LOP(and)(in, LTERM(signal)(hij, vdotr, inv_r2)));
  if ((F & F_DDIFF) && R->diffuses) { /* over the neighbours that diffuse (diffusion.h) */
    const int dd_uniform = R->dd_uniform;
    const LT rhoj = GATHER(rho);
    const LT cx = dd_uniform ? R->cxx : LOP(add)(R->cxi, LSET(E_ARR, w->ddcx));
    const LT cy = dd_uniform ? R->cyy : LOP(add)(R->cyi, LSET(E_ARR, w->ddcy));
    SPH_IF3(const LT cz = dd_uniform ? R->czz : LOP(add)(R->czi, LSET(E_ARR, w->ddcz));)
    const LVEC c = {{SPH_XYZ(cx, cy, cz)}};
    const LT psi = LTERM(diffusion_psi)(R->rhoi, rhoj, rv, c);
    /* the masses they diffuse with: a wall particle's row its fluid
     * neighbours' only; without mdbc and diffusing walls ddm = fm */
#define E_WDD(q, a) (kind[jk[q]] == SPH_KIND_FLUID ? a[jk[q]] : 0.0)
    const LT mdd = !fluid         ? LSET(E_WDD, w->ddm)
                   : R->mdd_is_mx ? LSET(E_ARR, w->fm)
                                  : LSET(E_ARR, w->ddm);
#undef E_WDD
    const LT d = LTERM(diffusion)(psi, f, mdd, rhoj);
    LACC(S->dd, (F & F_VARH) ? LOP(mul)(hij, d) : d); /* per-particle h: h_ij in the sum */
  }
  G->dx = dx, G->dy = dy, G->r2 = r2, G->r = r, G->inv_r = inv_r, G->inv_r2 = inv_r2;
  G->hij = hij, G->eta2_ij = eta2_ij, G->wij = wij, G->f = f, G->dvx = dvx, G->dvy = dvy;
  G->mj = mj, G->vdotr = vdotr;
  SPH_IF3(G->dz = dz, G->dvz = dvz;)
  G->rv = rv, G->gw = gw, G->dv = dv, G->cg = cg;
  return 1;
}

/* The relative velocity the viscous terms of a pair read: a mirror
 * particle's is its no-slip velocity (boundary.h; the scalar loop only),
 * an adami wall neighbour's its no-slip velocity too, and none of them
 * acts on a free-slip one (vis: the lanes they act on); the continuity
 * keeps v_ij. */
LOOP_ATTR LVIS SPH_PT_XGLUE(pair_viscous_velocity, FL)(const LROW *restrict R,
                                                       const LPAIR *restrict G,
                                                       const uint32_t *restrict jk) {
  const int32_t *restrict kind = R->kind;
  const uint8_t *restrict flags = R->flags;
  const LT zero = R->zero, one = R->one, dx = G->dx, dy = G->dy;
  SPH_IF3(const LT dz = G->dz;)
  LVIS o = {.vvx = G->dvx, .vvy = G->dvy, .vvdotr = G->vdotr};
  SPH_IF3(o.vvz = G->dvz;)
#if LW == 1
  if (R->mirror && kind[jk[0]] == SPH_KIND_MIRROR) {
    const sph_particles *restrict p = R->p;
    o.vvx = R->vxi - p->vxh[jk[0]];
    o.vvy = R->vyi - p->vyh[jk[0]];
#if SPH_DIM == 2
    o.vvdotr = o.vvx * dx + o.vvy * dy;
#else
    o.vvz = R->vzi - p->vzh[jk[0]];
    o.vvdotr = o.vvx * dx + o.vvy * dy + o.vvz * dz;
#endif
  }
#endif
  o.vis = LOP(lt)(zero, one);
  if (R->adami_v) {
    const double *const *restrict agv = (const double *const *)R->w->gv;
#define E_AF(q, f) ((kind[jk[q]] == SPH_KIND_WALL && (flags[jk[q]] & (f))) ? 1.0 : 0.0)
#define E_AGV(q, a)                                                                                \
  ((kind[jk[q]] == SPH_KIND_WALL && (flags[jk[q]] & SPH_FLAG_ADAMI)) ? agv[a][jk[q]] : 0.0)
    const LMASK ad = LOP(lt)(zero, LSET(E_AF, SPH_FLAG_ADAMI));
    o.vis = LOP(lt)(zero, LOP(sub)(one, LSET(E_AF, SPH_FLAG_INVISCID)));
    o.vvx = LOP(sel)(ad, LOP(sub)(R->vxi, LSET(E_AGV, 0)), o.vvx);
    o.vvy = LOP(sel)(ad, LOP(sub)(R->vyi, LSET(E_AGV, 1)), o.vvy);
#if SPH_DIM == 2
    const LT avdotr = LOP(add)(LOP(mul)(o.vvx, dx), LOP(mul)(o.vvy, dy));
#else
    o.vvz = LOP(sel)(ad, LOP(sub)(R->vzi, LSET(E_AGV, 2)), o.vvz);
    const LT avdotr =
        LOP(add)(LOP(add)(LOP(mul)(o.vvx, dx), LOP(mul)(o.vvy, dy)), LOP(mul)(o.vvz, dz));
#endif
    o.vvdotr = LOP(sel)(ad, avdotr, o.vvdotr);
#undef E_AGV
#undef E_AF
  }
  return o;
}

/* A fluid-wall pair on a free-slip wall: the pressure and Pi_ij along the
 * wall particle's normal (normal_part), Pi_ij of the normal relative
 * velocity (normal_vdotr); fs the lanes of such pairs. With the Riemann
 * pressure, the closing speed of a pair with a wall particle that has a
 * normal is the normal one too (rnorm: the lanes fn). Elsewhere the
 * gradient and the closing speeds as they are. */
LOOP_ATTR LNORM SPH_PT_XGLUE(pair_wall_normals, FL)(const LROW *restrict R, const LPAIR *restrict G,
                                                    const LVIS *restrict V,
                                                    const uint32_t *restrict jk) {
  const unsigned F = R->F;
  const LT zero = R->zero;
  const int fluid = R->fluid, slip = R->slip, rnorm = R->rnorm;
  const LVEC cg = G->cg;
  LNORM o = {.pgx = cg.c[0], .pgy = cg.c[1], .avr = V->vvdotr, .rvr = G->vdotr};
  SPH_IF3(o.pgz = cg.c[2];)
  if (!((slip || rnorm) && (fluid || R->slip_i || R->rnorm_i))) return o;
  const sph_particles *restrict p = R->p;
  const int32_t *restrict kind = R->kind;
  const uint8_t *restrict flags = R->flags;
  const size_t i = R->i;
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
    fs = LOP(lt)(zero, LOP(all)(R->slip_i ? 1.0 : 0.0));
    fn = LOP(lt)(zero, LOP(all)(R->rnorm_i ? 1.0 : 0.0));
    wmx = LOP(all)(p->mx[i]);
    wmy = LOP(all)(p->my[i]);
    SPH_IF3(wmz = LOP(all)(p->mz[i]);)
  }
  const LVEC wm = {{SPH_XYZ(wmx, wmy, wmz)}};
  if (slip) {
    const LVEC ng = LTERM(normal_part)(cg, wm);
    o.pgx = LOP(sel)(fs, ng.c[0], cg.c[0]);
    o.pgy = LOP(sel)(fs, ng.c[1], cg.c[1]);
    SPH_IF3(o.pgz = LOP(sel)(fs, ng.c[2], cg.c[2]);)
    const LVEC vv = {{SPH_XYZ(V->vvx, V->vvy, V->vvz)}};
    if (F & F_AV) o.avr = LOP(sel)(fs, LTERM(normal_vdotr)(vv, G->rv, wm), V->vvdotr);
  }
  if (rnorm) o.rvr = LOP(sel)(fn, LTERM(normal_vdotr)(G->dv, G->rv, wm), G->vdotr);
  return o;
}

/* The pair's force on i per unit mass of i (*pa) and i's half of its heat
 * (*heat, with the ledger), for every pair kind of a fluid row (and a wall
 * row's heat): the pressure (the Riemann interface pressure, or
 * p_i/rho_i^2 + p_j/rho_j^2), the artificial viscosity, the stress tensor
 * and Morris' viscosity, each where the term set has it. */
LOOP_ATTR void SPH_PT_XGLUE(pair_momentum, FL)(const LROW *restrict R, const LPAIR *restrict G,
                                               const LVIS *restrict V, const LNORM *restrict N,
                                               const uint32_t *restrict jk, LNB nbr, LVEC *pa,
                                               LT *heat) {
  const unsigned F = R->F;
  const sph_force_work *restrict w = R->w;
  const size_t i = R->i;
  const LT mj = G->mj, f = G->f;
  LT pij;
  if (F & F_RIEMANN) { /* the interface pressure; the closing speed from v_ij (a
                        * mirror's reflected velocity, a wall's normal part) */
    const LT rhoi = R->rhoi, pi = R->pi;
    const LT rhoj = GATHER(rho);
    LT pj = LOP(mul)(LOP(mul)(GATHER(prho2), rhoj), rhoj);
    if (R->phased) { /* a wall of the other phase (pair_phases) below i, g . (x_j - x_i) > 0,
                      * presses no less than i's column */
      const LT hg = SPH_PT_XGLUE(pair_head, FL)(R, G);
      const LMASK below = LOP(lt)(LOP(sel)(LOP(lt)(R->zero, G->ow), hg, R->zero), R->zero);
      pj = LOP(sel)(below, LTERM(wall_pressure_floor)(pj, pi, hg), pj);
    }
    const LT close = LOP(neg)(LOP(mul)(N->rvr, G->inv_r));
    pij = R->phased ? LTERM(riemann_pressure_phases)(pi, pj, rhoi, rhoj, close, G->wi, G->wj,
                                                     G->zij, R->rkc)
                    : LTERM(riemann_pressure)(pi, pj, rhoi, rhoj, close, R->rz0, R->rkc);
  } else {
    pij = LOP(add)(R->pri, GATHER(prho2));
  }
  if (F & F_AV) {
    const LT inv_rb = LTERM(inv_rho_mean)(R->rhoi, GATHER(rho));
    const LT av = LTERM(artificial_viscosity)(N->avr, G->hij, G->r2, G->eta2_ij, R->ci, GATHER(cs),
                                              R->nalpha, R->beta, inv_rb);
    pij = LOP(add)(pij, R->adami_v ? LOP(and)(V->vis, av) : av);
  }
  const LT mp = LOP(mul)(mj, pij);
  const LVEC pg = {{SPH_XYZ(N->pgx, N->pgy, N->pgz)}};
  *pa = LTERM(pressure_force)(mp, pg);
  if (F & F_LEDGER) *heat = LTERM(pressure_heat)(mp, G->dv, pg);
  if (F & F_STRESS) {
#define E_S(q, a) w->a[jk[q]]
    LT txx = LOP(add)(LOP(all)(w->sxx[i]), LSET(E_S, sxx));
    LT txy = LOP(add)(LOP(all)(w->sxy[i]), LSET(E_S, sxy));
    LT tyy = LOP(add)(LOP(all)(w->syy[i]), LSET(E_S, syy));
    SPH_IF3(LT txz = LOP(add)(LOP(all)(w->sxz[i]), LSET(E_S, sxz));
            LT tyz = LOP(add)(LOP(all)(w->syz[i]), LSET(E_S, syz));
            LT tzz = LOP(add)(LOP(all)(w->szz[i]), LSET(E_S, szz));)
#undef E_S
    if (R->phased) { /* two phases: the capillary stress in the volume form (Pi_i + Pi_j) /
                      * (rho_i rho_j) (surface_tension.c) */
      const LT inv = LOP(div)(R->one, LOP(mul)(R->rhoi, GATHER(rho)));
      txx = LOP(mul)(txx, inv), txy = LOP(mul)(txy, inv), tyy = LOP(mul)(tyy, inv);
      SPH_IF3(txz = LOP(mul)(txz, inv), tyz = LOP(mul)(tyz, inv), tzz = LOP(mul)(tzz, inv);)
    }
#if SPH_DIM == 2
    const LSYM t = {{txx, txy, tyy}};
#else
    const LSYM t = {{txx, txy, txz, tyy, tyz, tzz}};
#endif
    LVEC sv = LTERM(stress_force)(mj, t, G->gw);
    if (R->adami_v)
      sv = (LVEC){{SPH_XYZ(LOP(and)(V->vis, sv.c[0]), LOP(and)(V->vis, sv.c[1]),
                           LOP(and)(V->vis, sv.c[2]))}};
    pa->c[0] = LOP(add)(pa->c[0], sv.c[0]);
    pa->c[1] = LOP(add)(pa->c[1], sv.c[1]);
    SPH_IF3(pa->c[2] = LOP(add)(pa->c[2], sv.c[2]);)
    if (F & F_LEDGER) *heat = LOP(sub)(*heat, LTERM(stress_heat)(mj, t, G->dv, G->gw));
  }
  if (F & F_MORRIS) {
    LT c = R->phased
               ? LTERM(morris_phases_factor)(mj, GATHER(rho), G->mu2, f, G->r2, R->rhoi, G->eta2_ij)
               : LTERM(morris_factor)(mj, R->nu4, f, G->r2, R->rhoi, GATHER(rho), G->eta2_ij);
    if (R->adami_v) c = LOP(and)(V->vis, c);
    pa->c[0] = LOP(add)(pa->c[0], LOP(mul)(c, V->vvx));
    pa->c[1] = LOP(add)(pa->c[1], LOP(mul)(c, V->vvy));
    SPH_IF3(pa->c[2] = LOP(add)(pa->c[2], LOP(mul)(c, V->vvz));)
    if (F & F_LEDGER) *heat = LOP(sub)(*heat, LTERM(morris_heat)(c, G->dv));
  }
}

/* The terms of a pair of two fluid particles (a fluid row; the lanes of
 * other neighbours masked out): the Riemann pressure's continuity term
 * (over fluid_j) and XSPH (over m_j of fluid j, 0 for the others). */
LOOP_ATTR void SPH_PT_XGLUE(pair_fluid_fluid, FL)(const LROW *restrict R, LSUMS *restrict S,
                                                  const LPAIR *restrict G, LMASK fluid_j,
                                                  const uint32_t *restrict jk, LNB nbr) {
  const unsigned F = R->F;
  const sph_force_work *restrict w = R->w;
  if (F & F_RIEMANN) {
    const LT rhoi = R->rhoi, pi = R->pi;
    const LT rhoj = GATHER(rho), pj = LOP(mul)(LOP(mul)(GATHER(prho2), rhoj), rhoj);
    const LT hg = SPH_PT_XGLUE(pair_head, FL)(R, G);
    const LT jump = LOP(sub)(LOP(sub)(pi, pj), hg);
    LT rd = LTERM(riemann_density)(rhoi, G->mj, rhoj, jump, G->f, G->r, R->rinv_z0);
    if (R->phased) { /* two phases: between particles of one phase alone (of one impedance
                      * too, a drop in a liquid of its own density) */
      const uint8_t *restrict ph = R->phase;
      const uint8_t phi = ph[R->i];
#define E_SAME(q, a) (ph[jk[q]] == phi ? 1.0 : 0.0)
      rd = LOP(and)(LOP(lt)(R->zero, LSET(E_SAME, 0)), rd);
#undef E_SAME
    }
    LACC(S->rd, LOP(and)(fluid_j, rd));
  }
  if (F & F_XSPH) {
    const LT inv_rb = LTERM(inv_rho_mean)(R->rhoi, GATHER(rho));
    const LT c = LTERM(xsph_factor)(LSET(E_ARR, w->fm), inv_rb, G->wij);
    LDEC(S->xs, LOP(mul)(c, G->dvx));
    LDEC(S->ys, LOP(mul)(c, G->dvy));
    SPH_IF3(LDEC(S->zs, LOP(mul)(c, G->dvz));)
  }
}

/* The energy ledger's share of a pair: i's half of its heat (a repulsive
 * wall or mirror neighbour's heat all i's; a wall particle's half of the
 * heat of its pairs with fluid only) and, for a fluid i, the power and the
 * force of wall particles on it (external to the fluid). */
LOOP_ATTR void SPH_PT_XGLUE(pair_ledger, FL)(const LROW *restrict R, LSUMS *restrict S,
                                             LMASK fluid_j, const uint32_t *restrict jk, LNB nbr,
                                             LVEC pa, LT heat) {
  const sph_force_hot *restrict hot = R->hot;
  const int32_t *restrict kind = R->kind;
  const uint8_t *restrict flags = R->flags;
  const LT zero = R->zero;
  LT vwx = GATHER(vx), vwy = GATHER(vy); /* a wall neighbour's velocity */
  SPH_IF3(LT vwz = GATHER(vz);)
  if (R->passive) { /* a repulsive wall or mirror neighbour: i takes the whole heat */
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
    const LVEC vi = {{SPH_XYZ(R->vxi, R->vyi, R->vzi)}};
    const LVEC vw = {{SPH_XYZ(vwx, vwy, vwz)}};
    heat = LOP(sel)(pas, LTERM(passive_heat)(pa, vi, vw), heat);
  }
  /* a wall particle: its half of the heat of its pairs with fluid only */
  LACC(S->du, R->fluid ? heat : LOP(and)(fluid_j, heat));
  if (!R->fluid) return;
  /* the power of wall particles' forces on i, per unit mass of i, and
   * the force of walls and mirror particles: external to the fluid */
  const LT wx = LOP(sel)(fluid_j, zero, pa.c[0]), wy = LOP(sel)(fluid_j, zero, pa.c[1]);
  SPH_IF3(const LT wz = LOP(sel)(fluid_j, zero, pa.c[2]);)
  const LVEC wa = {{SPH_XYZ(wx, wy, wz)}}, vw = {{SPH_XYZ(vwx, vwy, vwz)}};
  LACC(S->wpow, LTERM(wall_power)(wa, vw));
  LACC(S->wfx, wx);
  LACC(S->wfy, wy);
  SPH_IF3(LACC(S->wfz, wz);)
}

/* The row's sums written out: (l0 + l1) + (l2 + l3) of the lanes (the
 * scalar loop's own sums), the density's dissipative rates added last.
 * Returns sigma_i. */
LOOP_ATTR double SPH_PT_XGLUE(row_end, FL)(const LROW *restrict R, const LSUMS *restrict S) {
  const unsigned F = R->F;
  sph_particles *restrict p = R->p;
  const sph_force_params *restrict fp = R->fp;
  sph_force_work *restrict w = R->w;
  const size_t i = R->i;
#if LW == 1
#define LSUM(v) (v)
#define LMAXALL(v) (v)
#else
#define LSUM(v) (LAOP(store)(lv, v), (lv[0] + lv[1]) + (lv[2] + lv[3]))
#define LMAXALL(v) (LAOP(store)(lv, v), lanes_max4(lv))
#endif
  double lv[4];
  (void)lv;
  p->drho[i] = LSUM(S->drho);
  double dds = 0.0; /* the density's dissipative rates, added last */
  if (F & F_DDIFF) dds = LSUM(S->dd) * diffusion_scale(fp, F);
  if (F & F_RIEMANN) dds += LSUM(S->rd);
  if (F & (F_DDIFF | F_RIEMANN)) {
    p->drho[i] += dds;
    if (F & F_LEDGER) w->dd[i] = dds;
  }
  if (F & F_LEDGER) {
    p->du[i] = LSUM(S->du);
    w->wpow[i] = LSUM(S->wpow);
    w->wfx[i] = LSUM(S->wfx);
    w->wfy[i] = LSUM(S->wfy);
    SPH_IF3(w->wfz[i] = LSUM(S->wfz);)
  }
  const double sigma_i = LMAXALL(S->sig);
  if (R->fluid) {
    p->ax[i] = LSUM(S->ax) + fp->gx;
    p->ay[i] = LSUM(S->ay) + fp->gy;
    SPH_IF3(p->az[i] = LSUM(S->az) + fp->gz;)
    if (F & F_XSPH) {
      p->xsx[i] = fp->xsph * LSUM(S->xs);
      p->xsy[i] = fp->xsph * LSUM(S->ys);
      SPH_IF3(p->xsz[i] = fp->xsph * LSUM(S->zs);)
    }
  } else {
    p->ax[i] = p->ay[i] = 0.0;
    SPH_IF3(p->az[i] = 0.0;)
  }
  return sigma_i;
#undef LMAXALL
#undef LSUM
}

/* Particle i's row, fluid (fluid_row 1: every pair's force, fluid-fluid
 * terms, the ledger's wall power) or a wall particle's (0: its density's
 * rates, and with the ledger its half of the heat of its pairs with
 * fluid); fluid_row a literal at both calls. Returns sigma_i. */
LOOP_ATTR double SPH_PT_XGLUE(row, FL)(sph_particles *restrict p, const sph_nlist *restrict l,
                                       const sph_force_params *restrict fp,
                                       sph_force_work *restrict w, size_t i, const unsigned F,
                                       const int fluid_row) {
  size_t cnt;
  const uint32_t *restrict nb = SPH_PT_XGLUE(row_entries, FL)(l, fp, w, i, F, &cnt);
  LROW R;
  SPH_PT_XGLUE(row_begin, FL)(&R, p, fp, w, i, F, cnt);
  R.fluid = fluid_row; /* (as row_begin found it: a constant from here on) */
  const LA azero = LAOP(all)(0.0);
  LSUMS S = {.drho = azero,
             .ax = azero,
             .ay = azero,
             .xs = azero,
             .ys = azero,
             .sig = azero,
             .dd = azero,
             .du = azero,
             .wpow = azero,
             .wfx = azero,
             .wfy = azero,
             .rd = azero};
  SPH_IF3(S.az = S.zs = S.wfz = azero;)
  const sph_force_hot *restrict hot = w->hot;
  for (size_t k = 0; k < cnt; k += LW) {
    const uint32_t *restrict jk = nb + k; /* this iteration's neighbours */
#if LW == 1
    LNB nbr = &hot[jk[0]]; /* read field by field, as needed */
#else
    LHOT(g); /* the neighbours' packed records, g[H_field] */
    LNB nbr = g;
#endif
    LPAIR G;
    if (!SPH_PT_XGLUE(pair_density, FL)(&R, &S, &G, jk, k, nbr)) continue;
    if (!fluid_row && !(F & F_LEDGER)) continue; /* a wall particle needs no other pair terms */
    /* with the ledger, XSPH and the Riemann pressure: m_j of fluid neighbours (0 for walls)
     * as their kind */
    const LT fmj = (F & (F_XSPH | F_LEDGER | F_RIEMANN)) ? LSET(E_ARR, w->fm) : R.zero;
    const LMASK fluid_j = LOP(lt)(R.zero, fmj);
    const LVIS V = SPH_PT_XGLUE(pair_viscous_velocity, FL)(&R, &G, jk);
    const LNORM N = SPH_PT_XGLUE(pair_wall_normals, FL)(&R, &G, &V, jk);
    LVEC pa;
    LT heat = R.zero; /* this particle's half of the pair's heat (energy ledger) */
    SPH_PT_XGLUE(pair_momentum, FL)(&R, &G, &V, &N, jk, nbr, &pa, &heat);
    if (fluid_row) SPH_PT_XGLUE(pair_fluid_fluid, FL)(&R, &S, &G, fluid_j, jk, nbr);
    if (F & F_LEDGER) {
      SPH_PT_XGLUE(pair_ledger, FL)(&R, &S, fluid_j, jk, nbr, pa, heat);
      if (!fluid_row) continue;
    }
    LACC(S.ax, pa.c[0]);
    LACC(S.ay, pa.c[1]);
    SPH_IF3(LACC(S.az, pa.c[2]);)
  }
  return SPH_PT_XGLUE(row_end, FL)(&R, &S);
}

/* A fluid particle's row: every pair's force, compiled for each term set. */
LOOP_ATTR double SPH_PT_XGLUE(fluid_row, FL)(sph_particles *restrict p, const sph_nlist *restrict l,
                                             const sph_force_params *restrict fp,
                                             sph_force_work *restrict w, size_t i,
                                             const unsigned F) {
  return SPH_PT_XGLUE(row, FL)(p, l, fp, w, i, F, 1);
}
/* A wall particle's row with the energy ledger (its density's rates and
 * its half of the heat of its pairs with fluid): one function per flavour
 * for every term set (F at run time, LOOP_SHARED: not inlined, not cloned),
 * which keeps the loops' code small; the same bits as a row compiled for F
 * (the run-time loops', tests/test_pair_terms.c). Without the ledger a
 * wall row sums pair_density_FL only and is compiled into each loop. */
LOOP_SHARED double SPH_PT_XGLUE(wall_row,
                                FL)(sph_particles *restrict p, const sph_nlist *restrict l,
                                    const sph_force_params *restrict fp, sph_force_work *restrict w,
                                    size_t i, const unsigned F) {
  return SPH_PT_XGLUE(row, FL)(p, l, fp, w, i, F, 0);
}

/* Returns sigma_i, the step rule's max_j |h v_ij.r_ij / r_ij^2| (0 for a
 * row that sums nothing). */
LOOP_ATTR double SPH_PT_XGLUE(interact, FL)(sph_particles *restrict p, const sph_nlist *restrict l,
                                            const sph_force_params *restrict fp,
                                            sph_force_work *restrict w, size_t i,
                                            const unsigned Fc) {
  const unsigned F = SPH_TERMS(Fc, F_LITERAL(Fc), w->terms);
  /* no rates: mirror particles, repulsive wall particles, adami wall particles (whose density
   * and pressure are the fluid's, walls/adami.h) */
  if (p->kind[i] == SPH_KIND_MIRROR || (p->flags[i] & (SPH_FLAG_REPULSIVE | SPH_FLAG_ADAMI))) {
    p->drho[i] = p->ax[i] = p->ay[i] = 0.0;
    SPH_IF3(p->az[i] = 0.0;)
    if (F & F_LEDGER) p->du[i] = w->wpow[i] = w->wfx[i] = w->wfy[i] = 0.0;
    SPH_IF3(if (F & F_LEDGER) w->wfz[i] = 0.0;)
    if ((F & F_DDIFF) && (F & F_LEDGER)) w->dd[i] = 0.0;
    return 0.0;
  }
  if (p->kind[i] == SPH_KIND_FLUID) return SPH_PT_XGLUE(fluid_row, FL)(p, l, fp, w, i, F);
  /* a wall row without the ledger (its density's rates only) inlined, the ledger's shared */
  if (!(F & F_LEDGER)) return SPH_PT_XGLUE(row, FL)(p, l, fp, w, i, F & ~F_LEDGER, 0);
  return SPH_PT_XGLUE(wall_row, FL)(p, l, fp, w, i, F);
}

#undef E_ARR
#undef E_HOT
#undef GATHER
#undef LNB
#undef LNORM
#undef LVIS
#undef LPAIR
#undef LSUMS
#undef LROW
#undef LSYM
#undef LVEC
#undef LTERM
#undef LOP
#undef LT
