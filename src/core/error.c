/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * error.c - formatting of library error messages (see error.h).
 */
#include "config.h"

#include "core/error.h"

#include <stdarg.h>
#include <stdio.h>

int sph_error_set(sph_error *err, const char *fmt, ...) {
  if (err) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    /* one line, always: a control byte (a newline in a reason from HDF5, a
     * raw byte of a damaged file) becomes a space (issue 21, D10) */
    for (char *c = err->msg; *c; c++)
      if ((unsigned char)*c < 0x20 || *c == 0x7f) *c = ' ';
  }
  return -1;
}
