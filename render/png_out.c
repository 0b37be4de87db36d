/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * png_out.c - PNG output through libpng (see png_out.h).
 *
 * Determinism: the file holds only IHDR, IDAT and IEND - no tIME, no text
 * chunks, no gamma guess - and libpng's row-filter heuristic and zlib are
 * deterministic, so the same pixels and level give the same bytes.
 * Atomicity: atomic_file.h. libpng reports
 * errors by longjmp; everything that must be released afterwards lives in
 * variables declared volatile or outside the setjmp frame.
 */
#include "config.h"

#include "png_out.h"

#include <png.h>
#include <stdio.h>

#include "atomic_file.h"

typedef struct png_failure {
  char msg[256];
} png_failure;

static void on_error(png_structp png, png_const_charp msg) {
  png_failure *f = png_get_error_ptr(png);
  snprintf(f->msg, sizeof f->msg, "%s", msg);
  png_longjmp(png, 1);
}

static void on_warning(png_structp png, png_const_charp msg) {
  (void)png;
  (void)msg;
}

/* Encodes into an open file; 0 on success, else f->msg says why. */
static int encode(FILE *fp, const uint8_t *rgb, int width, int height, int level, png_failure *f) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, f, on_error, on_warning);
  if (!png) {
    snprintf(f->msg, sizeof f->msg, "out of memory");
    return -1;
  }
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, NULL);
    snprintf(f->msg, sizeof f->msg, "out of memory");
    return -1;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return -1;
  }
  png_init_io(png, fp);
  png_set_compression_level(png, level);
  png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < height; y++)
    png_write_row(png, rgb + (size_t)y * (size_t)width * 3);
  png_write_end(png, NULL);
  png_destroy_write_struct(&png, &info);
  return 0;
}

typedef struct png_job {
  const uint8_t *rgb;
  int width, height, level;
} png_job;

static int write_png(FILE *fp, const void *ctx, char *why, size_t why_size) {
  const png_job *j = ctx;
  png_failure f = {""};
  if (encode(fp, j->rgb, j->width, j->height, j->level, &f) == 0) return 0;
  snprintf(why, why_size, "%s", f.msg);
  return -1;
}

int rpng_write(const char *path, const uint8_t *rgb, int width, int height, int level,
               sph_error *err) {
  if (level < 0 || level > 9)
    return sph_error_set(err, "%s: PNG compression level %d is not in 0..9", path, level);
  const png_job j = {rgb, width, height, level};
  return ratomic_write(path, "PNG", write_png, &j, err);
}
