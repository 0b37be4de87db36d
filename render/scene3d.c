/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * scene3d.c - the frame buffer, depth range and read-back of a 3-D view
 * (see scene3d.h).
 */
#include "config.h"

#include "scene3d.h"

#include <math.h>

#include "gl_supersample.h"
#include "lines_gl.h"
#include "mesh_gl.h"

/* Widens [lo, hi] by the depth along the view of point c, +- r. */
static void extend(const rcamera_frame *f, const float c[3], double r, double *lo, double *hi) {
  const double d = (c[0] - f->eye[0]) * f->forward[0] + (c[1] - f->eye[1]) * f->forward[1] +
                   (c[2] - f->eye[2]) * f->forward[2];
  *lo = fmin(*lo, d - r);
  *hi = fmax(*hi, d + r);
}

/* The nearest and farthest depth of the scene in front of the eye. */
static void depth_range(const rcamera *cam, const rscene3d *sc, double *near_d, double *far_d) {
  rcamera_frame f;
  rcamera_frame_of(cam, &f);
  double lo = INFINITY, hi = 0.0;
  for (size_t i = 0; i < sc->n_spheres; i++)
    extend(&f, sc->spheres[i].c, sc->spheres[i].r, &lo, &hi);
  for (int k = 0; k < RSCENE3D_MESHES; k++)
    for (size_t i = 0; sc->mesh[k] && i < sc->mesh[k]->nv; i++)
      extend(&f, sc->mesh[k]->p + 3 * i, 0.0, &lo, &hi);
  for (size_t i = 0; i < 2 * sc->n_segments; i++)
    extend(&f, sc->segments + 3 * i, 0.0, &lo, &hi);
  if (!(hi > 0.0)) hi = cam->distance;
  if (!(lo < hi)) lo = 0.5 * hi; /* nothing in front of the eye */
  *far_d = 1.01 * hi;
  /* in front of the eye: perspective depth needs near > 0 (anything
   * nearer than far/1e4 is cut) */
  *near_d = cam->ortho ? fmin(lo, 0.0) - 0.01 * hi : fmax(0.99 * lo, 1e-4 * hi);
}

int rscene3d_draw(const rgl *gl, const rcamera *cam, int w, int h, int samples, const rscene3d *sc,
                  rcolor bg, uint8_t *out, sph_error *err) {
  if (w < 1 || h < 1) return sph_error_set(err, "3-D view: bad size %dx%d", w, h);
  samples = rgl_fit_samples(gl, w, h, samples, 8.0, err); /* colour and depth */
  if (samples < 0) return -1;
  const int dw = w * samples, dh = h * samples;
  GLuint fbo = 0, rb[2] = {0, 0};
  int rc = 0;
  gl->GenFramebuffers(1, &fbo);
  gl->BindFramebuffer(GL_FRAMEBUFFER, fbo);
  gl->GenRenderbuffers(2, rb);
  gl->BindRenderbuffer(GL_RENDERBUFFER, rb[0]);
  gl->RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, dw, dh);
  gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
  gl->BindRenderbuffer(GL_RENDERBUFFER, rb[1]);
  gl->RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, dw, dh);
  gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
  if (gl->CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    rc = sph_error_set(err, "3-D view: cannot make a %dx%d framebuffer with depth", dw, dh);
    goto done;
  }
  double near_d, far_d;
  depth_range(cam, sc, &near_d, &far_d);
  float view[16], proj[16];
  rcamera_matrices(cam, (double)w / (double)h, near_d, far_d, view, proj);
  gl->Viewport(0, 0, dw, dh);
  gl->Disable(GL_SCISSOR_TEST);
  gl->Disable(GL_BLEND);
  gl->Enable(GL_DEPTH_TEST);
  gl->DepthFunc(GL_LESS);
  gl->ClearColor(bg.r / 255.0f, bg.g / 255.0f, bg.b / 255.0f, 1.0f);
  gl->ClearDepth(1.0);
  gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  rc = rspheres_gl(gl, view, proj, cam->ortho, sc->spheres, sc->n_spheres, err);
  size_t nt = 0;
  for (int k = 0; k < RSCENE3D_MESHES; k++)
    if (!rc && sc->mesh[k]) {
      rc = rmesh_gl(gl, view, proj, cam->ortho, sc->mesh[k], sc->mesh_rgba[k], err);
      nt += sc->mesh[k]->nt;
    }
  if (!rc)
    rc = rlines_gl(gl, view, proj, dw, dh, sc->segment_width * samples, sc->segments,
                   sc->n_segments, sc->segment_rgba, err);
  if (rc) goto done;
  gl->Finish();
  if (gl->GetError() != GL_NO_ERROR) {
    rc = sph_error_set(err, "3-D view: OpenGL error while drawing %zu spheres and %zu triangles",
                       sc->n_spheres, nt);
    goto done;
  }
  rc = rgl_read_averaged(gl, w, h, samples, 4, out, "3-D view", err);
done:
  gl->Disable(GL_DEPTH_TEST); /* the canvas draws without depth and with blending */
  gl->Enable(GL_BLEND);
  gl->DeleteRenderbuffers(2, rb);
  gl->DeleteFramebuffers(1, &fbo);
  return rc;
}
