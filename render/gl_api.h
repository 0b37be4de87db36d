/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * gl_api.h - the OpenGL entry points the renderer uses, as a table of
 * function pointers filled from the back end's proc-address loader.
 *
 * Why a table instead of calling gl* directly: libOSMesa exports the gl*
 * symbols itself while EGL reaches them through libglvnd; one program that
 * links both back ends can call each only through the pointers its own
 * loader hands out. Drawing code (canvas.c) sees only this table, so it does
 * not know which back end made the context (OSMesa, removed from upstream
 * Mesa in 25.1, or surfaceless EGL).
 */
#ifndef SPH_RENDER_GL_API_H
#define SPH_RENDER_GL_API_H

#include <GL/glcorearb.h>

#include "core/error.h"

/* One X(type, name) per entry point: the struct and the loader are both
 * generated from this list, so they cannot disagree. */
#define RGL_FUNCTIONS(X)                                                                           \
  X(PFNGLGETSTRINGPROC, GetString)                                                                 \
  X(PFNGLGETERRORPROC, GetError)                                                                   \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                                             \
  X(PFNGLVIEWPORTPROC, Viewport)                                                                   \
  X(PFNGLSCISSORPROC, Scissor)                                                                     \
  X(PFNGLENABLEPROC, Enable)                                                                       \
  X(PFNGLDISABLEPROC, Disable)                                                                     \
  X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate)                                                 \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                                               \
  X(PFNGLCLEARPROC, Clear)                                                                         \
  X(PFNGLFINISHPROC, Finish)                                                                       \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                                             \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                                               \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                                                     \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                                                     \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                                               \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                                       \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                                                   \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                                                   \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)                                             \
  X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)                                             \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)                                     \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                                                     \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                                                     \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                                               \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                                               \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                                               \
  X(PFNGLBUFFERDATAPROC, BufferData)                                                               \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                                         \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                                             \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)                                     \
  X(PFNGLCREATESHADERPROC, CreateShader)                                                           \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                                           \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                                                         \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                                             \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                                                   \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                                           \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                                         \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                                           \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                                             \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                                           \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                                                 \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                                               \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                                         \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                                               \
  X(PFNGLUNIFORM2FPROC, Uniform2f)                                                                 \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                                                 \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                                                 \
  X(PFNGLUNIFORM4FPROC, Uniform4f)                                                                 \
  X(PFNGLGENTEXTURESPROC, GenTextures)                                                             \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                                                             \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                                       \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                                               \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                                                         \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                                                         \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                                                               \
  X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced)                                             \
  X(PFNGLDRAWELEMENTSPROC, DrawElements)                                                           \
  X(PFNGLVERTEXATTRIBDIVISORPROC, VertexAttribDivisor)                                             \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                                                   \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                                                 \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                                                 \
  X(PFNGLCLEARDEPTHPROC, ClearDepth)

typedef struct rgl {
#define RGL_FIELD(type, name) type name;
  RGL_FUNCTIONS(RGL_FIELD)
#undef RGL_FIELD
} rgl;

/* A back end's proc-address function, wrapped to one signature. */
typedef void (*rgl_proc)(void);
typedef rgl_proc (*rgl_loader)(const char *name);

/* Fills every entry of gl through load("gl<Name>"). An entry point the
 * driver does not provide is an error naming it and the back end. */
int rgl_load(rgl *gl, rgl_loader load, const char *backend, sph_error *err);

#endif
