/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * gl_program.h - an OpenGL shader program from the sources of its vertex
 * and fragment shaders, with the driver's log in the error when a shader
 * does not compile or the program does not link; the camera's uniforms
 * the 3-D views' programs share.
 */
#ifndef SPH_RENDER_GL_PROGRAM_H
#define SPH_RENDER_GL_PROGRAM_H

#include "core/error.h"
#include "gl_api.h"

/* The linked program, or 0 with err ("WHO: shader does not compile: ...",
 * "WHO: shader program does not link: ..."); nothing is left allocated
 * on failure. */
GLuint rgl_program(const rgl *gl, const char *vertex_src, const char *fragment_src, const char *who,
                   sph_error *err);

/* Makes prog current and sets the 3-D views' camera uniforms "view" and
 * "proj" (column-major 4x4, camera.h) and "ortho" (where prog has it). */
void rgl_use_camera(const rgl *gl, GLuint prog, const float view[16], const float proj[16],
                    int ortho);

#endif
