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
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
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

/* Set in the environment of a handed-over program: it hands nothing
 * back (a loop between two programs of one dimension, SPH_TWIN naming this
 * one, or a file each reads as the other's; issue 61, E2). */
#define HANDED_OVER "SPH_HANDED_OVER"

/* Runs the other build with this command line (no return unless that fails: 1). */
static int exec_twin(const char *cmd, const char *what, const char *path, int dim) {
  const char *from = getenv(HANDED_OVER);
  if (from && *from) {
    fprintf(stderr,
            "sph %s: %s is a %d-D %s, and this %d-D program was started for it by %s: not "
            "handed back (is SPH_TWIN set to a program of the wrong dimension?)\n",
            cmd, path, dim, what, SPH_DIM, from);
    return 1;
  }
  const char *twin = sph_cli_twin();
  if (!twin || !sph_cli_argv) {
    fprintf(stderr,
            "sph %s: %s is a %d-D %s and the %d-D program (%s) is not installed beside "
            "this one\n",
            cmd, path, dim, what, dim, SPH_DIM == 2 ? "sph-3d" : "sph");
    return 1;
  }
  /* test hook (doc/testing.md): a signal in the hand-over's window */
  const char *hook = getenv("SPH_TEST_HANDOVER_SIGNAL");
  if (hook && *hook) raise(SIGTERM);
  setenv(HANDED_OVER, SPH_DIM == 2 ? "sph (2-D)" : "sph-3d (3-D)", 1);
  execv(twin, sph_cli_argv);
  unsetenv(HANDED_OVER);
  fprintf(stderr, "sph %s: cannot run the %d-D program %s: %s\n", cmd, dim, twin, strerror(errno));
  return 1;
}

/* The copy of a case file's text handed to the other program: the file
 * descriptor of an anonymous file holding it, and the path it was read
 * from (issue 61, E4). */
#define TEXT_FD "SPH_CASE_TEXT_FD"
#define TEXT_PATH "SPH_CASE_TEXT_PATH"

int sph_cli_read_case(const char *path, char **text, size_t *len, sph_error *err) {
  const char *fd = getenv(TEXT_FD), *from = getenv(TEXT_PATH);
  if (fd && from && strcmp(from, path) == 0) {
    char copy[64];
    snprintf(copy, sizeof copy, "/proc/self/fd/%d", atoi(fd));
    const int rc = sph_case_read_text(copy, text, len, err);
    close(atoi(fd));
    unsetenv(TEXT_FD);
    unsetenv(TEXT_PATH);
    if (rc) return sph_error_set(err, "%s: cannot read the copy of the case handed over", path);
    return 0;
  }
  return sph_case_read_text(path, text, len, err);
}

int sph_cli_hand_over(const char *cmd, const char *case_path, const char *text, size_t len,
                      const char *const *set, size_t n_set) {
  int dim = SPH_DIM;
  sph_error err = {{0}};
  if (sph_case_text_dimension(text, len, case_path, set, n_set, &dim, &err) || dim == SPH_DIM)
    return 0; /* (an error: the case reader says it in full) */
  /* a file that is not a regular one (a FIFO, a terminal, a pipe) cannot be
   * read a second time: the other program gets a copy of the text */
  struct stat st;
  if (stat(case_path, &st) != 0 || !S_ISREG(st.st_mode)) {
    const int fd = memfd_create("sph-case", 0);
    if (fd < 0 || write(fd, text, len) != (ssize_t)len) {
      fprintf(stderr, "sph %s: %s: cannot keep a copy of the case for the %d-D program: %s\n", cmd,
              case_path, dim, strerror(errno));
      if (fd >= 0) close(fd);
      return 1;
    }
    char v[32];
    snprintf(v, sizeof v, "%d", fd);
    setenv(TEXT_FD, v, 1);
    setenv(TEXT_PATH, case_path, 1);
  }
  return exec_twin(cmd, "case", case_path, dim);
}

int sph_cli_hand_over_snapshot(const char *cmd, const char *path) {
  int dim = SPH_DIM;
  sph_error err = {{0}};
  if (sph_snapshot_file_dimension(path, &dim, &err) || dim == SPH_DIM) return 0;
  return exec_twin(cmd, "snapshot", path, dim);
}

int sph_cli_hand_over_dim(const char *cmd, const char *name, int dim) {
  return dim == SPH_DIM ? 0 : exec_twin(cmd, "case", name, dim);
}
