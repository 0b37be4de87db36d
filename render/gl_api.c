/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * gl_api.c - fills the table of OpenGL entry points (see gl_api.h).
 *
 * Every pointer comes from the back end's own loader, never from the
 * linker, so the program links no libGL/libOpenGL (linking -lGL next to
 * OSMesa makes glGetString return NULL and nothing render, see
 * ../shared/TOOLCHAIN.md). A missing entry point is reported by name
 * instead of crashing on the first call.
 */
#include "config.h"

#include "gl_api.h"

#include <string.h>

int rgl_load(rgl *gl, rgl_loader load, const char *backend, sph_error *err) {
  memset(gl, 0, sizeof *gl);
#define RGL_LOAD(type, name)                                                                       \
  gl->name = (type)load("gl" #name);                                                               \
  if (!gl->name)                                                                                   \
    return sph_error_set(err, "%s back end: OpenGL function gl%s is not available", backend, #name);
  RGL_FUNCTIONS(RGL_LOAD)
#undef RGL_LOAD
  return 0;
}
