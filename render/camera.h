/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * camera.h - the camera of a 3-D view: an orbit about a point, named views,
 * the framing of a box, and the projection of world points (z up, metres)
 * onto an image of w x h pixels (origin top-left, y down, as the canvas).
 *
 * The eye sits at look_at + distance (cos e sin a, -cos e cos a, sin e):
 * azimuth a = 0 and elevation e = 0 look along +y (x to the right, z up:
 * the 2-D picture), a = 90 degrees from +x along -x (y to the right),
 * e = 90 straight down (x to the right, y up the image). Perspective with a
 * vertical field of view, or orthographic with a view height.
 */
#ifndef SPH_RENDER_CAMERA_H
#define SPH_RENDER_CAMERA_H

#include "core/error.h"

typedef struct rcamera {
  double look_at[3];
  double azimuth, elevation; /* degrees */
  double distance;           /* from look_at to the eye (m) */
  double fov;                /* vertical field of view (degrees), perspective */
  int ortho;                 /* orthographic: the view is `height` metres high */
  double height;
} rcamera;

/* A camera's frame: the eye, and its right, up and forward unit vectors. */
typedef struct rcamera_frame {
  double eye[3], right[3], up[3], forward[3];
} rcamera_frame;

/* The named views: "iso" (azimuth 30, elevation 25), "front" (0, 0),
 * "side" (90, 0), "top" (0, 90). Returns -1 for another name. */
int rcamera_named(const char *name, double *azimuth, double *elevation);
/* The names, for help and errors: "iso, front, side, top". */
const char *rcamera_names(void);

void rcamera_frame_of(const rcamera *c, rcamera_frame *f);

/* Frames the box lo..hi (3 values each) for an image of aspect w/h: looks at
 * its centre and sets the distance (perspective) or the height
 * (orthographic) so that its eight corners lie inside the image with a 5 %
 * margin; keeps the direction and the field of view. */
void rcamera_frame_box(rcamera *c, const double lo[3], const double hi[3], double aspect);

/* The projection of world point p for an image of w x h pixels: its pixel
 * position (px, py; y down) and its distance in front of the eye along the
 * view direction (depth, m; <= 0: behind the eye). Returns 0 if the point is
 * in front of the eye. */
int rcamera_project(const rcamera *c, int w, int h, const double p[3], double *px, double *py,
                    double *depth);

/* The OpenGL matrices (column-major): view (world to eye) and projection
 * (eye to clip) with the given near and far depths. */
void rcamera_matrices(const rcamera *c, double aspect, double near_d, double far_d, float view[16],
                      float proj[16]);

/* Checks a camera's numbers (fov in (0, 180), distance and height > 0,
 * elevation in [-90, 90], all finite); an error names the bad one. */
int rcamera_check(const rcamera *c, sph_error *err);

#endif
