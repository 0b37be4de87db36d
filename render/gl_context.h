/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * gl_context.h - an off-screen OpenGL 3.3 core context from a named back end.
 *
 * Back ends: "osmesa" (the default; Mesa's off-screen library, still in
 * Debian 12 but removed upstream in Mesa 25.1) and "egl" (surfaceless EGL,
 * EGL_MESA_platform_surfaceless, built when configure finds pkg-config egl).
 * Either way the caller draws into its own framebuffer object (canvas.c), so
 * the window-system buffer of the context is never read.
 *
 * A context belongs to one process and one thread: parallel rendering makes
 * one per worker process, after fork().
 */
#ifndef SPH_RENDER_GL_CONTEXT_H
#define SPH_RENDER_GL_CONTEXT_H

#include "core/error.h"
#include "gl_api.h"

typedef struct rgl_context {
  rgl gl;              /* entry points, valid while the context lives */
  const char *backend; /* "osmesa" or "egl" */
  void (*destroy)(struct rgl_context *c);
  void *impl; /* back-end state */
} rgl_context;

/* The back-end names, for help and error messages: "osmesa, egl". */
const char *rgl_backend_names(void);
/* Non-zero if name is a back end this build knows (egl may still fail at
 * run time if the driver offers no surfaceless platform). */
int rgl_backend_valid(const char *name);

/* Creates a context with the named back end and makes it current. */
int rgl_context_create(const char *backend, rgl_context **out, sph_error *err);
void rgl_context_destroy(rgl_context *c);

/* The back ends, called by rgl_context_create. */
int rgl_context_create_osmesa(rgl_context **out, sph_error *err);
int rgl_context_create_egl(rgl_context **out, sph_error *err);

#endif
