/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * atomic_file.c - files written whole or not at all (see atomic_file.h).
 */
#include "config.h"

#include "atomic_file.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

int ratomic_write(const char *path, const char *what, ratomic_writer write, const void *ctx,
                  sph_error *err) {
  const size_t n = strlen(path);
  char *tmp = malloc(n + 5);
  if (!tmp) return sph_error_set(err, "%s: out of memory", path);
  memcpy(tmp, path, n);
  memcpy(tmp + n, ".tmp", 5);
  FILE *fp = fopen(tmp, "wb");
  if (!fp) {
    sph_error_set(err, "%s: cannot create: %s", tmp, strerror(errno));
    free(tmp);
    return -1;
  }
  char why[256] = "";
  int rc = write(fp, ctx, why, sizeof why);
  if (fclose(fp) != 0 && rc == 0) {
    snprintf(why, sizeof why, "%s", strerror(errno));
    rc = -1;
  }
  if (rc == 0 && rename(tmp, path) != 0) {
    snprintf(why, sizeof why, "cannot rename %s: %s", tmp, strerror(errno));
    rc = -1;
  }
  if (rc != 0) {
    remove(tmp);
    sph_error_set(err, "%s: cannot write %s: %s", path, what, why);
  }
  free(tmp);
  return rc;
}
