/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * cli.h - the sub-commands of the `sph` program. Each takes the argument
 * vector starting at its own name and returns the process exit status.
 * They use the library's public API only.
 *
 * Exit statuses: 0 success, 1 bad input or I/O error, 2 usage error,
 * 3 numerical blow-up, 4 interrupted (a final snapshot was written).
 */
#ifndef SPH_CLI_H
#define SPH_CLI_H

#include <stdio.h>

#include "sph.h"

/* The program as the user started it, for messages that print a command
 * to run next (main.c): argv[0] if it holds a '/', with a libtool
 * build's ".libs/" (and "lt-") taken out, else "sph". */
extern const char *sph_cli_program;

/* The command line as main() received it (twin.c hands it on). */
extern char **sph_cli_argv;
/* The program built for the other dimension (twin.c), or NULL. */
const char *sph_cli_twin(void);
/* The case file's text, read once (sph_case_read_text): from the copy a
 * handing-over program left for this one where the file could be read only
 * once (a FIFO, /dev/stdin, <(...)). Non-zero with err. */
int sph_cli_read_case(const char *path, char **text, size_t *len, sph_error *err);
/* If the case's dimension (its text, with the overrides) is not this
 * build's, runs the other build with the same arguments, the text handed
 * on where the file cannot be read again (it does not return unless that
 * fails: 1, message printed); 0 where this build runs the case. */
int sph_cli_hand_over(const char *cmd, const char *case_path, const char *text, size_t len,
                      const char *const *set, size_t n_set);
/* The same for a snapshot file (its attribute "dimension"). */
int sph_cli_hand_over_snapshot(const char *cmd, const char *path);
/* A command that makes a case of dimension dim (sph new --dim): 0 when it
 * is this build's; else the other build runs the command line (no
 * return), or 1 with a message naming `name` when it cannot. */
int sph_cli_hand_over_dim(const char *cmd, const char *name, int dim);

int sph_cli_run(int argc, char **argv);
int sph_cli_info(int argc, char **argv);
int sph_cli_profile(int argc, char **argv);
int sph_cli_audit(int argc, char **argv);
int sph_cli_face(int argc, char **argv);
int sph_cli_new(int argc, char **argv);

/* Shared by the commands that take snapshot files: checks the options
 * (only --help / -h, and "--"), counts the files. Returns 0 to go on, -1
 * after printing the usage for --help, else the exit status (2). */
int sph_cli_snapshot_args(const char *cmd, const char *usage, int argc, char **argv, int *n_files);

/* Calls fn(path, ctx, err) for each snapshot argument in order (the files
 * sph_cli_snapshot_args counted: the first "--" is skipped); a failure is
 * reported on stderr as "sph CMD: <message>" after flushing stdout, and the
 * other files are still processed. Returns 0 if every call succeeded, 1
 * otherwise. */
int sph_cli_each_snapshot(const char *cmd, int argc, char **argv,
                          int (*fn)(const char *path, void *ctx, sph_error *err), void *ctx);

/* The case a snapshot was run from: its stored case text parsed again
 * with its stored --set overrides (cli_snapcase.c). 0, or -1 with err (and
 * nothing to free). */
int sph_cli_snapshot_case(const sph_snapshot *s, sph_case *c, sph_error *err);
/* The same with n_extra further overrides applied after the stored ones
 * (sph run --restart SNAPSHOT --set time.end=...). */
int sph_cli_snapshot_case_set(const sph_snapshot *s, const char *const *extra, size_t n_extra,
                              sph_case *c, sph_error *err);

/* Whether arg is one of the NULL-terminated names. */
int sph_cli_is_one_of(const char *arg, const char *const *names);
/* --threads VALUE: a whole number from 1 to 4096 into *threads; 0, or -1
 * with the message "CMD: --threads: ..." printed. */
int sph_cli_parse_threads(const char *cmd, const char *value, int *threads);
/* --max-particles VALUE: a count from 1 to SPH_MAX_PARTICLES_HARD into
 * *max; 0, or -1 with the message "CMD: --max-particles: ..." printed. */
int sph_cli_parse_max_particles(const char *cmd, const char *value, double *max);
/* --progress SECONDS (a number from 0 to 1e9) into *seconds: 0, or -1 with
 * the message printed (cmd first). */
int sph_cli_parse_progress(const char *cmd, const char *value, double *seconds);
/* The seconds between progress lines in a log when --progress is not given. */
#define SPH_CLI_PROGRESS_DEFAULT 60.0
/* Sets the OpenMP thread count (threads > 0; 0 keeps the default) and
 * returns the count in force; without OpenMP, 1 (with a note on stderr
 * when more were asked for and quiet is 0). */
int sph_cli_set_threads(int threads, int quiet);

/* Prints a "key: value" listing (sph_case_describe) line by line after
 * indent, each number outside quotes shortened to %.6g for reading. */
void sph_cli_print_listing(FILE *f, const char *listing, const char *indent);

/* mkdir -p: creates path and its parents; 0, or -1 with errno set. */
int sph_cli_make_dirs(const char *path);

/* One run per output directory (outdir_lock.c): a record lock on
 * DIR/.sph-lock, dropped by the kernel when the holder ends. */
typedef struct sph_cli_lock {
  int fd;
  char path[4200];
} sph_cli_lock;
/* Takes DIR's lock (DIR exists): 0, held until sph_cli_dir_unlock; 1 if
 * another process holds it (*holder its pid); -1 with errno set. */
int sph_cli_dir_lock(const char *dir, sph_cli_lock *lk, long *holder);
/* Removes the lock file and releases the lock (nothing if not held). */
void sph_cli_dir_unlock(sph_cli_lock *lk);
/* The pid of the process holding DIR's lock, or 0; creates nothing. */
long sph_cli_dir_holder(const char *dir);
/* "CMD: output directory DIR is in use by another run (pid HOLDER); ..."
 * on stderr; 1 (the exit status). */
int sph_cli_dir_busy(const char *cmd, const char *dir, long holder);
/* sph_cli_dir_lock with its failures said on stderr as CMD's: 0 held, 1
 * not (the exit status). */
int sph_cli_dir_take(const char *cmd, const char *dir, sph_cli_lock *lk);

#endif
