/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * atomic_file.h - writing a file so that it either appears whole or not
 * at all: the content goes to "<path>.tmp", which is closed (checked) and
 * renamed onto path (rename(2) replaces the target in one step on POSIX
 * file systems); on any failure the temporary file is removed. The PNG
 * images (png_out.h) and the PLY meshes (ply_out.h) are written so.
 */
#ifndef SPH_RENDER_ATOMIC_FILE_H
#define SPH_RENDER_ATOMIC_FILE_H

#include <stdio.h>

#include "core/error.h"

/* Writes the content into fp; returns 0, or -1 with the reason in why. */
typedef int (*ratomic_writer)(FILE *fp, const void *ctx, char *why, size_t why_size);

/* Writes path through write(ctx). An error reads "PATH: cannot write
 * WHAT: reason" (or names the temporary file it could not create). */
int ratomic_write(const char *path, const char *what, ratomic_writer write, const void *ctx,
                  sph_error *err);

#endif
