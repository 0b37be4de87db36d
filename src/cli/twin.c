/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * twin.c - one command for both dimensions: `sph` is the 2-D build of the
 * command line and `sph-3d` (installed in the package's libexec directory)
 * the same sources built for 3-D (doc/dimensions.md). A case file whose
 * `dimension` is not this build's is handed to the other build, which runs
 * it with the same arguments.
 */
#include "config.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/cli.h"
#include "sph.h"

char **sph_cli_argv;

/* The other build's program: $SPH_TWIN if set; else beside this program
 * (an installed or a libtool build's .libs directory: one level up); else
 * the configured libexec directory. NULL if none is there. */
const char *sph_cli_twin(void) {
  static char path[PATH_MAX + 64];
  const char *env = getenv("SPH_TWIN");
  if (env && *env) return access(env, X_OK) == 0 ? env : NULL;
  const char *name = SPH_DIM == 2 ? "sph-3d" : "sph";
  char self[PATH_MAX];
  const ssize_t k = readlink("/proc/self/exe", self, sizeof self - 1);
  if (k > 0) {
    self[k] = '\0';
    char *slash = strrchr(self, '/');
    if (slash) *slash = '\0';
    snprintf(path, sizeof path, "%s/%s", self, name);
    if (access(path, X_OK) == 0) return path;
    snprintf(path, sizeof path, "%s/../%s", self, name);
    if (access(path, X_OK) == 0) return path;
  }
#ifdef SPH_TWIN_DIR
  snprintf(path, sizeof path, "%s/%s", SPH_TWIN_DIR, name);
  if (access(path, X_OK) == 0) return path;
#endif
  return NULL;
}

/* Runs the other build with this command line (no return unless that fails: 1). */
static int exec_twin(const char *cmd, const char *what, const char *path, int dim) {
  const char *twin = sph_cli_twin();
  if (!twin || !sph_cli_argv) {
    fprintf(stderr,
            "sph %s: %s is a %d-D %s and the %d-D program (%s) is not installed beside "
            "this one\n",
            cmd, path, dim, what, dim, SPH_DIM == 2 ? "sph-3d" : "sph");
    return 1;
  }
  execv(twin, sph_cli_argv);
  fprintf(stderr, "sph %s: cannot run the %d-D program %s: %s\n", cmd, dim, twin, strerror(errno));
  return 1;
}

int sph_cli_hand_over(const char *cmd, const char *case_path, const char *const *set,
                      size_t n_set) {
  int dim = SPH_DIM;
  sph_error err = {{0}};
  if (sph_case_file_dimension(case_path, set, n_set, &dim, &err) || dim == SPH_DIM)
    return 0; /* (an error: the case reader says it in full) */
  return exec_twin(cmd, "case", case_path, dim);
}

int sph_cli_hand_over_snapshot(const char *cmd, const char *path) {
  int dim = SPH_DIM;
  sph_error err = {{0}};
  if (sph_snapshot_file_dimension(path, &dim, &err) || dim == SPH_DIM) return 0;
  return exec_twin(cmd, "snapshot", path, dim);
}
