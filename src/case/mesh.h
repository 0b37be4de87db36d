/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * mesh.h - closed triangle surfaces read from mesh files (STL, ASCII or
 * binary, OBJ, PLY and the other formats of the Open Asset Import Library,
 * Assimp) for the shapes of fluid blocks (shape.h): the surface welded by
 * exact coordinates, checked closed, consistently oriented and outward,
 * and its inside as a winding number. Internal to the library.
 */
#ifndef SPH_MESH_H
#define SPH_MESH_H

#include <stddef.h>

#include "case/case.h"

/* The largest mesh file read (bytes), checked before it is read: a binary
 * STL of about 20 million triangles. */
#define SPH_MESH_MAX_BYTES 1000000000L

/* Reads the surface in the file at path, each coordinate v becoming
 * scale v + offset (in double precision from the file's own, which for
 * binary STL and for Assimp's readers is single), into *out. 0, or -1
 * with the reason (the file's, the format's, or the first open,
 * non-manifold or wrongly turned edge, or an inward surface) in why. */
int sph_mesh_read(const char *path, double scale, const double offset[3], sph_mesh **out, char *why,
                  size_t len);
void sph_mesh_free(sph_mesh *m);

/* Its bounding box, its volume (positive: outward), its triangle count. */
void sph_mesh_bounds(const sph_mesh *m, double lo[3], double hi[3]);
double sph_mesh_volume(const sph_mesh *m);
size_t sph_mesh_triangles(const sph_mesh *m);

/* The winding number of the surface around the point x: 1 inside, 0
 * outside; any other value where the surface crosses or overlaps itself.
 * Counted along the ray from x up the z axis, each triangle it crosses
 * adding the sign of its normal's z; a ray through an edge or a vertex
 * is counted once by a fixed rule on the edges (each edge's function
 * computed from its lexicographically lower end), so the count is exact
 * for the rays of a lattice as well as between them. */
int sph_mesh_winding(const sph_mesh *m, const double x[3]);

/* The point c of the surface closest to x, the outward unit normal of its triangle there,
 * and the distance, over the triangles not wholly at or below the height `floor`; every
 * triangle looked at (a wall's few layers of particles per mesh). */
double sph_mesh_nearest(const sph_mesh *m, const double x[3], double floor, double c[3],
                        double n[3]);

#endif
