/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * adami.h - the generalized wall boundary condition of Adami, Hu and Adams
 * (2012) (AHA12 in doc/method.md): wall particles that carry the fluid's
 * pressure extrapolated to them, and, in the viscous terms only, the
 * velocity that makes the fluid's vanish on the wall.
 *
 * Before every interaction pass each wall particle w of an adami wall
 * (SPH_FLAG_ADAMI) takes, from the fluid particles f within its support,
 *
 *   p_w = [ sum_f p_f W_wf + (g - a_w) . sum_f rho_f r_wf W_wf ] / sum_f W_wf   (AHA12 eq. 27)
 *
 * with r_wf = x_w - x_f, g the body force and a_w the wall's own
 * acceleration (0 at rest; a prescribed motion's, motion.h), so that a
 * fluid at rest in a tank presses on the wall particles exactly as the
 * hydrostatic field continued into the wall would; p_w is clipped at 0
 * (a wall pushes the fluid, never pulls it: as the mdbc walls here and
 * TrixiParticles' AdamiPressureExtrapolation do) except where it stands
 * for the air of two phases, whose gauge pressure has no floor (below 0
 * the air is below its ambient pressure, not pulling), and 0 where no
 * fluid is within reach. Its density is the equation of state's inverse of p_w
 * (AHA12 eq. 28), so the pair terms read rho_w and p_w as they read a
 * fluid particle's. The no-slip velocity of AHA12 eq. (23)-(24),
 *
 *   v_w' = 2 v_w - sum_f v_f W_wf / sum_f W_wf,
 *
 * is what the viscous terms (artificial and laminar viscosity, the
 * strain rate) read for the wall particle (v_w where no fluid is within
 * reach); a free-slip adami wall (SPH_FLAG_INVISCID) takes no viscous pair
 * term at all (AHA12 §2.3.1). The continuity and the pressure read the
 * wall's own velocity. An adami wall particle has no rates: its density
 * is not integrated and its row of the main pass is skipped; with the
 * energy ledger its pairs with fluid are passive (the fluid particle
 * takes the pair's whole heat, the wall's motion its work), as mirror
 * and repulsive walls' are.
 *
 * Each wall particle reads its own row of the neighbour list, in storage
 * order, and writes only itself: the same bits for any thread count.
 */
#ifndef SPH_ADAMI_H
#define SPH_ADAMI_H

#include "core/particles.h"
#include "neighbours/grid.h"
#include "physics/eos.h"
#include "physics/models.h"
#include "walls/walls.h"

typedef struct sph_adami_params {
  sph_kernel_kind kernel;    /* the fluid's kernel */
  double h;                  /* its smoothing length when uniform */
  int var_h;                 /* per-particle h: a pair's is the mean h_wf */
  double g[SPH_DIM];         /* the body force per unit mass */
  sph_eos eos;               /* the fluid's equation of state */
  const sph_walls *walls;    /* the moving walls' laws (a_w), or NULL: every wall at rest */
  double t;                  /* the time the walls stand at (their last sph_walls_move) */
  const unsigned char *skip; /* or NULL: the wall particles i with skip[i] set are left alone
                                (a rank's walls made before: solver/ranks.c) */
} sph_adami_params;

/* Sets p->p and p->rho of every adami wall particle from its fluid
 * neighbours in the list l (complete for the support 2 h on p's
 * positions; with two phases from one phase's neighbours, the phase of
 * the fluid particle nearest the wall particle's mirror point x_w + m_w,
 * which p->wphase names: the wall stands for the mirror image of the fluid
 * beside it, a particle of that phase at that phase's pressure, in the
 * other phase's rows as in its own), and, unless gv is NULL,
 * gv[axis][w] its no-slip velocity (the other particles' entries are not touched). In a rank's
 * store (solver/ranks.c: a list with empty rows, grid.h no_row) a ghost wall particle whose row
 * lists only ghosts with empty rows is read by no row of the pass and is skipped: p and rho as they
 * were, gv its own velocity. Returns how many wall particles had fluid within reach. */
size_t sph_wall_adami(sph_particles *p, const sph_nlist *l, const sph_adami_params *ap,
                      double *const *gv);
/* The same for the adami wall particles which[0..k) alone. */
size_t sph_wall_adami_list(sph_particles *p, const sph_nlist *l, const sph_adami_params *ap,
                           double *const *gv, const size_t *which, size_t k);

#endif
