/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * vtk_out.h - a triangle mesh (isosurface.h) as a legacy VTK file (the
 * "VTK File Formats" of the VTK User's Guide: version 3.0, BINARY,
 * DATASET UNSTRUCTURED_GRID of triangles; big-endian floats and 32-bit
 * integers), which ParaView and VisIt open with the field as point data
 * (ParaView's PLY reader keeps only positions, normals, colours and
 * texture coordinates: a PLY's field property is dropped there), as meshio
 * does (it reads no legacy POLYDATA: hence the unstructured grid).
 *
 * POINTS (float), CELLS of three indices counter-clockwise from outside,
 * CELL_TYPES (5, the triangle), and POINT_DATA: VECTORS Normals (the unit outward
 * normal; VECTORS, as meshio reads no NORMALS section) and, when
 * the mesh has one, SCALARS named after the field it was coloured by. The
 * header's title line says what the surface is. Written atomically, as the
 * PNGs and PLYs are.
 */
#ifndef SPH_RENDER_VTK_OUT_H
#define SPH_RENDER_VTK_OUT_H

#include "core/error.h"
#include "isosurface.h"

/* Writes m to path; field names the vertices' values (m->val; NULL if
 * none); title is the header's second line (at most 255 characters, one
 * line). */
int rvtk_write(const char *path, const rmesh *m, const char *field, const char *title,
               sph_error *err);

#endif
