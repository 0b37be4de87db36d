/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * error.h - how the library reports failure.
 *
 * The library never prints and never exits: a function that can fail returns
 * a non-zero status and fills an sph_error with one human-readable line
 * (file, line, key or dataset, and what was expected). Only main() decides to
 * print it and to exit.
 */
#ifndef SPH_ERROR_H
#define SPH_ERROR_H

#ifdef __cplusplus
extern "C" {
#endif

#define SPH_ERROR_LEN 1024

typedef struct sph_error {
  char msg[SPH_ERROR_LEN];
} sph_error;

/* Formats a message into err (if err is not NULL) and returns -1, so that a
 * failing function can write `return sph_error_set(err, "...", ...);`. */
int sph_error_set(sph_error *err, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

#ifdef __cplusplus
}
#endif

#endif
