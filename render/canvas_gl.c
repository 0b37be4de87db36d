/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * canvas_gl.c - the raster canvas of canvas.h on OpenGL 3.3 core.
 *
 * Every primitive becomes triangles of one vertex format, drawn by one
 * shader program: a vertex carries its pixel position, an offset from the
 * shape's centre line (pixels), a radius r, and a colour. In shape mode
 * the fragment shader keeps coverage a = clamp((r - |offset|) S + 0.5, 0,
 * 1), S the sub-pixels per pixel: for a disc the offset is from the
 * centre, for a line it is across the line, and filled shapes use offset 0
 * and r = 1 (a = 1). This gives discs and lines a rim one sub-pixel wide,
 * while interiors get a = 1 exactly and, with `flat` colours and blending
 * SRC_ALPHA / ONE_MINUS_SRC_ALPHA, store the 8-bit colour unchanged.
 * In text mode the offset carries texture coordinates into a coverage
 * bitmap of FreeType's (font.c), one texel per sub-pixel, sampled nearest;
 * in image mode into an RGBA image.
 *
 * Supersampling: the framebuffer has S x S sub-pixels per pixel (the
 * vertex shader maps pixel coordinates onto it, so callers never see S);
 * rcanvas_read_rgb returns each pixel as the rounded mean of its
 * sub-pixels, in integers. A pixel inside a shape of one opaque colour
 * keeps that colour exactly, and the result depends only on the driver's
 * rasterisation, which llvmpipe does the same in every process.
 *
 * Vertices accumulate in a CPU array and go to the GPU in one draw call per
 * flush (on a clip change, a text or image, or a read). Drawing order
 * equals issue order, so the image depends only on the sequence of calls:
 * no depth test, no sorting. Output goes to an RGBA8 renderbuffer;
 * glReadPixels returns rows bottom-up, flipped here, and alpha is dropped
 * (the image is opaque).
 */
#include "config.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "canvas_impl.h"
#include "font.h"
#include "gl_program.h"
#include "gl_supersample.h"

typedef struct vertex {
  float x, y;   /* pixel position, y down */
  float ox, oy; /* offset from the shape's centre (line) in pixels; texture coordinates */
  float r;      /* radius of full coverage */
  uint8_t rgba[4];
} vertex;

enum { MODE_SHAPE = 0, MODE_TEXT = 1, MODE_IMAGE = 2 };

typedef struct glcanvas {
  struct rcanvas base;
  const rgl *gl;
  int dw, dh; /* the framebuffer: w * S by h * S */
  GLuint fbo, rbo, vao, vbo, prog, tex;
  GLint loc_mode;
  vertex *v;
  size_t nv, cap;
  int oom; /* an allocation failed: reported by rcanvas_read_rgb */
} glcanvas;

static const char *vertex_src =
    "#version 330 core\n"
    "layout(location = 0) in vec2 pos;\n"
    "layout(location = 1) in vec2 off;\n"
    "layout(location = 2) in float rad;\n"
    "layout(location = 3) in vec4 col;\n"
    "uniform vec2 size;\n"
    "out vec2 v_off;\n"
    "flat out float v_rad;\n"
    "flat out vec4 v_col;\n"
    "void main() {\n"
    "  v_off = off; v_rad = rad; v_col = col;\n"
    "  gl_Position = vec4(2.0 * pos.x / size.x - 1.0, 1.0 - 2.0 * pos.y / size.y, 0.0, 1.0);\n"
    "}\n";

static const char *fragment_src =
    "#version 330 core\n"
    "in vec2 v_off;\n"
    "flat in float v_rad;\n"
    "flat in vec4 v_col;\n"
    "uniform int mode;\n"
    "uniform float samples;\n"
    "uniform sampler2D tex;\n"
    "out vec4 frag;\n"
    "void main() {\n"
    "  if (mode == 2) {\n"
    "    vec4 t = texture(tex, v_off);\n"
    "    if (t.a <= 0.0) discard;\n"
    "    frag = t;\n"
    "    return;\n"
    "  }\n"
    "  float a = mode == 1 ? texture(tex, v_off).r\n"
    "                      : clamp((v_rad - length(v_off)) * samples + 0.5, 0.0, 1.0);\n"
    "  if (a <= 0.0) discard;\n"
    "  frag = vec4(v_col.rgb, v_col.a * a);\n"
    "}\n";

static int make_program(glcanvas *c, sph_error *err) {
  c->prog = rgl_program(c->gl, vertex_src, fragment_src, "canvas", err);
  return c->prog ? 0 : -1;
}

static const rcanvas_ops gl_ops;

static void gl_destroy(rcanvas *base) {
  glcanvas *c = (glcanvas *)base;
  const rgl *gl = c->gl;
  if (c->tex) gl->DeleteTextures(1, &c->tex);
  if (c->vbo) gl->DeleteBuffers(1, &c->vbo);
  if (c->vao) gl->DeleteVertexArrays(1, &c->vao);
  if (c->prog) gl->DeleteProgram(c->prog);
  if (c->rbo) gl->DeleteRenderbuffers(1, &c->rbo);
  if (c->fbo) gl->DeleteFramebuffers(1, &c->fbo);
  free(c->v);
  free(c);
}

int rcanvas_gl_create(const rgl *gl, int width, int height, int samples, rcanvas **out,
                      sph_error *err) {
  *out = NULL;
  if (width < 1 || height < 1) return sph_error_set(err, "canvas: bad size %dx%d", width, height);
  /* as many sub-pixels as asked for, or as the limits leave room for */
  samples = rgl_fit_samples(gl, width, height, samples, 4.0, err);
  if (samples < 0) return -1;
  glcanvas *c = calloc(1, sizeof *c);
  if (!c) return sph_error_set(err, "canvas: out of memory");
  c->base.ops = &gl_ops;
  c->base.w = width;
  c->base.h = height;
  c->base.samples = samples;
  c->gl = gl;
  c->dw = width * samples;
  c->dh = height * samples;
  rcanvas *base = &c->base;
  gl->GenFramebuffers(1, &c->fbo);
  gl->BindFramebuffer(GL_FRAMEBUFFER, c->fbo);
  gl->GenRenderbuffers(1, &c->rbo);
  gl->BindRenderbuffer(GL_RENDERBUFFER, c->rbo);
  gl->RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, c->dw, c->dh);
  gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, c->rbo);
  if (gl->CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    gl_destroy(base);
    return sph_error_set(err, "canvas: cannot make a %dx%d RGBA8 framebuffer", width * samples,
                         height * samples);
  }
  if (make_program(c, err) != 0) {
    gl_destroy(base);
    return -1;
  }
  gl->GenVertexArrays(1, &c->vao);
  gl->BindVertexArray(c->vao);
  gl->GenBuffers(1, &c->vbo);
  gl->BindBuffer(GL_ARRAY_BUFFER, c->vbo);
  gl->VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(vertex), (void *)offsetof(vertex, x));
  gl->VertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, sizeof(vertex), (void *)offsetof(vertex, ox));
  gl->VertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, sizeof(vertex), (void *)offsetof(vertex, r));
  gl->VertexAttribPointer(3, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(vertex),
                          (void *)offsetof(vertex, rgba));
  for (GLuint i = 0; i < 4; i++)
    gl->EnableVertexAttribArray(i);
  gl->UseProgram(c->prog);
  gl->Uniform2f(gl->GetUniformLocation(c->prog, "size"), (float)width, (float)height);
  gl->Uniform1f(gl->GetUniformLocation(c->prog, "samples"), (float)samples);
  gl->Uniform1i(gl->GetUniformLocation(c->prog, "tex"), 0);
  c->loc_mode = gl->GetUniformLocation(c->prog, "mode");
  gl->Uniform1i(c->loc_mode, MODE_SHAPE);
  gl->GenTextures(1, &c->tex);
  gl->ActiveTexture(GL_TEXTURE0);
  gl->BindTexture(GL_TEXTURE_2D, c->tex);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gl->Viewport(0, 0, c->dw, c->dh);
  gl->Enable(GL_BLEND);
  gl->BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  gl->Disable(GL_SCISSOR_TEST);
  if (gl->GetError() != GL_NO_ERROR) {
    gl_destroy(base);
    return sph_error_set(err, "canvas: OpenGL error while setting up");
  }
  *out = base;
  return 0;
}

/* Makes this canvas's framebuffer, program and buffers current, so two
 * canvases may share a context (only one is drawn into at a time). */
static void bind(glcanvas *c) {
  const rgl *gl = c->gl;
  gl->BindFramebuffer(GL_FRAMEBUFFER, c->fbo);
  gl->UseProgram(c->prog);
  gl->BindVertexArray(c->vao);
  gl->BindBuffer(GL_ARRAY_BUFFER, c->vbo);
  gl->ActiveTexture(GL_TEXTURE0);
  gl->BindTexture(GL_TEXTURE_2D, c->tex);
  gl->Viewport(0, 0, c->dw, c->dh);
}

static void flush(glcanvas *c) {
  if (c->nv == 0) return;
  const rgl *gl = c->gl;
  bind(c);
  gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(c->nv * sizeof(vertex)), c->v, GL_STREAM_DRAW);
  gl->DrawArrays(GL_TRIANGLES, 0, (GLsizei)c->nv);
  c->nv = 0;
}

/* Room for n more vertices; NULL (and c->oom set) if memory runs out. */
static vertex *reserve(glcanvas *c, size_t n) {
  if (c->oom) return NULL;
  if (c->nv + n > c->cap) {
    size_t cap = c->cap ? c->cap : 4096;
    while (cap < c->nv + n)
      cap *= 2;
    vertex *v = realloc(c->v, cap * sizeof *v);
    if (!v) {
      c->oom = 1;
      return NULL;
    }
    c->v = v;
    c->cap = cap;
  }
  vertex *out = c->v + c->nv;
  c->nv += n;
  return out;
}

static void put(vertex *v, double x, double y, double ox, double oy, double r, rcolor col) {
  v->x = (float)x;
  v->y = (float)y;
  v->ox = (float)ox;
  v->oy = (float)oy;
  v->r = (float)r;
  v->rgba[0] = col.r;
  v->rgba[1] = col.g;
  v->rgba[2] = col.b;
  v->rgba[3] = col.a;
}

/* A quad with corners p0..p3 (in order around it) and their offsets. */
static void quad(glcanvas *c, const double p[4][2], const double o[4][2], double r, rcolor col) {
  vertex *v = reserve(c, 6);
  if (!v) return;
  static const int order[6] = {0, 1, 2, 0, 2, 3};
  for (int k = 0; k < 6; k++) {
    int i = order[k];
    put(&v[k], p[i][0], p[i][1], o[i][0], o[i][1], r, col);
  }
}

static void gl_clear(rcanvas *base, rcolor col) {
  glcanvas *c = (glcanvas *)base;
  const rgl *gl = c->gl;
  flush(c);
  bind(c);
  gl->Disable(GL_SCISSOR_TEST);
  gl->ClearColor(col.r / 255.0f, col.g / 255.0f, col.b / 255.0f, 1.0f);
  gl->Clear(GL_COLOR_BUFFER_BIT);
}

static void gl_clip(rcanvas *base, const rrect *r) {
  glcanvas *c = (glcanvas *)base;
  const rgl *gl = c->gl;
  flush(c);
  if (!r) {
    gl->Disable(GL_SCISSOR_TEST);
    return;
  }
  int S = base->samples;
  int x0 = (int)floor(r->x0 + 0.5), x1 = (int)floor(r->x1 + 0.5);
  int y0 = (int)floor(r->y0 + 0.5), y1 = (int)floor(r->y1 + 0.5);
  if (x1 < x0) x1 = x0;
  if (y1 < y0) y1 = y0;
  gl->Enable(GL_SCISSOR_TEST);
  gl->Scissor(x0 * S, (base->h - y1) * S, (x1 - x0) * S,
              (y1 - y0) * S); /* GL counts rows from the bottom */
}

static void gl_rect(rcanvas *base, rrect r, rcolor col) {
  const double p[4][2] = {{r.x0, r.y0}, {r.x1, r.y0}, {r.x1, r.y1}, {r.x0, r.y1}};
  const double o[4][2] = {{0, 0}, {0, 0}, {0, 0}, {0, 0}};
  quad((glcanvas *)base, p, o, 1.0, col);
}

static void gl_disc(rcanvas *base, double cx, double cy, double rad, rcolor col) {
  double e = rad + 1.0; /* room for the rim beyond the radius */
  const double p[4][2] = {{cx - e, cy - e}, {cx + e, cy - e}, {cx + e, cy + e}, {cx - e, cy + e}};
  const double o[4][2] = {{-e, -e}, {e, -e}, {e, e}, {-e, e}};
  quad((glcanvas *)base, p, o, rad, col);
}

static void gl_line(rcanvas *base, double x0, double y0, double x1, double y1, double width,
                    rcolor col) {
  double dx = x1 - x0, dy = y1 - y0, len = sqrt(dx * dx + dy * dy);
  double hw = 0.5 * width, e = hw + 1.0;
  double nx = -dy / len * e, ny = dx / len * e; /* unit normal times the half extent */
  const double p[4][2] = {
      {x0 + nx, y0 + ny}, {x1 + nx, y1 + ny}, {x1 - nx, y1 - ny}, {x0 - nx, y0 - ny}};
  const double o[4][2] = {{0, e}, {0, e}, {0, -e}, {0, -e}};
  quad((glcanvas *)base, p, o, hw, col);
}

static void gl_triangle(rcanvas *base, const double p[3][2], rcolor col) {
  vertex *v = reserve((glcanvas *)base, 3);
  if (!v) return;
  for (int k = 0; k < 3; k++)
    put(&v[k], p[k][0], p[k][1], 0, 0, 1.0, col);
}

/* Draws the quad p (corners in order around it, with texture coordinates
 * t) in mode, with the texture just uploaded. */
static void textured(glcanvas *c, const double p[4][2], const double t[4][2], rcolor col,
                     int mode) {
  quad(c, p, t, 1.0, col);
  c->gl->Uniform1i(c->loc_mode, mode);
  flush(c);
  c->gl->Uniform1i(c->loc_mode, MODE_SHAPE);
}

static void upload(glcanvas *c, GLint internal, GLenum format, int w, int h, const void *data) {
  const rgl *gl = c->gl;
  flush(c);
  bind(c);
  gl->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl->TexImage2D(GL_TEXTURE_2D, 0, internal, w, h, 0, format, GL_UNSIGNED_BYTE, data);
}

static void gl_image(rcanvas *base, rrect r, int iw, int ih, const uint8_t *rgba) {
  glcanvas *c = (glcanvas *)base;
  upload(c, GL_RGBA8, GL_RGBA, iw, ih, rgba);
  const double p[4][2] = {{r.x0, r.y0}, {r.x1, r.y0}, {r.x1, r.y1}, {r.x0, r.y1}};
  const double t[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  textured(c, p, t, (rcolor){255, 255, 255, 255}, MODE_IMAGE);
}

/* The text is rasterised at the framebuffer's resolution and placed on
 * whole sub-pixels (its fraction of a sub-pixel along the text goes into
 * the raster), so each texel covers one sub-pixel. */
static void gl_text(rcanvas *base, double x, double y, const char *s, int scale, rcolor col,
                    int vertical) {
  glcanvas *c = (glcanvas *)base;
  const double S = base->samples;
  /* the pen along the text and the baseline across it, in sub-pixels */
  double along = vertical ? -y * S : x * S, across = floor((vertical ? x : y) * S + 0.5);
  double whole = floor(along);
  rfont_bitmap b;
  sph_error err;
  if (rfont_raster(s, rfont_em(scale * S), along - whole, &b, &err) != 0) {
    rcanvas_fail(base, &err);
    return;
  }
  upload(c, GL_R8, GL_RED, b.w, b.h, b.a);
  /* the bitmap's extent: u along the text, v down the glyphs (sub-pixels) */
  double u0 = whole - b.ox, u1 = u0 + b.w, v0 = across - b.oy, v1 = v0 + b.h;
  if (vertical) {
    /* (u, v) -> (x, y) = (v, -u): the bitmap turned a quarter counter-clockwise */
    const double p[4][2] = {
        {v0 / S, -u1 / S}, {v1 / S, -u1 / S}, {v1 / S, -u0 / S}, {v0 / S, -u0 / S}};
    const double t[4][2] = {{1, 0}, {1, 1}, {0, 1}, {0, 0}};
    textured(c, p, t, col, MODE_TEXT);
  } else {
    const double p[4][2] = {{u0 / S, v0 / S}, {u1 / S, v0 / S}, {u1 / S, v1 / S}, {u0 / S, v1 / S}};
    const double t[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    textured(c, p, t, col, MODE_TEXT);
  }
  rfont_bitmap_free(&b);
}

static int gl_read_rgb(rcanvas *base, uint8_t *rgb, sph_error *err) {
  glcanvas *c = (glcanvas *)base;
  const rgl *gl = c->gl;
  if (c->oom) return sph_error_set(err, "canvas: out of memory while drawing");
  flush(c);
  bind(c);
  gl->Finish();
  return rgl_read_averaged(gl, base->w, base->h, base->samples, 3, rgb, "canvas", err);
}

static const rcanvas_ops gl_ops = {gl_destroy,  gl_clear, gl_clip, gl_rect,     gl_disc, gl_line,
                                   gl_triangle, gl_image, gl_text, gl_read_rgb, NULL,    NULL};
