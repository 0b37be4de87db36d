/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * canvas.c - the drawing surface of canvas.h on OpenGL 3.3 core.
 *
 * Every primitive becomes triangles of one vertex format, drawn by one
 * shader program: a vertex carries its pixel position, an offset from the
 * shape's centre line (pixels), a radius r, and a colour. The fragment
 * shader keeps coverage a = clamp(r - |offset| + 0.5, 0, 1): for a disc the
 * offset is from the centre, for a line it is across the line, and filled
 * shapes use offset 0 and r = 1 (a = 1). This gives discs and lines a
 * one-pixel anti-aliased rim, while interiors get a = 1 exactly and, with
 * `flat` colours and blending SRC_ALPHA / ONE_MINUS_SRC_ALPHA, store the
 * 8-bit colour unchanged - which the tests rely on.
 *
 * Vertices accumulate in a CPU array and go to the GPU in one draw call per
 * flush (on a clip change or a read). Drawing order equals issue order, so
 * the image depends only on the sequence of calls: no depth test, no
 * sorting. Output goes to an RGBA8 renderbuffer; glReadPixels returns rows
 * bottom-up, flipped here, and alpha is dropped (the image is opaque).
 */
#include "config.h"

#include "canvas.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "font.h"

typedef struct vertex {
  float x, y;   /* pixel position, y down */
  float ox, oy; /* offset from the shape's centre (line) in pixels */
  float r;      /* radius of full coverage */
  uint8_t rgba[4];
} vertex;

struct rcanvas {
  const rgl *gl;
  int w, h;
  GLuint fbo, rbo, vao, vbo, prog;
  vertex *v;
  size_t nv, cap;
  int oom; /* an allocation failed: reported by rcanvas_read_rgb */
};

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

static const char *fragment_src = "#version 330 core\n"
                                  "in vec2 v_off;\n"
                                  "flat in float v_rad;\n"
                                  "flat in vec4 v_col;\n"
                                  "out vec4 frag;\n"
                                  "void main() {\n"
                                  "  float a = clamp(v_rad - length(v_off) + 0.5, 0.0, 1.0);\n"
                                  "  if (a <= 0.0) discard;\n"
                                  "  frag = vec4(v_col.rgb, v_col.a * a);\n"
                                  "}\n";

static GLuint compile(const rgl *gl, GLenum kind, const char *src, sph_error *err) {
  GLuint s = gl->CreateShader(kind);
  gl->ShaderSource(s, 1, &src, NULL);
  gl->CompileShader(s);
  GLint ok = 0;
  gl->GetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[512] = "";
    gl->GetShaderInfoLog(s, sizeof log, NULL, log);
    gl->DeleteShader(s);
    sph_error_set(err, "canvas: shader does not compile: %s", log);
    return 0;
  }
  return s;
}

static int make_program(rcanvas *c, sph_error *err) {
  const rgl *gl = c->gl;
  GLuint vs = compile(gl, GL_VERTEX_SHADER, vertex_src, err);
  if (!vs) return -1;
  GLuint fs = compile(gl, GL_FRAGMENT_SHADER, fragment_src, err);
  if (!fs) {
    gl->DeleteShader(vs);
    return -1;
  }
  c->prog = gl->CreateProgram();
  gl->AttachShader(c->prog, vs);
  gl->AttachShader(c->prog, fs);
  gl->LinkProgram(c->prog);
  gl->DeleteShader(vs);
  gl->DeleteShader(fs);
  GLint ok = 0;
  gl->GetProgramiv(c->prog, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[512] = "";
    gl->GetProgramInfoLog(c->prog, sizeof log, NULL, log);
    return sph_error_set(err, "canvas: shader program does not link: %s", log);
  }
  return 0;
}

int rcanvas_create(const rgl *gl, int width, int height, rcanvas **out, sph_error *err) {
  *out = NULL;
  if (width < 1 || height < 1) return sph_error_set(err, "canvas: bad size %dx%d", width, height);
  GLint max_rb = 0, max_vp[2] = {0, 0};
  gl->GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_rb);
  gl->GetIntegerv(GL_MAX_VIEWPORT_DIMS, max_vp);
  if (width > max_rb || height > max_rb || width > max_vp[0] || height > max_vp[1])
    return sph_error_set(err, "image size %dx%d exceeds the driver's limit of %dx%d", width, height,
                         max_rb < max_vp[0] ? max_rb : max_vp[0],
                         max_rb < max_vp[1] ? max_rb : max_vp[1]);
  rcanvas *c = calloc(1, sizeof *c);
  if (!c) return sph_error_set(err, "canvas: out of memory");
  c->gl = gl;
  c->w = width;
  c->h = height;
  gl->GenFramebuffers(1, &c->fbo);
  gl->BindFramebuffer(GL_FRAMEBUFFER, c->fbo);
  gl->GenRenderbuffers(1, &c->rbo);
  gl->BindRenderbuffer(GL_RENDERBUFFER, c->rbo);
  gl->RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, c->rbo);
  if (gl->CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    rcanvas_destroy(c);
    return sph_error_set(err, "canvas: cannot make a %dx%d RGBA8 framebuffer", width, height);
  }
  if (make_program(c, err) != 0) {
    rcanvas_destroy(c);
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
  gl->Viewport(0, 0, width, height);
  gl->Enable(GL_BLEND);
  gl->BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  gl->Disable(GL_SCISSOR_TEST);
  if (gl->GetError() != GL_NO_ERROR) {
    rcanvas_destroy(c);
    return sph_error_set(err, "canvas: OpenGL error while setting up");
  }
  *out = c;
  return 0;
}

void rcanvas_destroy(rcanvas *c) {
  if (!c) return;
  const rgl *gl = c->gl;
  if (c->vbo) gl->DeleteBuffers(1, &c->vbo);
  if (c->vao) gl->DeleteVertexArrays(1, &c->vao);
  if (c->prog) gl->DeleteProgram(c->prog);
  if (c->rbo) gl->DeleteRenderbuffers(1, &c->rbo);
  if (c->fbo) gl->DeleteFramebuffers(1, &c->fbo);
  free(c->v);
  free(c);
}

int rcanvas_width(const rcanvas *c) { return c->w; }
int rcanvas_height(const rcanvas *c) { return c->h; }

/* Makes this canvas's framebuffer, program and buffers current, so two
 * canvases may share a context (only one is drawn into at a time). */
static void bind(rcanvas *c) {
  const rgl *gl = c->gl;
  gl->BindFramebuffer(GL_FRAMEBUFFER, c->fbo);
  gl->UseProgram(c->prog);
  gl->BindVertexArray(c->vao);
  gl->BindBuffer(GL_ARRAY_BUFFER, c->vbo);
  gl->Viewport(0, 0, c->w, c->h);
}

static void flush(rcanvas *c) {
  if (c->nv == 0) return;
  const rgl *gl = c->gl;
  bind(c);
  gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(c->nv * sizeof(vertex)), c->v, GL_STREAM_DRAW);
  gl->DrawArrays(GL_TRIANGLES, 0, (GLsizei)c->nv);
  c->nv = 0;
}

/* Room for n more vertices; NULL (and c->oom set) if memory runs out. */
static vertex *reserve(rcanvas *c, size_t n) {
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
static void quad(rcanvas *c, const double p[4][2], const double o[4][2], double r, rcolor col) {
  vertex *v = reserve(c, 6);
  if (!v) return;
  static const int order[6] = {0, 1, 2, 0, 2, 3};
  for (int k = 0; k < 6; k++) {
    int i = order[k];
    put(&v[k], p[i][0], p[i][1], o[i][0], o[i][1], r, col);
  }
}

void rcanvas_clear(rcanvas *c, rcolor col) {
  const rgl *gl = c->gl;
  flush(c);
  bind(c);
  gl->Disable(GL_SCISSOR_TEST);
  gl->ClearColor(col.r / 255.0f, col.g / 255.0f, col.b / 255.0f, 1.0f);
  gl->Clear(GL_COLOR_BUFFER_BIT);
}

void rcanvas_clip(rcanvas *c, const rrect *r) {
  const rgl *gl = c->gl;
  flush(c);
  if (!r) {
    gl->Disable(GL_SCISSOR_TEST);
    return;
  }
  int x0 = (int)floor(r->x0 + 0.5), x1 = (int)floor(r->x1 + 0.5);
  int y0 = (int)floor(r->y0 + 0.5), y1 = (int)floor(r->y1 + 0.5);
  if (x1 < x0) x1 = x0;
  if (y1 < y0) y1 = y0;
  gl->Enable(GL_SCISSOR_TEST);
  gl->Scissor(x0, c->h - y1, x1 - x0, y1 - y0); /* GL counts rows from the bottom */
}

void rcanvas_rect(rcanvas *c, rrect r, rcolor col) {
  if (r.x1 <= r.x0 || r.y1 <= r.y0) return;
  const double p[4][2] = {{r.x0, r.y0}, {r.x1, r.y0}, {r.x1, r.y1}, {r.x0, r.y1}};
  const double o[4][2] = {{0, 0}, {0, 0}, {0, 0}, {0, 0}};
  quad(c, p, o, 1.0, col);
}

void rcanvas_border(rcanvas *c, rrect r, double w, rcolor col) {
  rcanvas_rect(c, (rrect){r.x0 - w, r.y0 - w, r.x1 + w, r.y0}, col);
  rcanvas_rect(c, (rrect){r.x0 - w, r.y1, r.x1 + w, r.y1 + w}, col);
  rcanvas_rect(c, (rrect){r.x0 - w, r.y0, r.x0, r.y1}, col);
  rcanvas_rect(c, (rrect){r.x1, r.y0, r.x1 + w, r.y1}, col);
}

void rcanvas_disc(rcanvas *c, double cx, double cy, double rad, rcolor col) {
  double e = rad + 1.0; /* one pixel of rim beyond the radius */
  const double p[4][2] = {{cx - e, cy - e}, {cx + e, cy - e}, {cx + e, cy + e}, {cx - e, cy + e}};
  const double o[4][2] = {{-e, -e}, {e, -e}, {e, e}, {-e, e}};
  quad(c, p, o, rad, col);
}

void rcanvas_line(rcanvas *c, double x0, double y0, double x1, double y1, double width,
                  rcolor col) {
  double dx = x1 - x0, dy = y1 - y0, len = sqrt(dx * dx + dy * dy);
  if (!(len > 0.0)) return;
  double hw = 0.5 * width, e = hw + 1.0;
  double nx = -dy / len * e, ny = dx / len * e; /* unit normal times the half extent */
  const double p[4][2] = {
      {x0 + nx, y0 + ny}, {x1 + nx, y1 + ny}, {x1 - nx, y1 - ny}, {x0 - nx, y0 - ny}};
  const double o[4][2] = {{0, e}, {0, e}, {0, -e}, {0, -e}};
  quad(c, p, o, hw, col);
}

void rcanvas_triangle(rcanvas *c, double x0, double y0, double x1, double y1, double x2, double y2,
                      rcolor col) {
  vertex *v = reserve(c, 3);
  if (!v) return;
  put(&v[0], x0, y0, 0, 0, 1.0, col);
  put(&v[1], x1, y1, 0, 0, 1.0, col);
  put(&v[2], x2, y2, 0, 0, 1.0, col);
}

void rcanvas_text(rcanvas *c, double x, double y, const char *s, int scale, rcolor col, int halign,
                  int valign, int vertical) {
  if (scale < 1) scale = 1;
  double w = rfont_width(s, scale);
  /* the text box in its own frame: u along the text, v down the glyphs */
  double u0 = -w * 0.5 * halign;
  double v0 = -RFONT_CAP * scale * 0.5 * valign;
  /* whole pixels, so glyph pixels are sharp */
  x = floor(x + 0.5);
  y = floor(y + 0.5);
  u0 = floor(u0 + 0.5);
  v0 = floor(v0 + 0.5);
  for (size_t i = 0; s[i]; i++) {
    uint8_t rows[RFONT_ROWS];
    rfont_glyph((unsigned char)s[i], rows);
    double gu = u0 + (double)i * RFONT_ADVANCE * scale;
    for (int r = 0; r < RFONT_ROWS; r++) {
      for (int k = 0; k < RFONT_COLS;) {
        if (!(rows[r] >> (RFONT_COLS - 1 - k) & 1)) {
          k++;
          continue;
        }
        int k1 = k;
        while (k1 < RFONT_COLS && (rows[r] >> (RFONT_COLS - 1 - k1) & 1))
          k1++;
        double ua = gu + k * scale, ub = gu + k1 * scale; /* one run of lit pixels */
        double va = v0 + r * scale, vb = va + scale;
        if (vertical)
          rcanvas_rect(c, (rrect){x + va, y - ub, x + vb, y - ua}, col);
        else
          rcanvas_rect(c, (rrect){x + ua, y + va, x + ub, y + vb}, col);
        k = k1;
      }
    }
  }
}

int rcanvas_read_rgb(rcanvas *c, uint8_t *rgb, sph_error *err) {
  const rgl *gl = c->gl;
  if (c->oom) return sph_error_set(err, "canvas: out of memory while drawing");
  flush(c);
  bind(c);
  gl->Finish();
  size_t row = (size_t)c->w * 4;
  uint8_t *rgba = malloc(row * (size_t)c->h);
  if (!rgba) return sph_error_set(err, "canvas: out of memory reading %dx%d pixels", c->w, c->h);
  gl->PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl->ReadPixels(0, 0, c->w, c->h, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  if (gl->GetError() != GL_NO_ERROR) {
    free(rgba);
    return sph_error_set(err, "canvas: glReadPixels failed");
  }
  for (int y = 0; y < c->h; y++) {
    const uint8_t *src = rgba + (size_t)(c->h - 1 - y) * row; /* bottom-up to top-down */
    uint8_t *dst = rgb + (size_t)y * c->w * 3;
    for (int x = 0; x < c->w; x++) {
      dst[3 * x + 0] = src[4 * x + 0];
      dst[3 * x + 1] = src[4 * x + 1];
      dst[3 * x + 2] = src[4 * x + 2];
    }
  }
  free(rgba);
  return 0;
}
