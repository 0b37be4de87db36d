/*
 * main.c - the `sph` command: dispatches to the sub-commands of cli.h.
 */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

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
          "      [--restart SNAPSHOT]\n"
          "                 run a case file (YAML), writing HDF5 snapshots, an XDMF index\n"
          "                 and diagnostics.csv into DIR (default out/<case name>); with\n"
          "                 --restart, continue an earlier run from one of its snapshots\n"
          "  info SNAPSHOT...\n"
          "                 print a snapshot's header and the range of every field\n"
          "  audit CASE --particles N1,N2,... [--times t1,t2,...] [-o DIR]\n"
          "                 energy deviation against particle count and time (paper A\n"
          "                 Table 4), running the case once per count\n"
          "  profile SNAPSHOT...\n"
          "                 film-flow error against paper A eq. (26) (inclined plane)\n"
          "  face SNAPSHOT...\n"
          "                 front-face angle of a breaking wave, and when it first stands\n"
          "                 vertical (paper B 4.3)\n"
          "\n"
          "options:\n"
          "  -h, --help     show this help (also: sph COMMAND --help)\n"
          "  --version      show the version and build\n"
          "\n"
          "exit status: 0 success, 1 bad input or I/O error, 2 usage error,\n"
          "             3 numerical blow-up, 4 interrupted (final snapshot written)\n");
}

/* Threads that wait at the end of a parallel loop sleep rather than spin,
 * unless the user chose otherwise. A step has about a dozen short parallel
 * loops; with spinning waiters a second thread that is not scheduled (any
 * other load on the machine) stalls every loop: the a/50 dam break took
 * 289 s on 2 threads against 42 s on 1 with one other job running, and
 * 9.1 s (passive) against 19.6 s (spinning) for its first 0.04 s. The
 * OpenMP runtime reads OMP_WAIT_POLICY when it is loaded, before main(),
 * so the program re-executes itself once with the variable set. */
static void prefer_passive_wait(char **argv) {
#ifdef _OPENMP
  if (getenv("OMP_WAIT_POLICY")) return;
  if (setenv("OMP_WAIT_POLICY", "passive", 1) == 0) execv("/proc/self/exe", argv);
  /* if the re-exec failed, run as we are */
#else
  (void)argv;
#endif
}

int main(int argc, char **argv) {
  prefer_passive_wait(argv);
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
  if (!strcmp(cmd, "face")) return sph_cli_face(argc - 1, argv + 1);
  fprintf(stderr,
          "sph: unknown command '%s' (valid: run, info, audit, profile, face; see sph --help)\n",
          cmd);
  return 2;
}
