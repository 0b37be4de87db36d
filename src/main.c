/*
 * main.c - the `sph` command: dispatches to the sub-commands of cli.h.
 */
#include "config.h"

#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "version.h"

static void usage(FILE *f) {
  fprintf(f,
          "usage: sph COMMAND [options]\n"
          "\n"
          "Deterministic weakly-compressible SPH solver for 2-D free-surface flows.\n"
          "\n"
          "commands:\n"
          "  run CASE [-o DIR] [--threads N] [--set key=value]... [--quiet]\n"
          "                 run a case file (YAML), writing HDF5 snapshots, an XDMF index\n"
          "                 and diagnostics.csv into DIR (default out/<case name>)\n"
          "  info SNAPSHOT...\n"
          "                 print a snapshot's header and the range of every field\n"
          "  audit CASE --particles N1,N2,... [--times t1,t2,...] [-o DIR]\n"
          "                 energy deviation against particle count and time (paper A\n"
          "                 Table 4), running the case once per count\n"
          "  profile SNAPSHOT...\n"
          "                 film-flow error against paper A eq. (26) (inclined plane)\n"
          "\n"
          "options:\n"
          "  -h, --help     show this help (also: sph COMMAND --help)\n"
          "  --version      show the version and build\n"
          "\n"
          "exit status: 0 success, 1 bad input or I/O error, 2 usage error,\n"
          "             3 numerical blow-up, 4 interrupted (final snapshot written)\n");
}

int main(int argc, char **argv) {
  if (argc < 2) {
    usage(stderr);
    return 2;
  }
  const char *cmd = argv[1];
  if (!strcmp(cmd, "-h") || !strcmp(cmd, "--help") || !strcmp(cmd, "help")) {
    usage(stdout);
    return 0;
  }
  if (!strcmp(cmd, "--version")) {
    printf("%s\nconfigured with: %s\ncompiler: %s\n", sph_version(), sph_configure_args(),
           sph_compiler());
    return 0;
  }
  if (!strcmp(cmd, "run")) return sph_cli_run(argc - 1, argv + 1);
  if (!strcmp(cmd, "info")) return sph_cli_info(argc - 1, argv + 1);
  if (!strcmp(cmd, "profile")) return sph_cli_profile(argc - 1, argv + 1);
  if (!strcmp(cmd, "audit")) return sph_cli_audit(argc - 1, argv + 1);
  fprintf(stderr,
          "sph: unknown command '%s' (valid: run, info, audit, profile; see sph --help)\n", cmd);
  return 2;
}
