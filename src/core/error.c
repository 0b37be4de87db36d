/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * error.c - formatting of library error messages (see error.h).
 */
#include "config.h"

#include "core/error.h"

#include <stdarg.h>
#include <stdio.h>

/* The length of the UTF-8 sequence at s (1 to 4), or 0 if the bytes there
 * are not one (RFC 3629: no overlong forms, no surrogates, at most
 * U+10FFFF). */
static int utf8_length(const unsigned char *s) {
  const unsigned c = s[0];
  if (c < 0x80) return 1;
  int n;
  unsigned lo = 0x80, hi = 0xbf; /* the range of the second byte */
  if (c >= 0xc2 && c <= 0xdf)
    n = 2;
  else if (c >= 0xe0 && c <= 0xef) {
    n = 3;
    if (c == 0xe0) lo = 0xa0;
    if (c == 0xed) hi = 0x9f;
  } else if (c >= 0xf0 && c <= 0xf4) {
    n = 4;
    if (c == 0xf0) lo = 0x90;
    if (c == 0xf4) hi = 0x8f;
  } else
    return 0;
  if (s[1] < lo || s[1] > hi) return 0;
  for (int k = 2; k < n; k++)
    if (s[k] < 0x80 || s[k] > 0xbf) return 0;
  return n;
}

int sph_error_set(sph_error *err, const char *fmt, ...) {
  if (err) {
    char raw[sizeof err->msg];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(raw, sizeof raw, fmt, ap);
    va_end(ap);
    /* one line, always: a control byte (a newline in a reason from HDF5, a
     * raw byte of a damaged file) becomes a space (issue 21, D10); a byte
     * that is not UTF-8 (a case file in Latin-1, a damaged name) is written
     * as \xNN, so the message is valid text (issue 39, D8) */
    size_t o = 0;
    for (const unsigned char *c = (const unsigned char *)raw; *c && o + 5 < sizeof err->msg;) {
      const int n = utf8_length(c);
      if (n == 0) {
        o += (size_t)snprintf(err->msg + o, sizeof err->msg - o, "\\x%02x", *c);
        c++;
      } else if (n == 1) {
        err->msg[o++] = (*c < 0x20 || *c == 0x7f) ? ' ' : (char)*c;
        c++;
      } else {
        for (int k = 0; k < n; k++)
          err->msg[o++] = (char)*c++;
      }
    }
    err->msg[o] = '\0';
  }
  return -1;
}
