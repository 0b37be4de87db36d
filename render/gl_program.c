/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * gl_program.c - compiles and links a shader program (see gl_program.h).
 */
#include "config.h"

#include "gl_program.h"

#include <stddef.h>

static GLuint compile(const rgl *gl, GLenum kind, const char *src, const char *who,
                      sph_error *err) {
  GLuint s = gl->CreateShader(kind);
  gl->ShaderSource(s, 1, &src, NULL);
  gl->CompileShader(s);
  GLint ok = 0;
  gl->GetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[512] = "";
    gl->GetShaderInfoLog(s, sizeof log, NULL, log);
    gl->DeleteShader(s);
    sph_error_set(err, "%s: shader does not compile: %s", who, log);
    return 0;
  }
  return s;
}

GLuint rgl_program(const rgl *gl, const char *vertex_src, const char *fragment_src, const char *who,
                   sph_error *err) {
  GLuint vs = compile(gl, GL_VERTEX_SHADER, vertex_src, who, err);
  if (!vs) return 0;
  GLuint fs = compile(gl, GL_FRAGMENT_SHADER, fragment_src, who, err);
  if (!fs) {
    gl->DeleteShader(vs);
    return 0;
  }
  GLuint p = gl->CreateProgram();
  gl->AttachShader(p, vs);
  gl->AttachShader(p, fs);
  gl->LinkProgram(p);
  gl->DeleteShader(vs);
  gl->DeleteShader(fs);
  GLint ok = 0;
  gl->GetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[512] = "";
    gl->GetProgramInfoLog(p, sizeof log, NULL, log);
    gl->DeleteProgram(p);
    sph_error_set(err, "%s: shader program does not link: %s", who, log);
    return 0;
  }
  return p;
}

void rgl_use_camera(const rgl *gl, GLuint prog, const float view[16], const float proj[16],
                    int ortho) {
  gl->UseProgram(prog);
  gl->UniformMatrix4fv(gl->GetUniformLocation(prog, "view"), 1, GL_FALSE, view);
  gl->UniformMatrix4fv(gl->GetUniformLocation(prog, "proj"), 1, GL_FALSE, proj);
  const GLint o = gl->GetUniformLocation(prog, "ortho");
  if (o >= 0) gl->Uniform1i(o, ortho ? 1 : 0);
}
