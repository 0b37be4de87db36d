/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * outdir_lock.c - one run per output directory.
 *
 * A run holds a POSIX record lock (fcntl F_SETLK, a write lock on the
 * whole file) on DIR/.sph-lock while it writes into DIR. The kernel drops
 * the lock when the process ends, however it ends, so a lock file left by
 * a run that died is not held and the next run simply takes it: there is
 * no stale lock to clean up. A second run finds the lock held and is told
 * the holder's pid (F_GETLK). The file is empty, so two output directories
 * of the same case compare equal; the holder removes it when it is done.
 */
#include "config.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/cli.h"

#define LOCK_NAME ".sph-lock"

static int lock_path(const char *dir, char *path, size_t n) {
  const int k = snprintf(path, n, "%s/" LOCK_NAME, dir);
  if (k < 0 || (size_t)k >= n) {
    errno = ENAMETOOLONG;
    return -1;
  }
  return 0;
}

/* The pid holding a write lock on fd's file, or 0 if none. */
static long lock_holder(int fd) {
  struct flock fl;
  memset(&fl, 0, sizeof fl);
  fl.l_type = F_WRLCK;
  fl.l_whence = SEEK_SET;
  if (fcntl(fd, F_GETLK, &fl) == -1 || fl.l_type == F_UNLCK) return 0;
  return (long)fl.l_pid;
}

long sph_cli_dir_holder(const char *dir) {
  char path[4200];
  if (lock_path(dir, path, sizeof path)) return 0;
  const int fd = open(path, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0; /* no lock file: nobody holds the directory */
  const long pid = lock_holder(fd);
  close(fd);
  return pid;
}

int sph_cli_dir_lock(const char *dir, sph_cli_lock *lk, long *holder) {
  *holder = 0;
  lk->fd = -1;
  if (lock_path(dir, lk->path, sizeof lk->path)) return -1;
  for (int attempt = 0; attempt < 100; attempt++) {
    const int fd = open(lk->path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) return -1;
    struct flock fl;
    memset(&fl, 0, sizeof fl);
    fl.l_type = F_WRLCK;
    fl.l_whence = SEEK_SET;
    if (fcntl(fd, F_SETLK, &fl) == -1) {
      const int e = errno;
      if (e == EACCES || e == EAGAIN) {
        *holder = lock_holder(fd);
        close(fd);
        if (*holder == 0) continue; /* released in between: try again */
        return 1;
      }
      close(fd);
      errno = e;
      return -1;
    }
    /* locked; but if the holder before us removed the file after we had
     * opened it, the lock is on a file no one else will see: start over */
    struct stat a, b;
    if (fstat(fd, &a) == 0 && stat(lk->path, &b) == 0 && a.st_dev == b.st_dev &&
        a.st_ino == b.st_ino) {
      lk->fd = fd;
      return 0;
    }
    close(fd);
  }
  errno = EAGAIN;
  return -1;
}

void sph_cli_dir_unlock(sph_cli_lock *lk) {
  if (lk->fd < 0) return;
  unlink(lk->path); /* while still held: a run waiting on it starts over */
  close(lk->fd);
  lk->fd = -1;
}

int sph_cli_dir_busy(const char *cmd, const char *dir, long holder) {
  fprintf(stderr,
          "%s: output directory %s is in use by another run (pid %ld); wait for it to end or "
          "choose another with -o\n",
          cmd, dir, holder);
  return 1;
}

int sph_cli_dir_take(const char *cmd, const char *dir, sph_cli_lock *lk) {
  long holder = 0;
  const int rc = sph_cli_dir_lock(dir, lk, &holder);
  if (rc == 1) return sph_cli_dir_busy(cmd, dir, holder);
  if (rc) {
    fprintf(stderr, "%s: cannot lock output directory %s: %s\n", cmd, dir, strerror(errno));
    return 1;
  }
  return 0;
}
