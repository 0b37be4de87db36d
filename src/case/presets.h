/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * presets.h - the schemes of numerics.scheme as data: one table of (key
 * path, value) per scheme, the only place a scheme's keys are spelled.
 *
 * The case reader (case.c) puts a scheme's values into the case's tree for
 * every key the case leaves out, before any key is read, so the readers
 * read them as if the case gave them, and every key the case gives keeps
 * its own value (the start-up listing names those, sph_case.scheme_kept).
 * The describer prints the resolved values key by key; doc/method.md's
 * table of the schemes is held to this one by tests/test_case.c;
 * bench/validation names a scheme instead of listing its keys. Every scheme gives a value for every
 * key of every other (the same keys in the same order), so that a scheme named on the command line
 * replaces all of another's.
 */
#ifndef SPH_PRESETS_H
#define SPH_PRESETS_H

#include <stddef.h>

/* One key of a scheme: its dotted path and its value as YAML text; `needs`
 * (NULL, or a dotted path) names what must be in the case for the value to
 * be put in (geometry.tank for the tank's wall model: a case without a tank
 * gets none). */
typedef struct sph_preset_key {
  const char *key;
  const char *value;
  const char *needs;
} sph_preset_key;

typedef struct sph_preset {
  const char *name;           /* numerics.scheme's value */
  const char *title;          /* one line: what the scheme is */
  const sph_preset_key *keys; /* SPH_PRESET_KEYS of them, in the table's order */
} sph_preset;

/* The number of keys of every scheme. */
#define SPH_PRESET_KEYS 11

/* The schemes, the default first; *n their count. */
const sph_preset *sph_presets(size_t *n);
/* The scheme named name, or NULL. */
const sph_preset *sph_preset_named(const char *name);
/* The default scheme (the first). */
const sph_preset *sph_preset_default(void);

#endif
