/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * surface.h - the free surface of a 3-D snapshot as a mesh: the level 1/2
 * of the fluid's kernel sum (interp3d.h) on a lattice of a given cell,
 * by marching cubes (isosurface.h), with the snapshot's field interpolated
 * to its vertices.
 */
#ifndef SPH_RENDER_SURFACE_H
#define SPH_RENDER_SURFACE_H

#include "core/error.h"
#include "isosurface.h"
#include "snapdata.h"

/* The level of the kernel sum taken as the free surface. */
#define RSURFACE_LEVEL 0.5

/* The cell of the lattice: given if > 0, else half the snapshot's particle
 * spacing (its attribute dx). An error if neither is known. */
int rsurface_cell(const rsnap *s, double given, double *cell, sph_error *err);

/* The free surface of s (loaded with its volumes, rsnap_load_volumes),
 * with s->val at the vertices if with_field and s has a field. */
int rsurface_of(const rsnap *s, double cell, int with_field, rmesh *m, sph_error *err);

#endif
