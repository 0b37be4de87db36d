/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * gl_program.h - an OpenGL shader program from the sources of its vertex
 * and fragment shaders, with the driver's log in the error when a shader
 * does not compile or the program does not link.
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

#endif
