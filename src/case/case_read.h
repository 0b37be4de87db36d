/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * case_read.h - what the readers of the case file's sections share
 * (internal to src/case/): the reader's context, the helpers several
 * sections use, and each section file's entry point. case.c reads the
 * top level, physics, numerics and time and calls geometry.c and output.c
 * in schema order (see case.c for the algorithm and its invariants).
 */
#ifndef SPH_CASE_READ_H
#define SPH_CASE_READ_H

#include "case/case.h"
#include "case/yaml_tree.h"

typedef sph_yaml_node node;
typedef sph_yaml_entry entry;
typedef sph_yaml_range range;

/* The reader's context and what the cross-checks between sections need. */
typedef struct ctx {
  sph_yaml_ctx t;
  const node *dx_node;       /* numerics.dx, for the cross-checks */
  const node *stop_node;     /* time.stop if given */
  const node *shifting_node; /* numerics.shifting if given */
  const node *cgrad_node;    /* numerics.gradient_correction if given */
  const node *air_node;      /* physics.air if given */
  const node *air_map;       /* physics.air's mapping if given */
} ctx;

/* names[k] of a NULL-terminated list of choices, "unknown" past its end. */
const char *sph_case_choice_name(const char *const *names, int k);

/* A name made of letters, digits, '_', '-' and '.' at path.key (case.c). */
int sph_case_read_plain_name(const ctx *x, const node *m, const char *path, const char *key,
                             const char **out);

/* A block's bottom and top along the vertical (y; z in 3-D). */
static inline double sph_case_block_bottom(const sph_fluid_block *f) {
#if SPH_DIM == 2
  return f->y0;
#else
  return f->z0;
#endif
}
static inline double sph_case_block_top(const sph_fluid_block *f) {
#if SPH_DIM == 2
  return f->y1;
#else
  return f->z1;
#endif
}

/* geometry.c: the geometry section of the tree root (numerics read
 * before it), and the particles it makes at dx, from above (c->est_fluid,
 * c->est_wall). */
int sph_case_read_geometry(const ctx *x, const node *root, sph_case *c);
void sph_case_estimate_particles(sph_case *c);

/* air.c: physics.air of the physics mapping, and (after the geometry and
 * the numerics) whether the two-phase terms cover the case. */
int sph_case_read_air(ctx *x, const node *physics, sph_case *c);
int sph_case_check_air(const ctx *x, sph_case *c);
/* The air's material keys at their defaults (set_defaults), and its
 * listing "{rho0: ..., ...}" into buf (snprintf's return). */
void sph_case_air_defaults(sph_case *c);
int sph_case_air_listing(const sph_case *c, char *buf, size_t n);
/* output.c: the output section (geometry and time read before it). */
int sph_case_read_output(const ctx *x, const node *root, sph_case *c);

#endif
