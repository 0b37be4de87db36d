/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * mesh_gl.c - lit triangle meshes on OpenGL 3.3 core (see mesh_gl.h): one
 * interleaved vertex buffer (position, normal, colour) and one indexed
 * draw.
 */
#include "config.h"

#include "mesh_gl.h"

#include <limits.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "gl_program.h"

static const char *vertex_src = "#version 330 core\n"
                                "layout(location = 0) in vec3 position;\n"
                                "layout(location = 1) in vec3 normal;\n"
                                "layout(location = 2) in vec4 color;\n"
                                "uniform mat4 view;\n"
                                "uniform mat4 proj;\n"
                                "out vec3 v_pos;\n"
                                "out vec3 v_normal;\n"
                                "out vec4 v_color;\n"
                                "void main() {\n"
                                "  vec4 e = view * vec4(position, 1.0);\n"
                                "  v_pos = e.xyz;\n"
                                "  v_normal = mat3(view) * normal;\n"
                                "  v_color = color;\n"
                                "  gl_Position = proj * e;\n"
                                "}\n";

static const char *fragment_src =
    "#version 330 core\n"
    "in vec3 v_pos;\n"
    "in vec3 v_normal;\n"
    "in vec4 v_color;\n"
    "uniform int ortho;\n"
    "out vec4 frag;\n"
    "void main() {\n"
    "  vec3 d = ortho == 1 ? vec3(0.0, 0.0, -1.0) : normalize(v_pos);\n"
    "  vec3 n = normalize(v_normal);\n"
    "  if (dot(n, d) > 0.0) n = -n;\n"
    "  vec3 l = normalize(vec3(-0.35, 0.55, 0.75));\n"
    "  vec3 h = normalize(l - d);\n"
    "  float diffuse = max(dot(n, l), 0.0);\n"
    "  float specular = pow(max(dot(n, h), 0.0), 40.0);\n"
    "  frag = vec4(min(v_color.rgb * (0.3 + 0.7 * diffuse) + 0.15 * specular, 1.0), 1.0);\n"
    "}\n";

typedef struct vertex {
  float p[3], n[3];
  uint8_t rgba[4];
} vertex;

int rmesh_gl(const rgl *gl, const float view[16], const float proj[16], int ortho, const rmesh *m,
             const uint8_t *rgba, sph_error *err) {
  if (!m->nt) return 0;
  if (m->nt > INT_MAX / 3)
    return sph_error_set(err, "surface: %zu triangles are more than one draw takes", m->nt);
  vertex *v = malloc(m->nv * sizeof *v);
  if (!v) return sph_error_set(err, "surface: out of memory for %zu vertices", m->nv);
  for (size_t i = 0; i < m->nv; i++) {
    memcpy(v[i].p, m->p + 3 * i, sizeof v[i].p);
    memcpy(v[i].n, m->normal + 3 * i, sizeof v[i].n);
    memcpy(v[i].rgba, rgba + 4 * i, sizeof v[i].rgba);
  }
  GLuint prog = rgl_program(gl, vertex_src, fragment_src, "surface", err);
  if (!prog) {
    free(v);
    return -1;
  }
  GLuint vao = 0, buf[2] = {0, 0};
  rgl_use_camera(gl, prog, view, proj, ortho);
  gl->GenVertexArrays(1, &vao);
  gl->BindVertexArray(vao);
  gl->GenBuffers(2, buf);
  gl->BindBuffer(GL_ARRAY_BUFFER, buf[0]);
  gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(m->nv * sizeof *v), v, GL_STATIC_DRAW);
  free(v);
  gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, buf[1]);
  gl->BufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(3 * m->nt * sizeof *m->tri), m->tri,
                 GL_STATIC_DRAW);
  gl->VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(vertex), (void *)offsetof(vertex, p));
  gl->VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(vertex), (void *)offsetof(vertex, n));
  gl->VertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(vertex),
                          (void *)offsetof(vertex, rgba));
  for (GLuint k = 0; k < 3; k++)
    gl->EnableVertexAttribArray(k);
  gl->DrawElements(GL_TRIANGLES, (GLsizei)(3 * m->nt), GL_UNSIGNED_INT, (void *)0);
  gl->DeleteBuffers(2, buf);
  gl->DeleteVertexArrays(1, &vao);
  gl->DeleteProgram(prog);
  return 0;
}
