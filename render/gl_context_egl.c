/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * gl_context_egl.c - the surfaceless EGL back end: a core-profile 3.3
 * context with no window system and no surface (EGL_MESA_platform_surfaceless,
 * EGL_KHR_surfaceless_context, EGL_KHR_no_config_context).
 *
 * This is what keeps the renderer working on Mesa 25.1 and later, where
 * OSMesa is gone. Entry points come from eglGetProcAddress, which with
 * EGL_KHR_get_all_proc_addresses also returns the core GL 1.x functions, so
 * nothing links libOpenGL. Without EGL at build time the back end is a stub
 * that explains why it is unavailable.
 */
#include "config.h"

#include "gl_context.h"

#include <stddef.h>

#ifdef HAVE_EGL

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <stdlib.h>

typedef struct egl_impl {
  EGLDisplay dpy;
  EGLContext ctx;
} egl_impl;

static rgl_proc egl_loader(const char *name) { return (rgl_proc)eglGetProcAddress(name); }

static void egl_destroy(rgl_context *c) {
  egl_impl *e = c->impl;
  if (e) {
    if (e->dpy != EGL_NO_DISPLAY) {
      eglMakeCurrent(e->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (e->ctx != EGL_NO_CONTEXT) eglDestroyContext(e->dpy, e->ctx);
      eglTerminate(e->dpy);
    }
    free(e);
  }
  free(c);
}

static int egl_fail(rgl_context *c, sph_error *err, const char *what) {
  EGLint code = eglGetError();
  egl_destroy(c);
  return sph_error_set(err, "egl back end: %s (EGL error 0x%04x)", what, (unsigned)code);
}

int rgl_context_create_egl(rgl_context **out, sph_error *err) {
  *out = NULL;
  rgl_context *c = calloc(1, sizeof *c);
  egl_impl *e = calloc(1, sizeof *e);
  if (!c || !e) {
    free(c);
    free(e);
    return sph_error_set(err, "egl back end: out of memory");
  }
  e->dpy = EGL_NO_DISPLAY;
  e->ctx = EGL_NO_CONTEXT;
  c->impl = e;
  c->backend = "egl";
  c->destroy = egl_destroy;

  PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
      (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
  if (!get_display) return egl_fail(c, err, "eglGetPlatformDisplayEXT is not available");
  e->dpy = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
  if (e->dpy == EGL_NO_DISPLAY) return egl_fail(c, err, "no surfaceless display");
  EGLint major = 0, minor = 0;
  if (!eglInitialize(e->dpy, &major, &minor)) {
    EGLint code = eglGetError();
    e->dpy = EGL_NO_DISPLAY; /* not initialised: nothing to terminate */
    egl_destroy(c);
    return sph_error_set(err,
                         "egl back end: cannot initialise the surfaceless display "
                         "(EGL error 0x%04x)",
                         (unsigned)code);
  }
  if (!eglBindAPI(EGL_OPENGL_API)) return egl_fail(c, err, "desktop OpenGL is not supported");
  const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                            3,
                            EGL_CONTEXT_MINOR_VERSION,
                            3,
                            EGL_CONTEXT_OPENGL_PROFILE_MASK,
                            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                            EGL_NONE};
  e->ctx = eglCreateContext(e->dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
  if (e->ctx == EGL_NO_CONTEXT) return egl_fail(c, err, "cannot create an OpenGL 3.3 core context");
  if (!eglMakeCurrent(e->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, e->ctx))
    return egl_fail(c, err, "cannot make the context current without a surface");
  if (rgl_load(&c->gl, egl_loader, c->backend, err) != 0) {
    egl_destroy(c);
    return -1;
  }
  *out = c;
  return 0;
}

#else /* !HAVE_EGL */

int rgl_context_create_egl(rgl_context **out, sph_error *err) {
  *out = NULL;
  return sph_error_set(err, "egl back end: this sph-render was built without EGL "
                            "(install libegl-dev and rerun configure)");
}

#endif
