/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * gl_supersample.h - a supersampled framebuffer: how many sub-pixels per
 * pixel fit under the driver's limits, and the image read back with each
 * pixel the rounded mean of its sub-pixels, in integers (so a pixel inside
 * a shape of one opaque colour keeps that colour exactly). The raster
 * canvas (canvas_gl.c) and the 3-D spheres (spheres.c) both draw this way.
 */
#ifndef SPH_RENDER_GL_SUPERSAMPLE_H
#define SPH_RENDER_GL_SUPERSAMPLE_H

#include <stdint.h>

#include "core/error.h"
#include "gl_api.h"

/* The framebuffer may take at most this many bytes. */
#define RGL_FRAMEBUFFER_BYTES_MAX (1024.0 * 1024.0 * 1024.0)

/* The sub-pixels per pixel and axis, from `samples` down to 1, that fit an
 * image of w x h pixels into the driver's renderbuffer and viewport sizes
 * and into RGL_FRAMEBUFFER_BYTES_MAX at bytes_per_sample bytes a sub-pixel
 * (-1 with err if w x h itself exceeds the driver's limit). */
int rgl_fit_samples(const rgl *gl, int w, int h, int samples, double bytes_per_sample,
                    sph_error *err);

/* Reads the bound framebuffer (w * samples by h * samples RGBA8) into out,
 * w x h pixels of `channels` bytes (3: RGB; 4: RGBA with alpha 255), top row
 * first, each the rounded mean of its sub-pixels. Errors begin with who. */
int rgl_read_averaged(const rgl *gl, int w, int h, int samples, int channels, uint8_t *out,
                      const char *who, sph_error *err);

#endif
