/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * afl_main.c - the AFL++ driver of one fuzz target (harness.h), chosen at
 * build time: -DFUZZ_TARGET_CASE, -DFUZZ_TARGET_SNAPSHOT or -DFUZZ_TARGET_CSV. Built by
 * fuzz/run with afl-clang-fast (persistent mode: many inputs per process);
 * built with any other compiler it replays the files named on its command
 * line once each (or stdin), which is how a crash is reproduced by hand.
 */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "harness.h"

static char scratch[4096];

static int one(const uint8_t *data, size_t len) {
#if defined(FUZZ_TARGET_CASE)
  return sph_fuzz_case(data, len);
#elif defined(FUZZ_TARGET_SNAPSHOT)
  return sph_fuzz_snapshot(data, len, scratch);
#elif defined(FUZZ_TARGET_CSV)
  return sph_fuzz_csv(data, len, scratch);
#else
#error "define FUZZ_TARGET_CASE, FUZZ_TARGET_SNAPSHOT or FUZZ_TARGET_CSV"
#endif
}

static uint8_t *read_all(FILE *f, size_t *len) {
  size_t cap = 65536, n = 0;
  uint8_t *buf = malloc(cap);
  while (buf) {
    n += fread(buf + n, 1, cap - n, f);
    if (n < cap) break;
    uint8_t *nb = realloc(buf, 2 * cap);
    if (!nb) {
      free(buf);
      return NULL;
    }
    buf = nb;
    cap *= 2;
  }
  *len = n;
  return buf;
}

#ifdef __AFL_FUZZ_TESTCASE_LEN
__AFL_FUZZ_INIT();
#endif

int main(int argc, char **argv) {
  const char *dir = getenv("FUZZ_SCRATCH_DIR");
  snprintf(scratch, sizeof scratch, "%s/sph_fuzz_%ld.h5", dir && *dir ? dir : "/tmp",
           (long)getpid());
#ifdef __AFL_FUZZ_TESTCASE_LEN
  (void)argc;
  (void)argv;
  __AFL_INIT();
  const uint8_t *buf = __AFL_FUZZ_TESTCASE_BUF;
  while (__AFL_LOOP(2000))
    one(buf, (size_t)__AFL_FUZZ_TESTCASE_LEN);
#else
  for (int i = 1; i <= argc; i++) {
    if (i == argc && argc > 1) break;
    FILE *f = i < argc ? fopen(argv[i], "rb") : stdin;
    if (!f) {
      perror(argv[i]);
      return 1;
    }
    size_t len = 0;
    uint8_t *data = read_all(f, &len);
    if (f != stdin) fclose(f);
    if (!data) return 1;
    one(data, len);
    free(data);
  }
#endif
  remove(scratch);
  return 0;
}
