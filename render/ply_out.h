/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ply_out.h - a triangle mesh (isosurface.h) as a PLY file (Turk 1994,
 * the Stanford polygon format; binary little-endian), which ParaView,
 * meshio, MeshLab and Blender open.
 *
 * Elements: `vertex` with float x y z and nx ny nz (the unit outward
 * normal) and, when the mesh has one, a float property named after the
 * field it was coloured by; `face` with a `list uchar uint vertex_indices`
 * of three indices, counter-clockwise from outside. Comment lines say
 * what the surface is, the snapshot's time and the lattice's cell.
 * Written atomically ("<path>.tmp", then rename), as the PNGs are.
 */
#ifndef SPH_RENDER_PLY_OUT_H
#define SPH_RENDER_PLY_OUT_H

#include "core/error.h"
#include "isosurface.h"

/* Writes m to path; field names the vertices' values (m->val; NULL if
 * none); comments are extra comment lines (n_comments of them). */
int rply_write(const char *path, const rmesh *m, const char *field, const char *const *comments,
               int n_comments, sph_error *err);

#endif
