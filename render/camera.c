/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * camera.c - the orbit camera of a 3-D view (see camera.h).
 *
 * The frame: forward f = -(cos e sin a, -cos e cos a, sin e) from the eye
 * to look_at, right r = (cos a, sin a, 0) (horizontal, so the top view
 * keeps x to the right), up u = r x f = (-sin a sin e, cos a sin e, cos e).
 */
#include "config.h"

#include "camera.h"

#include <math.h>
#include <string.h>

#define DEG (3.14159265358979323846 / 180.0)
/* the framing's margin: the box fills 1/1.05 of the image */
#define MARGIN 1.05

static const struct {
  const char *name;
  double azimuth, elevation;
} views[] = {{"iso", 30.0, 25.0}, {"front", 0.0, 0.0}, {"side", 90.0, 0.0}, {"top", 0.0, 90.0}};

int rcamera_named(const char *name, double *azimuth, double *elevation) {
  for (size_t k = 0; k < sizeof views / sizeof views[0]; k++)
    if (strcmp(views[k].name, name) == 0) {
      *azimuth = views[k].azimuth;
      *elevation = views[k].elevation;
      return 0;
    }
  return -1;
}

const char *rcamera_names(void) { return "iso, front, side, top"; }

static double dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void rcamera_frame_of(const rcamera *c, rcamera_frame *f) {
  const double a = c->azimuth * DEG, e = c->elevation * DEG;
  const double ca = cos(a), sa = sin(a), ce = cos(e), se = sin(e);
  const double dir[3] = {ce * sa, -ce * ca, se}; /* from look_at to the eye */
  for (int k = 0; k < 3; k++) {
    f->eye[k] = c->look_at[k] + c->distance * dir[k];
    f->forward[k] = -dir[k];
  }
  f->right[0] = ca, f->right[1] = sa, f->right[2] = 0.0;
  f->up[0] = -sa * se, f->up[1] = ca * se, f->up[2] = ce;
}

void rcamera_frame_box(rcamera *c, const double lo[3], const double hi[3], double aspect) {
  for (int k = 0; k < 3; k++)
    c->look_at[k] = 0.5 * (lo[k] + hi[k]);
  rcamera_frame f;
  rcamera_frame_of(c, &f);
  const double t = tan(0.5 * c->fov * DEG);
  double need = 0.0, half = 0.0, reach = 0.0;
  for (int q = 0; q < 8; q++) {
    const double d[3] = {(q & 1 ? hi[0] : lo[0]) - c->look_at[0],
                         (q & 2 ? hi[1] : lo[1]) - c->look_at[1],
                         (q & 4 ? hi[2] : lo[2]) - c->look_at[2]};
    const double r = fabs(dot(d, f.right)), u = fabs(dot(d, f.up)), fw = dot(d, f.forward);
    const double extent = fmax(u, r / aspect); /* half the view height it needs */
    half = fmax(half, extent);
    need = fmax(need, MARGIN * extent / t - fw);
    reach = fmax(reach, sqrt(dot(d, d)));
  }
  if (c->ortho) {
    c->height = 2.0 * MARGIN * half;
    c->distance = 2.0 * reach + 1e-6; /* in front of the whole box */
  } else {
    c->distance = fmax(need, 1.01 * reach);
  }
}

int rcamera_project(const rcamera *c, int w, int h, const double p[3], double *px, double *py,
                    double *depth) {
  rcamera_frame f;
  rcamera_frame_of(c, &f);
  const double d[3] = {p[0] - f.eye[0], p[1] - f.eye[1], p[2] - f.eye[2]};
  const double xe = dot(d, f.right), ye = dot(d, f.up), ze = dot(d, f.forward);
  const double aspect = (double)w / (double)h;
  double half_h; /* half the view's height at the point's depth */
  if (c->ortho)
    half_h = 0.5 * c->height;
  else
    half_h = ze * tan(0.5 * c->fov * DEG);
  *depth = ze;
  if (!c->ortho && !(ze > 0.0)) {
    *px = *py = NAN;
    return -1;
  }
  const double nx = xe / (half_h * aspect), ny = ye / half_h;
  *px = 0.5 * (nx + 1.0) * (double)w;
  *py = 0.5 * (1.0 - ny) * (double)h;
  return 0;
}

void rcamera_matrices(const rcamera *c, double aspect, double near_d, double far_d, float view[16],
                      float proj[16]) {
  rcamera_frame f;
  rcamera_frame_of(c, &f);
  memset(view, 0, 16 * sizeof *view);
  memset(proj, 0, 16 * sizeof *proj);
  for (int k = 0; k < 3; k++) { /* rows r, u, -f */
    view[4 * k + 0] = (float)f.right[k];
    view[4 * k + 1] = (float)f.up[k];
    view[4 * k + 2] = (float)-f.forward[k];
  }
  view[12] = (float)-dot(f.right, f.eye);
  view[13] = (float)-dot(f.up, f.eye);
  view[14] = (float)dot(f.forward, f.eye);
  view[15] = 1.0f;
  if (c->ortho) {
    const double hh = 0.5 * c->height, hw = hh * aspect;
    proj[0] = (float)(1.0 / hw);
    proj[5] = (float)(1.0 / hh);
    proj[10] = (float)(-2.0 / (far_d - near_d));
    proj[14] = (float)(-(far_d + near_d) / (far_d - near_d));
    proj[15] = 1.0f;
  } else {
    const double t = tan(0.5 * c->fov * DEG);
    proj[0] = (float)(1.0 / (t * aspect));
    proj[5] = (float)(1.0 / t);
    proj[10] = (float)(-(far_d + near_d) / (far_d - near_d));
    proj[11] = -1.0f;
    proj[14] = (float)(-2.0 * far_d * near_d / (far_d - near_d));
  }
}

int rcamera_check(const rcamera *c, sph_error *err) {
  for (int k = 0; k < 3; k++)
    if (!isfinite(c->look_at[k])) return sph_error_set(err, "--look-at: expected finite numbers");
  if (!(c->azimuth > -1e6 && c->azimuth < 1e6))
    return sph_error_set(err, "--azimuth: expected a finite angle in degrees, got %g", c->azimuth);
  if (!(c->elevation >= -90.0 && c->elevation <= 90.0))
    return sph_error_set(err, "--elevation: expected an angle from -90 to 90 degrees, got %g",
                         c->elevation);
  if (!c->ortho && !(c->fov > 0.0 && c->fov < 180.0))
    return sph_error_set(err, "--fov: expected an angle between 0 and 180 degrees, got %g", c->fov);
  if (!(c->distance > 0.0 && isfinite(c->distance)))
    return sph_error_set(err, "--distance: expected a positive number of metres, got %g",
                         c->distance);
  if (c->ortho && !(c->height > 0.0 && isfinite(c->height)))
    return sph_error_set(err, "the orthographic view's height must be positive, got %g", c->height);
  return 0;
}
