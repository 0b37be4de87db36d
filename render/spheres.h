/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * spheres.h - particles of a 3-D snapshot as lit spheres, drawn into a
 * scene (scene3d.h).
 *
 * Each sphere is a screen-facing quad whose fragments cast their ray onto
 * the sphere (perspective or orthographic), light the hit point (ambient,
 * diffuse and a little specular from a fixed light above-left of the eye)
 * and write its depth, so spheres cut into one another as solid balls do.
 * The spheres are drawn in the order given.
 */
#ifndef SPH_RENDER_SPHERES_H
#define SPH_RENDER_SPHERES_H

#include <stddef.h>
#include <stdint.h>

#include "core/error.h"
#include "gl_api.h"

/* One sphere: centre (m), radius (m), colour (straight RGBA; alpha 255). */
typedef struct rsphere {
  float c[3];
  float r;
  uint8_t rgba[4];
} rsphere;

/* Draws the n spheres with the camera's matrices (camera.h) into the
 * current frame buffer, depth-tested. */
int rspheres_gl(const rgl *gl, const float view[16], const float proj[16], int ortho,
                const rsphere *s, size_t n, sph_error *err);

#endif
