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
  }
  return -1;
}
