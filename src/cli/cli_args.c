/*
 * cli_args.c - the argument check shared by the sub-commands that take a
 * list of snapshot files (sph info, sph profile): options may stand
 * anywhere before "--", --help prints the usage, anything else starting
 * with '-' is an error, and at least one file is required; and mkdir -p
 * for the commands that write a directory (sph run, sph audit).
 */
#include "config.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"

int sph_cli_each_snapshot(const char *cmd, int argc, char **argv,
                          int (*fn)(const char *path, void *ctx, sph_error *err), void *ctx) {
  int status = 0, dashdash = 0;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!dashdash && strcmp(a, "--") == 0) {
      dashdash = 1;
      continue;
    }
    sph_error err;
    if (fn(a, ctx, &err)) {
      fflush(stdout); /* keep stdout and stderr in order on a terminal */
      fprintf(stderr, "sph %s: %s\n", cmd, err.msg);
      status = 1;
    }
  }
  return status;
}

int sph_cli_snapshot_args(const char *cmd, const char *usage, int argc, char **argv,
                          int *n_files) {
  int dashdash = 0;
  *n_files = 0;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (dashdash || a[0] != '-' || a[1] == '\0') {
      (*n_files)++;
    } else if (strcmp(a, "--") == 0) {
      dashdash = 1;
    } else if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
      fputs(usage, stdout);
      return -1;
    } else {
      fprintf(stderr, "sph %s: unknown option '%s'\n%s", cmd, a, usage);
      return 2;
    }
  }
  if (*n_files == 0) {
    fprintf(stderr, "sph %s: no snapshot given\n%s", cmd, usage);
    return 2;
  }
  return 0;
}

int sph_cli_make_dirs(const char *path) {
  char buf[4096];
  if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf) return -1;
  for (char *q = buf + 1; *q; q++) {
    if (*q != '/') continue;
    *q = 0;
    if (mkdir(buf, 0777) && errno != EEXIST) return -1;
    *q = '/';
  }
  if (mkdir(buf, 0777) && errno != EEXIST) return -1;
  struct stat st;
  if (stat(buf, &st) || !S_ISDIR(st.st_mode)) {
    errno = ENOTDIR;
    return -1;
  }
  return 0;
}
