/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * pair_terms.h - the physics of one particle pair i, j, written once.
 *
 * Every term of the interaction pass (continuity, density diffusion, pressure, artificial
 * viscosity, viscous stress, Morris viscosity, XSPH, the energy ledger's
 * heat and wall power, the Lennard-Jones wall force) and the branch-free
 * cubic spline they use is a small always-inline function in
 * pair_terms_body.h, written in the operations of src/core/lanes.h. This
 * header includes that body once per arithmetic flavour, so that
 *
 *   name_v1    serves the scalar loop (one pair at a time),
 *   name_v4e   the portable four-lane loop,
 *   name_v4x   the AVX2 four-lane loop (where SPH_LANES_AVX is defined),
 *   name_v8z   the AVX-512 eight-lane loop (where SPH_LANES_AVX512 is),
 *
 * and each lane of a lane loop does, pair for pair, exactly the IEEE
 * operations of the scalar loop (tests/test_pair_terms.c holds them to one
 * another and to a naive all-pairs oracle). The loops that call them are
 * in src/solver/interact.h; doc/adding-a-term.md says how to add one.
 *
 * Notation (paper A = dam-break paper, paper B = breaking-wave paper):
 * r_ij = x_i - x_j, v_ij = v_i - v_j, grad_i W_ij = F_ij r_ij with
 * F_ij = (1/r) dW/dr, h_ij the pair's smoothing length, rho_ij the mean
 * density, prho2 = p / rho^2.
 */
#ifndef SPH_PAIR_TERMS_H
#define SPH_PAIR_TERMS_H

#include "core/dim.h"
#include "core/lanes.h"

#define SPH_PT_GLUE(a, b) a##_##b
#define SPH_PT_XGLUE(a, b) SPH_PT_GLUE(a, b)

#define FL v1
#define PT_ATTR static inline __attribute__((always_inline))
#include "physics/pair_terms_body.h"
#undef PT_ATTR
#undef FL

#define FL v4e
#define PT_ATTR static inline __attribute__((always_inline))
#include "physics/pair_terms_body.h"
#undef PT_ATTR
#undef FL

#ifdef SPH_LANES_AVX
#define FL v4x
#define PT_ATTR static inline __attribute__((always_inline, target("avx2")))
#include "physics/pair_terms_body.h"
#undef PT_ATTR
#undef FL
#endif

#ifdef SPH_LANES_AVX512
#define FL v8z
#define PT_ATTR static inline __attribute__((always_inline, target("avx512f")))
#include "physics/pair_terms_body.h"
#undef PT_ATTR
#undef FL
#endif

#endif
