/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * png_out.h - writes an 8-bit RGB image as a PNG file, atomically.
 */
#ifndef SPH_RENDER_PNG_OUT_H
#define SPH_RENDER_PNG_OUT_H

#include <stdint.h>

#include "core/error.h"

/* Writes rgb (width * height * 3 bytes, top row first) to path with zlib
 * compression level 0..9. The file appears complete or not at all: it is
 * written to "<path>.tmp" and renamed; on failure nothing is left. */
int rpng_write(const char *path, const uint8_t *rgb, int width, int height, int level,
               sph_error *err);

#endif
