/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * spheres.h - particles of a 3-D snapshot as lit spheres, seen by a camera
 * (camera.h), into an RGBA image.
 *
 * Each sphere is a screen-facing quad whose fragments cast their ray onto
 * the sphere (perspective or orthographic), light the hit point (ambient,
 * diffuse and a little specular from a fixed light above-left of the eye)
 * and write its depth, so spheres cut into one another as solid balls do.
 * The image is drawn at samples x samples sub-pixels per pixel and each
 * pixel is the rounded mean of its sub-pixels, in integers. The spheres are
 * drawn in the order given, with a less-than depth test: the image depends
 * only on the inputs and the driver's rasterisation (llvmpipe's is the
 * same in every process and for any thread count).
 */
#ifndef SPH_RENDER_SPHERES_H
#define SPH_RENDER_SPHERES_H

#include <stddef.h>
#include <stdint.h>

#include "camera.h"
#include "canvas.h"
#include "core/error.h"
#include "gl_api.h"

/* One sphere: centre (m), radius (m), colour (straight RGBA; alpha 255). */
typedef struct rsphere {
  float c[3];
  float r;
  uint8_t rgba[4];
} rsphere;

/* Draws the n spheres over background bg into rgba (w * h * 4 bytes, top
 * row first, alpha 255) with the current context of gl. Fails, naming the
 * limit, if the image at that many samples exceeds the driver's
 * framebuffer size or 1 GiB. */
int rspheres_draw(const rgl *gl, const rcamera *cam, int w, int h, int samples, const rsphere *s,
                  size_t n, rcolor bg, uint8_t *rgba, sph_error *err);

#endif
