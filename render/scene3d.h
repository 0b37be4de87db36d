/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * scene3d.h - one 3-D view: spheres (spheres.h) and meshes (mesh_gl.h:
 * the free surface, the obstacles' boxes) seen by a camera (camera.h),
 * into an RGBA image.
 *
 * All are drawn into one frame buffer with a less-than depth test, so
 * spheres and surfaces hide one another as solid objects do, between near
 * and far planes that hold all of them; then segments (the tank's edges,
 * lines_gl.h), hidden where something stands in front of them. The image is drawn at samples x
 * samples sub-pixels per pixel and each pixel is the rounded mean of its
 * sub-pixels, in integers: the image depends only on the inputs and the
 * driver's rasterisation (llvmpipe's is the same in every process and for
 * any thread count).
 */
#ifndef SPH_RENDER_SCENE3D_H
#define SPH_RENDER_SCENE3D_H

#include <stddef.h>
#include <stdint.h>

#include "camera.h"
#include "canvas.h"
#include "core/error.h"
#include "gl_api.h"
#include "isosurface.h"
#include "spheres.h"

#define RSCENE3D_MESHES 2

typedef struct rscene3d {
  const rsphere *spheres; /* drawn first, in this order */
  size_t n_spheres;
  const rmesh *mesh[RSCENE3D_MESHES];        /* then these, NULL for none */
  const uint8_t *mesh_rgba[RSCENE3D_MESHES]; /* 4 bytes per vertex of each */
  const float *segments; /* last, blended: n_segments x (both ends), lines_gl.h */
  size_t n_segments;
  double segment_width; /* pixels of the image */
  uint8_t segment_rgba[4];
} rscene3d;

/* Draws scene sc over background bg into rgba (w * h * 4 bytes, top row
 * first, alpha 255) with the current context of gl. Fails, naming the
 * limit, if the image at that many samples exceeds the driver's
 * framebuffer size or 1 GiB. */
int rscene3d_draw(const rgl *gl, const rcamera *cam, int w, int h, int samples, const rscene3d *sc,
                  rcolor bg, uint8_t *rgba, sph_error *err);

#endif
