/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * cli_args.c - the argument check shared by the sub-commands that take a
 * list of snapshot files (sph info, sph profile): options may stand
 * anywhere before "--", --help prints the usage, anything else starting
 * with '-' is an error, and at least one file is required; and mkdir -p
 * for the commands that write a directory (sph run, sph audit); the
 * options every running command shares (--threads).
 */
#include "config.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"

int sph_cli_each_snapshot(const char *cmd, int argc, char **argv,
                          int (*fn)(const char *path, void *ctx, sph_error *err), void *ctx) {
  int status = 0, dashdash = 0, first = 1;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!dashdash && strcmp(a, "--") == 0) {
      dashdash = 1;
      continue;
    }
    /* the first file decides the build: a snapshot of the other dimension
     * hands the whole command line to it (twin.c) */
    if (first && sph_cli_hand_over_snapshot(cmd, a)) return 1;
    first = 0;
    sph_error err;
    if (fn(a, ctx, &err)) {
      fflush(stdout); /* keep stdout and stderr in order on a terminal */
      fprintf(stderr, "sph %s: %s\n", cmd, err.msg);
      status = 1;
    }
  }
  return status;
}

int sph_cli_snapshot_args(const char *cmd, const char *usage, int argc, char **argv, int *n_files) {
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

int sph_cli_is_one_of(const char *arg, const char *const *names) {
  for (; *names; names++)
    if (!strcmp(arg, *names)) return 1;
  return 0;
}

int sph_cli_parse_threads(const char *cmd, const char *value, int *threads) {
  char *end;
  const long t = strtol(value, &end, 10);
  if (*end || end == value || t < 1 || t > 4096) {
    fprintf(stderr, "%s: --threads: expected a whole number from 1 to 4096, got '%s'\n", cmd,
            value);
    return -1;
  }
  *threads = (int)t;
  return 0;
}

int sph_cli_parse_max_particles(const char *cmd, const char *value, double *max) {
  char *end;
  const double n = strtod(value, &end);
  if (end == value || *end || !(n >= 1.0) || !(n <= SPH_MAX_PARTICLES_HARD)) {
    fprintf(stderr, "%s: --max-particles: expected a count from 1 to %.0f, got '%s'\n", cmd,
            SPH_MAX_PARTICLES_HARD, value);
    return -1;
  }
  *max = n;
  return 0;
}

int sph_cli_parse_progress(const char *cmd, const char *value, double *seconds) {
  char *end;
  const double v = strtod(value, &end);
  if (end == value || *end || !(v >= 0.0) || !(v <= 1e9)) {
    fprintf(stderr, "%s: --progress: expected seconds between progress lines (0: none), got '%s'\n",
            cmd, value);
    return -1;
  }
  *seconds = v;
  return 0;
}

int sph_cli_set_threads(int threads, int quiet) {
#ifndef _OPENMP
  if (threads > 1 && !quiet) fprintf(stderr, "sph: built without OpenMP; running on 1 thread\n");
#else
  (void)quiet;
#endif
  return sph_set_threads(threads);
}

/* Whether c ends a number token in a listing value. */
static int ends_token(char c) {
  return c == '\0' || c == '\n' || c == ',' || c == ']' || c == '}' || c == ' ';
}

void sph_cli_print_listing(FILE *f, const char *listing, const char *indent) {
  int at_line_start = 1, quoted = 0, after_colon = 0;
  char prev = ' ';
  for (const char *q = listing; *q;) {
    if (at_line_start) {
      fputs(indent, f);
      at_line_start = quoted = after_colon = 0;
      prev = ' ';
    }
    const char c = *q;
    if (after_colon && !quoted && (prev == ' ' || prev == '[' || prev == ',') &&
        (c == '-' || c == '+' || c == '.' || (c >= '0' && c <= '9'))) {
      char *end;
      const double v = strtod(q, &end);
      if (end != q && ends_token(*end)) {
        fprintf(f, "%.6g", v);
        prev = end[-1];
        q = end;
        continue;
      }
    }
    if (c == '"') quoted = !quoted;
    if (c == ':' && !after_colon) after_colon = 1;
    fputc(c, f);
    if (c == '\n') at_line_start = 1;
    prev = c;
    q++;
  }
}
