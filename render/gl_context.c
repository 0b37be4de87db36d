/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * gl_context.c - chooses the back end that makes an OpenGL context.
 *
 * Names, not codes: an unknown back end is an error that lists the valid
 * ones. A build without EGL still knows the name "egl" and says why it
 * cannot use it, so scripts get a clear message rather than "unknown".
 */
#include "config.h"

#include "gl_context.h"

#include <string.h>

const char *rgl_backend_names(void) { return "osmesa, egl"; }

int rgl_backend_valid(const char *name) {
  return strcmp(name, "osmesa") == 0 || strcmp(name, "egl") == 0;
}

int rgl_context_create(const char *backend, rgl_context **out, sph_error *err) {
  *out = NULL;
  if (strcmp(backend, "osmesa") == 0) return rgl_context_create_osmesa(out, err);
  if (strcmp(backend, "egl") == 0) return rgl_context_create_egl(out, err);
  return sph_error_set(err, "unknown back end '%s' (valid: %s)", backend, rgl_backend_names());
}

void rgl_context_destroy(rgl_context *c) {
  if (c && c->destroy) c->destroy(c);
}
