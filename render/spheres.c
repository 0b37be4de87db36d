/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * spheres.c - lit sphere impostors on OpenGL 3.3 core (see spheres.h).
 *
 * One instanced draw: each sphere is an instance of a four-vertex strip, a
 * quad facing the eye placed r in front of the sphere's centre and 1.1 r
 * wide each way (a sphere seen off the axis of a perspective view projects
 * a little wider than r on a plane normal to the axis: 1/cos of the
 * half field of view at most). The fragment shader intersects the ray
 * through its point (from the eye, or along the view direction when
 * orthographic) with the sphere, discards a miss, shades the hit point and
 * writes its depth.
 */
#include "config.h"

#include "spheres.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>

#include "gl_program.h"
#include "gl_supersample.h"

static const char *vertex_src =
    "#version 330 core\n"
    "layout(location = 0) in vec3 center;\n"
    "layout(location = 1) in float radius;\n"
    "layout(location = 2) in vec4 color;\n"
    "uniform mat4 view;\n"
    "uniform mat4 proj;\n"
    "out vec3 v_pos;\n"
    "flat out vec3 v_center;\n"
    "flat out float v_radius;\n"
    "flat out vec4 v_color;\n"
    "void main() {\n"
    "  vec2 q = vec2((gl_VertexID & 1) != 0 ? 1.1 : -1.1, (gl_VertexID & 2) != 0 ? 1.1 : -1.1);\n"
    "  vec3 c = (view * vec4(center, 1.0)).xyz;\n"
    "  v_center = c; v_radius = radius; v_color = color;\n"
    "  v_pos = vec3(c.xy + q * radius, c.z + radius);\n"
    "  gl_Position = proj * vec4(v_pos, 1.0);\n"
    "}\n";

static const char *fragment_src =
    "#version 330 core\n"
    "in vec3 v_pos;\n"
    "flat in vec3 v_center;\n"
    "flat in float v_radius;\n"
    "flat in vec4 v_color;\n"
    "uniform mat4 proj;\n"
    "uniform int ortho;\n"
    "out vec4 frag;\n"
    "void main() {\n"
    "  vec3 o = ortho == 1 ? v_pos : vec3(0.0);\n"
    "  vec3 d = ortho == 1 ? vec3(0.0, 0.0, -1.0) : normalize(v_pos);\n"
    "  vec3 oc = o - v_center;\n"
    "  float b = dot(d, oc), c = dot(oc, oc) - v_radius * v_radius, disc = b * b - c;\n"
    "  if (disc < 0.0) discard;\n"
    "  vec3 p = o + (-b - sqrt(disc)) * d;\n"
    "  vec3 n = (p - v_center) / v_radius;\n"
    "  vec3 l = normalize(vec3(-0.35, 0.55, 0.75));\n"
    "  vec3 h = normalize(l - d);\n"
    "  float diffuse = max(dot(n, l), 0.0);\n"
    "  float specular = pow(max(dot(n, h), 0.0), 40.0);\n"
    "  frag = vec4(min(v_color.rgb * (0.3 + 0.7 * diffuse) + 0.15 * specular, 1.0), 1.0);\n"
    "  vec4 clip = proj * vec4(p, 1.0);\n"
    "  gl_FragDepth = 0.5 * clip.z / clip.w + 0.5;\n"
    "}\n";

/* The nearest and farthest depth of the spheres in front of the eye. */
static void depth_range(const rcamera *cam, const rsphere *s, size_t n, double *near_d,
                        double *far_d) {
  rcamera_frame f;
  rcamera_frame_of(cam, &f);
  double lo = INFINITY, hi = 0.0;
  for (size_t i = 0; i < n; i++) {
    const double d = (s[i].c[0] - f.eye[0]) * f.forward[0] + (s[i].c[1] - f.eye[1]) * f.forward[1] +
                     (s[i].c[2] - f.eye[2]) * f.forward[2];
    lo = fmin(lo, d - s[i].r);
    hi = fmax(hi, d + s[i].r);
  }
  if (!(hi > 0.0)) hi = cam->distance;
  if (!(lo < hi)) lo = 0.5 * hi; /* no sphere in front of the eye */
  *far_d = 1.01 * hi;
  /* in front of the eye: perspective depth needs near > 0 (a sphere nearer
   * than far/1e4 is cut) */
  *near_d = cam->ortho ? fmin(lo, 0.0) - 0.01 * hi : fmax(0.99 * lo, 1e-4 * hi);
}

int rspheres_draw(const rgl *gl, const rcamera *cam, int w, int h, int samples, const rsphere *s,
                  size_t n, rcolor bg, uint8_t *out, sph_error *err) {
  if (w < 1 || h < 1) return sph_error_set(err, "spheres: bad size %dx%d", w, h);
  samples = rgl_fit_samples(gl, w, h, samples, 8.0, err); /* colour and depth */
  if (samples < 0) return -1;
  const int dw = w * samples, dh = h * samples;
  GLuint fbo = 0, rb[2] = {0, 0}, vao = 0, vbo = 0, prog = 0;
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
    rc = sph_error_set(err, "spheres: cannot make a %dx%d framebuffer with depth", dw, dh);
    goto done;
  }
  if (!(prog = rgl_program(gl, vertex_src, fragment_src, "spheres", err))) {
    rc = -1;
    goto done;
  }
  double near_d, far_d;
  depth_range(cam, s, n, &near_d, &far_d);
  float view[16], proj[16];
  rcamera_matrices(cam, (double)w / (double)h, near_d, far_d, view, proj);
  gl->UseProgram(prog);
  gl->UniformMatrix4fv(gl->GetUniformLocation(prog, "view"), 1, GL_FALSE, view);
  gl->UniformMatrix4fv(gl->GetUniformLocation(prog, "proj"), 1, GL_FALSE, proj);
  gl->Uniform1i(gl->GetUniformLocation(prog, "ortho"), cam->ortho ? 1 : 0);
  gl->GenVertexArrays(1, &vao);
  gl->BindVertexArray(vao);
  gl->GenBuffers(1, &vbo);
  gl->BindBuffer(GL_ARRAY_BUFFER, vbo);
  gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(n * sizeof *s), s, GL_STATIC_DRAW);
  gl->VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof *s, (void *)offsetof(rsphere, c));
  gl->VertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, sizeof *s, (void *)offsetof(rsphere, r));
  gl->VertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof *s,
                          (void *)offsetof(rsphere, rgba));
  for (GLuint k = 0; k < 3; k++) {
    gl->EnableVertexAttribArray(k);
    gl->VertexAttribDivisor(k, 1);
  }
  gl->Viewport(0, 0, dw, dh);
  gl->Disable(GL_SCISSOR_TEST);
  gl->Disable(GL_BLEND);
  gl->Enable(GL_DEPTH_TEST);
  gl->DepthFunc(GL_LESS);
  gl->ClearColor(bg.r / 255.0f, bg.g / 255.0f, bg.b / 255.0f, 1.0f);
  gl->ClearDepth(1.0);
  gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (n) gl->DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)n);
  gl->Finish();
  if (gl->GetError() != GL_NO_ERROR) {
    rc = sph_error_set(err, "spheres: OpenGL error while drawing %zu spheres", n);
    goto done;
  }
  rc = rgl_read_averaged(gl, w, h, samples, 4, out, "spheres", err);
done:
  gl->Disable(GL_DEPTH_TEST); /* the canvas draws without depth and with blending */
  gl->Enable(GL_BLEND);
  if (vbo) gl->DeleteBuffers(1, &vbo);
  if (vao) gl->DeleteVertexArrays(1, &vao);
  if (prog) gl->DeleteProgram(prog);
  gl->DeleteRenderbuffers(2, rb);
  gl->DeleteFramebuffers(1, &fbo);
  return rc;
}
