/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * gl_context_osmesa.c - the OSMesa back end: a core-profile 3.3 context.
 *
 * OSMesa needs a client buffer bound to its default framebuffer; we give it
 * a 1x1 one, because all drawing goes to the canvas's framebuffer object and
 * is read back with glReadPixels after glFinish. Entry points come from
 * OSMesaGetProcAddress, never from the linker (see gl_api.c).
 */
#include "config.h"

#include "gl_context.h"

#include <GL/osmesa.h>
#include <stdlib.h>

typedef struct osmesa_impl {
  OSMesaContext ctx;
  unsigned char pixel[4]; /* the 1x1 default framebuffer */
} osmesa_impl;

static rgl_proc osmesa_loader(const char *name) { return (rgl_proc)OSMesaGetProcAddress(name); }

static void osmesa_destroy(rgl_context *c) {
  osmesa_impl *m = c->impl;
  if (m) {
    OSMesaMakeCurrent(NULL, NULL, 0, 0, 0);
    if (m->ctx) OSMesaDestroyContext(m->ctx);
    free(m);
  }
  free(c);
}

int rgl_context_create_osmesa(rgl_context **out, sph_error *err) {
  *out = NULL;
  rgl_context *c = calloc(1, sizeof *c);
  osmesa_impl *m = calloc(1, sizeof *m);
  if (!c || !m) {
    free(c);
    free(m);
    return sph_error_set(err, "osmesa back end: out of memory");
  }
  c->impl = m;
  c->backend = "osmesa";
  c->destroy = osmesa_destroy;
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         0,
                         OSMESA_STENCIL_BITS,
                         0,
                         OSMESA_PROFILE,
                         OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION,
                         3,
                         OSMESA_CONTEXT_MINOR_VERSION,
                         3,
                         0};
  m->ctx = OSMesaCreateContextAttribs(attribs, NULL);
  if (!m->ctx) {
    osmesa_destroy(c);
    return sph_error_set(err, "osmesa back end: cannot create an OpenGL 3.3 core context");
  }
  if (!OSMesaMakeCurrent(m->ctx, m->pixel, GL_UNSIGNED_BYTE, 1, 1)) {
    osmesa_destroy(c);
    return sph_error_set(err, "osmesa back end: cannot make the context current");
  }
  if (rgl_load(&c->gl, osmesa_loader, c->backend, err) != 0) {
    osmesa_destroy(c);
    return -1;
  }
  *out = c;
  return 0;
}
