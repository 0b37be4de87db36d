/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * yaml_tree.h - a strict YAML reader: text to a small tree whose every node
 * and key remembers where it came from, dotted-key overrides, and typed
 * readers that report the first violation as "origin:line: key: expected
 * ..., got ...". Internal to the library (the case schema, src/case/case.c,
 * is built on it); tests/test_yaml_tree.c holds it to its rules.
 *
 * What it refuses while reading (sph_yaml_parse): duplicate keys, keys that
 * are not scalars, aliases, explicit tags, more than one document, nesting
 * deeper than SPH_YAML_MAX_DEPTH. An override "dotted.key=value"
 * (sph_yaml_apply_set) parses its value as a document of its own and puts
 * it at that path, creating mappings on the way; its nodes say which
 * override they came from. Every function that can fail sets the context's
 * error and returns non-zero; nothing is printed.
 */
#ifndef SPH_YAML_TREE_H
#define SPH_YAML_TREE_H

#include <stddef.h>

#include "core/error.h"

#define SPH_YAML_FROM_FILE (-1)   /* a node's source: the text (else the index of an override) */
#define SPH_YAML_FROM_SCHEME (-2) /* or the scheme's default for a key the case leaves out */
#define SPH_YAML_MAX_DEPTH 64     /* the deepest nesting accepted */
#define SPH_YAML_KEYLEN 256       /* room for a dotted key such as geometry.fluid[3].x */

typedef enum { SPH_YAML_SCALAR, SPH_YAML_LIST, SPH_YAML_MAP } sph_yaml_kind;

typedef struct sph_yaml_node sph_yaml_node;

typedef struct sph_yaml_entry {
  char *key;
  int src;     /* SPH_YAML_FROM_FILE or the index of the --set that added the key */
  size_t line; /* 1-based line of the key in the file; 0 from --set */
  sph_yaml_node *val;
} sph_yaml_entry;

struct sph_yaml_node {
  sph_yaml_kind kind;
  int src;                 /* SPH_YAML_FROM_FILE or the index of the --set that gave it */
  size_t line;             /* 1-based line in the file; 0 from --set */
  char *text;              /* scalar: its text */
  int plain;               /* scalar: written plain (not quoted, not a block scalar) */
  size_t n;                /* list items or mapping entries */
  sph_yaml_node **items;   /* list */
  sph_yaml_entry *entries; /* mapping, in the order written */
};

/* An interval: kind 0 = unbounded, '[' / ']' closed, '(' / ')' open. `what`,
 * if set, replaces the generated description in messages. */
typedef struct sph_yaml_range {
  double lo, hi;
  char lo_kind, hi_kind;
  const char *what;
} sph_yaml_range;

/* Where the text and the overrides come from, and where errors go. */
typedef struct sph_yaml_ctx {
  const char *origin; /* the file path (or the caller's name for the text) */
  const char *text;   /* the whole text, for locating syntax errors */
  size_t len;
  const char *const *set; /* the overrides "dotted.key=value" */
  sph_error *err;
  const char *scheme; /* the scheme whose defaults were put in (sph_yaml_put_default), or NULL */
} sph_yaml_ctx;

/* The ranges most keys take: any number, > 0, >= 0, [0, 1]. */
extern const sph_yaml_range SPH_YAML_ANY, SPH_YAML_POS, SPH_YAML_NONNEG, SPH_YAML_UNIT;

/* ---- the tree ---- */

/* Parses one YAML document (text, len) into *out; an empty document is an
 * empty plain scalar (YAML's null). src is SPH_YAML_FROM_FILE or the index
 * of the override the text is the value of, key that override's key (for
 * messages). */
int sph_yaml_parse(const sph_yaml_ctx *x, const char *text, size_t len, int src, const char *key,
                   sph_yaml_node **out);
/* Applies override i of x->set to the mapping root. */
int sph_yaml_apply_set(const sph_yaml_ctx *x, sph_yaml_node *root, int i);
/* Puts value (YAML text) at the dotted key, creating mappings on the way, its
 * nodes from SPH_YAML_FROM_SCHEME (messages name x->scheme); the caller has
 * checked that the key is not there. */
int sph_yaml_put_default(const sph_yaml_ctx *x, sph_yaml_node *root, const char *key,
                         const char *value);
void sph_yaml_free(sph_yaml_node *t);
/* The entry of key in the mapping m, or NULL. */
sph_yaml_entry *sph_yaml_find(const sph_yaml_node *m, const char *key);

/* ---- errors and text ---- */

/* "origin[:line]: key: message" (the origin of an override's node is the
 * override); returns -1. */
int sph_yaml_fail(const sph_yaml_ctx *x, int src, size_t line, const char *key, const char *fmt,
                  ...) __attribute__((format(printf, 5, 6)));
/* The same at the node t's place. */
int sph_yaml_fail_at(const sph_yaml_ctx *x, const sph_yaml_node *t, const char *key,
                     const char *fmt, ...) __attribute__((format(printf, 4, 5)));
int sph_yaml_oom(const sph_yaml_ctx *x);
/* What a node is, for "got ...": a quoted, shortened, printable scalar, or
 * "a mapping", "a list of n items", "nothing". */
const char *sph_yaml_got(const sph_yaml_node *t, char *buf, size_t n);
/* prefix.key (key alone without a prefix). */
void sph_yaml_join(char *buf, size_t n, const char *prefix, const char *key);
/* "a, b, c" of a NULL-terminated list. */
void sph_yaml_list_names(const char *const *names, char *buf, size_t n);
/* snprintf where truncation is harmless (names, messages). */
void sph_yaml_bprintf(char *buf, size_t n, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* A copy of s[0 .. n-1], NUL-terminated (NULL when out of memory). */
char *sph_yaml_dup(const char *s, size_t n);

/* ---- typed readers of a node (kp: its dotted key, for messages) ---- */

/* A finite decimal number, plain, within r. */
int sph_yaml_read_number(const sph_yaml_ctx *x, const sph_yaml_node *t, const char *kp,
                         const sph_yaml_range *r, double *out);
int sph_yaml_read_int(const sph_yaml_ctx *x, const sph_yaml_node *t, const char *kp, long lo,
                      long hi, int *out);
/* true or false, plain. */
int sph_yaml_read_bool(const sph_yaml_ctx *x, const sph_yaml_node *t, const char *kp, int *out);
/* One of the NULL-terminated names: its index. */
int sph_yaml_read_choice(const sph_yaml_ctx *x, const sph_yaml_node *t, const char *kp,
                         const char *const *names, int *out);
/* A list of exactly two numbers; axis ('x', 'y'; 0: none) also requires v0 < v1. */
/* A list of exactly n numbers (n <= 8): a vector such as gravity. */
int sph_yaml_read_vector(const sph_yaml_ctx *x, const sph_yaml_node *t, const char *kp, int n,
                         double *out);
int sph_yaml_read_pair(const sph_yaml_ctx *x, const sph_yaml_node *t, const char *kp, char axis,
                       double out[2]);

/* ---- keys of a mapping m at the dotted path ---- */

/* Unknown keys of m are errors (valid: NULL-terminated). */
int sph_yaml_check_keys(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *path,
                        const char *const *valid);
/* The value of key in m: 1 found, 0 absent (optional), -1 missing
 * (required); kp gets path.key. */
int sph_yaml_lookup(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *path,
                    const char *key, int required, const sph_yaml_node **out,
                    char kp[SPH_YAML_KEYLEN]);
/* The typed readers above on m's key: 1 read, 0 absent, -1 an error. */
int sph_yaml_get_number(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *path,
                        const char *key, int required, const sph_yaml_range *r, double *out);
int sph_yaml_get_int(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *path,
                     const char *key, long lo, long hi, int *out);
int sph_yaml_get_bool(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *path,
                      const char *key, int *out);
int sph_yaml_get_choice(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *path,
                        const char *key, const char *const *names, int *out);
int sph_yaml_get_vector(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *path,
                        const char *key, int required, int n, double *out);
int sph_yaml_get_pair(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *path,
                      const char *key, int required, char axis, double out[2]);
/* A mapping-valued key whose own keys are all in valid. */
int sph_yaml_get_section(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *path,
                         const char *key, int required, const char *const *valid,
                         const sph_yaml_node **out);
/* A scalar key's text, a new string in *out (the old one freed). */
int sph_yaml_get_string(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *key,
                        int required, char **out);

#endif
