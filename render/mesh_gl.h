/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * mesh_gl.h - a triangle mesh (isosurface.h) as a lit surface, drawn into
 * a scene (scene3d.h).
 *
 * Each vertex has its own colour and its normal; the fragments are lit as
 * the spheres are (ambient, diffuse and a little specular from the same
 * light above-left of the eye), with the normal interpolated across the
 * triangle (Phong shading) and turned towards the eye where the back of
 * the surface shows (an open mesh seen from inside).
 */
#ifndef SPH_RENDER_MESH_GL_H
#define SPH_RENDER_MESH_GL_H

#include <stdint.h>

#include "core/error.h"
#include "gl_api.h"
#include "isosurface.h"

/* Draws mesh m with one RGBA colour per vertex (4 m->nv bytes) and the
 * camera's matrices into the current frame buffer, depth-tested. */
int rmesh_gl(const rgl *gl, const float view[16], const float proj[16], int ortho, const rmesh *m,
             const uint8_t *rgba, sph_error *err);

#endif
