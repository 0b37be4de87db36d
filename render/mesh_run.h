/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * mesh_run.h - the mesh mode: `sph-render mesh SNAPSHOT|RUN_DIR... -o OUT`
 * writes each 3-D snapshot's free surface (surface.h) as a PLY file
 * (ply_out.h): OUT itself for one snapshot named .ply, else
 * OUT/surface_NNNN.ply numbered like the snapshot.
 */
#ifndef SPH_RENDER_MESH_RUN_H
#define SPH_RENDER_MESH_RUN_H

#include "core/error.h"
#include "options.h"

int rmesh_run(const roptions *o, const char *prog, sph_error *err);

#endif
