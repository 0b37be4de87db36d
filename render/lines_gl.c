/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * lines_gl.c - depth-tested segments as screen-facing quads on OpenGL 3.3
 * core (see lines_gl.h): one instanced draw, each instance a segment whose
 * vertex shader places the quad's four corners in clip space.
 */
#include "config.h"

#include "lines_gl.h"

#include <limits.h>

#include "gl_program.h"

static const char *vertex_src =
    "#version 330 core\n"
    "layout(location = 0) in vec3 a;\n"
    "layout(location = 1) in vec3 b;\n"
    "uniform mat4 view;\n"
    "uniform mat4 proj;\n"
    "uniform vec2 half_size;\n" /* the frame buffer's half width and height, pixels */
    "uniform float half_width;\n"
    "void main() {\n"
    "  vec4 ca = proj * view * vec4(a, 1.0), cb = proj * view * vec4(b, 1.0);\n"
    "  vec2 pa = ca.xy / ca.w * half_size, pb = cb.xy / cb.w * half_size;\n"
    "  vec2 d = pb - pa;\n"
    "  d = length(d) > 0.0 ? normalize(d) : vec2(1.0, 0.0);\n"
    "  vec2 n = vec2(-d.y, d.x);\n"
    "  bool end = (gl_VertexID & 1) != 0;\n"
    "  float side = (gl_VertexID & 2) != 0 ? 1.0 : -1.0;\n"
    "  vec4 c = end ? cb : ca;\n"
    "  vec2 off = (n * side + d * (end ? 1.0 : -1.0)) * half_width / half_size;\n"
    "  gl_Position = vec4(c.xy + off * c.w, c.z - 2e-4 * c.w, c.w);\n"
    "}\n";

static const char *fragment_src = "#version 330 core\n"
                                  "uniform vec4 color;\n"
                                  "out vec4 frag;\n"
                                  "void main() { frag = color; }\n";

int rlines_gl(const rgl *gl, const float view[16], const float proj[16], int fw, int fh,
              double width, const float *seg, size_t n, const uint8_t rgba[4], sph_error *err) {
  if (!n) return 0;
  if (n > INT_MAX) return sph_error_set(err, "lines: %zu segments", n);
  GLuint vao = 0, vbo = 0, prog = rgl_program(gl, vertex_src, fragment_src, "lines", err);
  if (!prog) return -1;
  rgl_use_camera(gl, prog, view, proj, 0);
  gl->Uniform2f(gl->GetUniformLocation(prog, "half_size"), 0.5f * (float)fw, 0.5f * (float)fh);
  gl->Uniform1f(gl->GetUniformLocation(prog, "half_width"), (float)(0.5 * width));
  GLint color = gl->GetUniformLocation(prog, "color");
  gl->GenVertexArrays(1, &vao);
  gl->BindVertexArray(vao);
  gl->GenBuffers(1, &vbo);
  gl->BindBuffer(GL_ARRAY_BUFFER, vbo);
  gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(n * 6 * sizeof *seg), seg, GL_STATIC_DRAW);
  gl->VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof *seg, (void *)0);
  gl->VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof *seg, (void *)(3 * sizeof *seg));
  for (GLuint k = 0; k < 2; k++) {
    gl->EnableVertexAttribArray(k);
    gl->VertexAttribDivisor(k, 1);
  }
  gl->Uniform4f(color, rgba[0] / 255.0f, rgba[1] / 255.0f, rgba[2] / 255.0f, rgba[3] / 255.0f);
  gl->Enable(GL_BLEND);
  gl->BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  gl->DepthMask(GL_FALSE);
  gl->DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)n);
  gl->DepthMask(GL_TRUE);
  gl->Disable(GL_BLEND);
  for (GLuint k = 0; k < 2; k++)
    gl->VertexAttribDivisor(k, 0);
  gl->DeleteBuffers(1, &vbo);
  gl->DeleteVertexArrays(1, &vao);
  gl->DeleteProgram(prog);
  return 0;
}
