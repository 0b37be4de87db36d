/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * lines_gl.h - straight segments in a 3-D view (the tank's edges), drawn
 * into a scene (scene3d.h) with the depth test, so that what stands in
 * front of a segment hides it.
 *
 * Each segment is a quad facing the eye, `width` pixels of the frame
 * buffer wide with square caps, its depth the segment's pulled 1e-4 of the
 * depth range towards the eye (a segment lying on a surface shows on it);
 * it is blended over what is drawn with the colour's alpha and writes no
 * depth.
 */
#ifndef SPH_RENDER_LINES_GL_H
#define SPH_RENDER_LINES_GL_H

#include <stddef.h>
#include <stdint.h>

#include "core/error.h"
#include "gl_api.h"

/* Draws n segments (6 floats each: both ends, m) in colour rgba (straight
 * alpha) with the camera's matrices into the current frame buffer of
 * fw x fh pixels. */
int rlines_gl(const rgl *gl, const float view[16], const float proj[16], int fw, int fh,
              double width, const float *seg, size_t n, const uint8_t rgba[4], sph_error *err);

#endif
