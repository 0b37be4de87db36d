/*
 * cli_args.c - the argument check shared by the sub-commands that take a
 * list of snapshot files (sph info, sph profile): options may stand
 * anywhere before "--", --help prints the usage, anything else starting
 * with '-' is an error, and at least one file is required.
 */
#include "config.h"

#include <stdio.h>
#include <string.h>

#include "cli.h"

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
