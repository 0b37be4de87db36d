/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * main.c - the `sph` command: dispatches to the sub-commands of cli.h.
 */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli/cli.h"
#include "sph.h"

static void usage(FILE *f) {
  fprintf(f, "usage: sph COMMAND [options]\n"
             "\n"
             "Deterministic weakly-compressible SPH solver for free-surface flows in 2-D\n"
             "and 3-D (a case's dimension: 3 runs in the 3-D build, sph-3d).\n"
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
             "  new NAME [-o FILE]\n"
             "                 write NAME.yaml, a case to start from: every key set or shown\n"
             "                 with its default and range, runs as written\n"
             "\n"
             "options:\n"
             "  -h, --help     show this help (also: sph COMMAND --help)\n"
             "  --version      show the version and build\n"
             "\n"
             "exit status: 0 success, 1 bad input or I/O error, 2 usage error,\n"
             "             3 numerical blow-up, 4 interrupted (final snapshot written)\n");
}

/* Processes running or ready to run at this moment, this one included
 * (procs_running in /proc/stat); -1 if unknown. */
static int procs_running(void) {
  FILE *f = fopen("/proc/stat", "r");
  if (!f) return -1;
  char line[256]; /* longer lines (intr) come in pieces, none of which starts with the key */
  int n = -1;
  while (n < 0 && fgets(line, sizeof line, f))
    if (sscanf(line, "procs_running %d", &n) != 1) n = -1;
  fclose(f);
  return n;
}

/* Whether nothing else wants the CPUs: besides this process, fewer than
 * half a process running or ready on average over 20 looks 1 ms apart
 * (about 20 ms); no when it cannot tell. */
static int machine_idle(void) {
  int others = 0;
  for (int k = 0; k < 20; k++) {
    if (k) {
      const struct timespec pause = {0, 1000000L};
      nanosleep(&pause, NULL);
    }
    const int r = procs_running();
    if (r < 1) return 0;
    others += r - 1;
  }
  return others < 10;
}

/* How threads wait at the end of a parallel loop, unless the user chose
 * (OMP_WAIT_POLICY or GOMP_SPINCOUNT set). A step has five to nine short
 * parallel loops. On a busy machine (on average half a process or more
 * running or ready besides this one over 20 ms at start-up, or unknown)
 * waiters sleep at once (passive): with spinning
 * waiters a second thread that is not scheduled stalls every loop - the
 * a/50 dam break took 289 s on 2 threads against 42 s on 1 with one other
 * job running, and 9.1 s (passive) against 19.6 s (spinning) for its
 * first 0.04 s. On an idle machine they spin for GOMP_SPINCOUNT = 100000
 * turns first (some 0.1 ms), then sleep: the loops of a step follow each
 * other closely, and a futex sleep and wake-up per loop cost 2 threads
 * much of their gain (a/100 to t = 0.08 s: 27.5 s spinning, 32.2 s
 * passive, 54.1 s on 1 thread). The OpenMP runtime reads both variables
 * when it is loaded, before main(), so the program re-executes itself
 * once with one of them set. Only `sph run` on more than one thread
 * looks (20 ms: the earlier look, CPU time over 0.1 s, added 3 % to the
 * a/50 dam break on 2 threads); the other commands wait passively. */
static void choose_wait_policy(int argc, char **argv) {
#ifdef _OPENMP
  if (getenv("OMP_WAIT_POLICY") || getenv("GOMP_SPINCOUNT")) return;
  /* only `sph run` on more than one thread waits at loop ends: the other
   * commands, and a run given --threads 1, need not look */
  int run = argc > 1 && !strcmp(argv[1], "run");
  for (int i = 2; run && i + 1 < argc; i++)
    if ((!strcmp(argv[i], "-t") || !strcmp(argv[i], "--threads")) && !strcmp(argv[i + 1], "1"))
      run = 0;
  const int rc = run && machine_idle() ? setenv("GOMP_SPINCOUNT", "100000", 1)
                                       : setenv("OMP_WAIT_POLICY", "passive", 1);
  if (rc == 0) execv("/proc/self/exe", argv);
    /* if the re-exec failed, run as we are */
#else
  (void)argc;
  (void)argv;
#endif
}

const char *sph_cli_program = "sph";

/* sph_cli_program from argv[0] (cli.h). */
static void set_program(const char *arg0) {
  static char buf[4096];
  if (!arg0 || !strchr(arg0, '/') || strlen(arg0) >= sizeof buf) return;
  snprintf(buf, sizeof buf, "%s", arg0);
  char *libs = strstr(buf, "/.libs/");
  if (libs) { /* a libtool build: the wrapper script beside .libs */
    const char *name = libs + strlen("/.libs/");
    if (!strncmp(name, "lt-", 3)) name += 3;
    memmove(libs + 1, name, strlen(name) + 1);
  }
  sph_cli_program = buf;
}

int main(int argc, char **argv) {
  choose_wait_policy(argc, argv);
  sph_cli_argv = argv;
  set_program(argv[0]);
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
    const char *args = sph_configure_args();
    const char *twin = sph_cli_twin();
    printf("%s\nconfigured with: %s\nbuild: %s\ncompiler: %s\ndimensions: %d (this program), "
           "%d (%s)\n",
           sph_version(), *args ? args : "(no options: the defaults)", sph_build_features(),
           sph_compiler(), SPH_DIM, SPH_DIM == 2 ? 3 : 2, twin ? twin : "not found");
    return 0;
  }
  if (!strcmp(cmd, "run")) return sph_cli_run(argc - 1, argv + 1);
  if (!strcmp(cmd, "info")) return sph_cli_info(argc - 1, argv + 1);
  if (!strcmp(cmd, "profile")) return sph_cli_profile(argc - 1, argv + 1);
  if (!strcmp(cmd, "audit")) return sph_cli_audit(argc - 1, argv + 1);
  if (!strcmp(cmd, "face")) return sph_cli_face(argc - 1, argv + 1);
  if (!strcmp(cmd, "new")) return sph_cli_new(argc - 1, argv + 1);
  fprintf(
      stderr,
      "sph: unknown command '%s' (valid: run, info, audit, profile, face, new; see sph --help)\n",
      cmd);
  return 2;
}
