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
 * writes its depth. The frame buffer, the depth range and the read-back
 * are the scene's (scene3d.c).
 */
#include "config.h"

#include "spheres.h"

#include <stddef.h>

#include "gl_program.h"

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

int rspheres_gl(const rgl *gl, const float view[16], const float proj[16], int ortho,
                const rsphere *s, size_t n, sph_error *err) {
  if (!n) return 0;
  GLuint vao = 0, vbo = 0, prog = rgl_program(gl, vertex_src, fragment_src, "spheres", err);
  if (!prog) return -1;
  rgl_use_camera(gl, prog, view, proj, ortho);
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
  gl->DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)n);
  for (GLuint k = 0; k < 3; k++)
    gl->VertexAttribDivisor(k, 0);
  gl->DeleteBuffers(1, &vbo);
  gl->DeleteVertexArrays(1, &vao);
  gl->DeleteProgram(prog);
  return 0;
}
