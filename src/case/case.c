/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * case.c - the strict YAML case-file reader (see case.h).
 *
 * Algorithm. The text is parsed with libyaml's document API
 * (yaml_parser_load) and copied into a small private tree of scalars, lists
 * and mappings in which every node and every mapping key remembers where it
 * came from: the file and its 1-based line, or the index of the `--set`
 * override that produced it. While copying, duplicate keys, non-scalar keys,
 * aliases, explicit tags and extra documents are rejected. Each override
 * `dotted.key=value` is split at its first '='; its value is parsed as a YAML
 * document of its own and replaces the node at that path, or is added there
 * (creating intermediate mappings). Only then is the tree validated, in
 * schema order: every mapping is first checked for unknown keys, then each
 * key is read by a typed reader (number with a range, integer, boolean,
 * choice, string, pair of numbers) which reports the first violation as
 * "origin:line: dotted.key: expected ..., got ...". Defaults are stored in
 * the case before the readers run, so an absent optional key keeps its
 * default; derived values (c0, h) and the cross-checks between sections
 * follow the section they depend on.
 *
 * Invariants. The library never prints or exits: every function that can
 * fail returns non-zero with the error set. Every allocation is released on
 * every path; on failure the case is left zeroed, so sph_case_free is always
 * safe. The result depends only on the text and the overrides: the same
 * input gives the same case, the same first error and the same
 * sph_case_describe text.
 */
#include "config.h"

#include "case/case.h"

#include "physics/density_diffusion.h"
#include "physics/shifting.h"

#include "physics/filter.h"
#include "walls/wavemaker.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <yaml.h>

#define FROM_FILE (-1)            /* node source: the case file (else a --set index) */
#define MAX_DEPTH 64              /* deepest nesting accepted in a case file */
#define MAX_CASE_BYTES (1u << 20) /* the largest case file read: 1 MiB (issue 21, D8) */
#define MAX_DESCRIPTION 10000     /* the longest description, in bytes (stored in snapshots: D12) */
#define SPH_MAX_OUTPUTS 100000    /* output times from time.output_interval, at most */
#define KEYLEN 256                /* room for a dotted key such as geometry.fluid[3].x */

/* ---- choices -------------------------------------------------------------- */

static const char *const kernel_names[] = {"cubic_spline", "wendland_c2", NULL};
static const char *const integrator_names[] = {"predictor_corrector", "leapfrog", NULL};
static const char *const dt_rule_names[] = {"paper_b", "cfl", "fixed", NULL};
static const char *const boundary_names[] = {"dynamic", "fixed_layers", "repulsive",
                                             "mirror",  "mdbc",         NULL};
static const char *const viscosity_names[] = {"none", "stress_tensor", "morris", NULL};
static const char *const stop_names[] = {"none", "front_at_wall", NULL};

static const char *choice_name(const char *const *names, int k) {
  for (int i = 0; names[i]; i++)
    if (i == k) return names[i];
  return "unknown";
}

const char *sph_kernel_name(sph_kernel_kind k) { return choice_name(kernel_names, (int)k); }
const char *sph_integrator_name(sph_integrator_kind k) {
  return choice_name(integrator_names, (int)k);
}
const char *sph_dt_rule_name(sph_dt_rule r) { return choice_name(dt_rule_names, (int)r); }
const char *sph_boundary_name(sph_boundary_kind b) { return choice_name(boundary_names, (int)b); }
const char *sph_stop_name(sph_stop_kind s) { return choice_name(stop_names, (int)s); }
const char *sph_viscosity_name(sph_viscosity_kind v) {
  return choice_name(viscosity_names, (int)v);
}

int sph_case_needs_free_surface(const sph_case *c) {
  return c->output_free_surface || c->fs_h_factor > 0.0;
}

int sph_case_has_boundary(const sph_case *c, sph_boundary_kind b) {
  int has = c->tank.present && c->tank.boundary == b;
  for (size_t k = 0; k < c->n_walls; k++)
    has |= c->walls[k].boundary == b;
  return has;
}

/* ---- the tree ------------------------------------------------------------- */

typedef enum { NODE_SCALAR, NODE_LIST, NODE_MAP } node_kind;

typedef struct node node;

typedef struct entry {
  char *key;
  int src;     /* FROM_FILE or the index of the --set that added the key */
  size_t line; /* 1-based line of the key in the file; 0 from --set */
  node *val;
} entry;

struct node {
  node_kind kind;
  int src;        /* FROM_FILE or the index of the --set that gave it */
  size_t line;    /* 1-based line in the file; 0 from --set */
  char *text;     /* scalar: its text */
  int plain;      /* scalar: written plain (not quoted, not a block scalar) */
  size_t n;       /* list items or mapping entries */
  node **items;   /* list */
  entry *entries; /* mapping, in the order written */
};

static void node_free(node *t) {
  if (!t) return;
  for (size_t i = 0; i < t->n; i++) {
    if (t->kind == NODE_LIST) {
      node_free(t->items[i]);
    } else if (t->kind == NODE_MAP) {
      free(t->entries[i].key);
      node_free(t->entries[i].val);
    }
  }
  free(t->text);
  free(t->items);
  free(t->entries);
  free(t);
}

static node *node_new(node_kind kind, int src, size_t line) {
  node *t = calloc(1, sizeof *t);
  if (!t) return NULL;
  t->kind = kind;
  t->src = src;
  t->line = line;
  return t;
}

static char *dup_n(const char *s, size_t n) {
  char *d = malloc(n + 1);
  if (!d) return NULL;
  if (n) memcpy(d, s, n);
  d[n] = '\0';
  return d;
}

/* snprintf into a fixed buffer where truncation is harmless (names, messages). */
static void bprintf(char *buf, size_t n, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static void bprintf(char *buf, size_t n, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, n, fmt, ap);
  va_end(ap);
}

static entry *find(const node *m, const char *key) {
  for (size_t i = 0; i < m->n; i++)
    if (strcmp(m->entries[i].key, key) == 0) return &m->entries[i];
  return NULL;
}

/* ---- errors --------------------------------------------------------------- */

typedef struct ctx {
  const char *origin; /* the file path (or the caller's name for the text) */
  const char *text;   /* the case text, for locating reader errors */
  size_t len;
  const char *const *set; /* the overrides */
  sph_error *err;
  const node *dx_node;       /* numerics.dx, for the cross-checks */
  const node *stop_node;     /* time.stop if given */
  const node *shifting_node; /* numerics.shifting if given */
} ctx;

/* "origin[:line]: key: message"; the origin of a --set node is the --set. */
static int failv(const ctx *x, int src, size_t line, const char *key, const char *fmt, va_list ap) {
  char where[512], msg[768];
  if (src >= 0)
    bprintf(where, sizeof where, "--set %s", x->set[src]);
  else if (line > 0)
    bprintf(where, sizeof where, "%s:%zu", x->origin, line);
  else
    bprintf(where, sizeof where, "%s", x->origin);
  vsnprintf(msg, sizeof msg, fmt, ap);
  if (key && *key) return sph_error_set(x->err, "%s: %s: %s", where, key, msg);
  return sph_error_set(x->err, "%s: %s", where, msg);
}

static int fail(const ctx *x, int src, size_t line, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
static int fail(const ctx *x, int src, size_t line, const char *key, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int rc = failv(x, src, line, key, fmt, ap);
  va_end(ap);
  return rc;
}

static int fail_at(const ctx *x, const node *t, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static int fail_at(const ctx *x, const node *t, const char *key, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int rc = failv(x, t->src, t->line, key, fmt, ap);
  va_end(ap);
  return rc;
}

static int oom(const ctx *x) { return sph_error_set(x->err, "%s: out of memory", x->origin); }

/* What a node is, for "got ...": a quoted, shortened, printable scalar. */
static const char *got(const node *t, char *buf, size_t n) {
  if (t->kind == NODE_MAP) return "a mapping";
  if (t->kind == NODE_LIST) {
    if (t->n == 0) return "an empty list";
    bprintf(buf, n, "a list of %zu item%s", t->n, t->n == 1 ? "" : "s");
    return buf;
  }
  if (t->plain && !t->text[0]) return "nothing";
  char s[72];
  size_t len = strlen(t->text), k = len > 60 ? 60 : len;
  while (k < len && k > 0 && ((unsigned char)t->text[k] & 0xC0) == 0x80)
    k--;
  for (size_t i = 0; i < k; i++) {
    unsigned char ch = (unsigned char)t->text[i];
    s[i] = (ch < 0x20 || ch == 0x7f) ? '?' : (char)ch;
  }
  s[k] = '\0';
  bprintf(buf, n, "%s'%s%s'", t->plain ? "" : "the string ", s, k < len ? "..." : "");
  return buf;
}

static void join(char *buf, size_t n, const char *prefix, const char *key) {
  if (prefix && *prefix)
    bprintf(buf, n, "%s.%s", prefix, key);
  else
    bprintf(buf, n, "%s", key);
}

/* ---- YAML text to tree ---------------------------------------------------- */

typedef struct loader {
  const ctx *x;
  yaml_document_t *doc;
  int src;
  unsigned char *seen; /* per document node: copied already (so an alias) */
} loader;

static int copy_node(loader *L, yaml_node_t *y, const char *path, int depth, node **out);

static size_t mark_line(const loader *L, yaml_mark_t m) {
  return L->src == FROM_FILE ? m.line + 1 : 0;
}

/* The document node `id`, which must not have been copied before. */
static int child(loader *L, int id, size_t line, const char *path, yaml_node_t **out) {
  yaml_node_t *y = yaml_document_get_node(L->doc, id);
  *out = NULL;
  if (!y) return fail(L->x, L->src, line, path, "malformed YAML document");
  size_t k = (size_t)(y - L->doc->nodes.start);
  if (L->seen[k]) return fail(L->x, L->src, line, path, "aliases (*name) are not supported");
  L->seen[k] = 1;
  *out = y;
  return 0;
}

static int default_tag(const yaml_node_t *y) {
  const char *tag = (const char *)y->tag;
  const char *want = y->type == YAML_SCALAR_NODE     ? YAML_DEFAULT_SCALAR_TAG
                     : y->type == YAML_SEQUENCE_NODE ? YAML_DEFAULT_SEQUENCE_TAG
                                                     : YAML_DEFAULT_MAPPING_TAG;
  return !tag || strcmp(tag, want) == 0;
}

static int copy_scalar(loader *L, yaml_node_t *y, const char *path, node *t) {
  const char *v = (const char *)y->data.scalar.value;
  size_t len = y->data.scalar.length;
  if (memchr(v, '\0', len)) return fail_at(L->x, t, path, "a NUL character is not allowed");
  t->plain = y->data.scalar.style == YAML_PLAIN_SCALAR_STYLE;
  t->text = dup_n(v, len);
  return t->text ? 0 : oom(L->x);
}

static int copy_list(loader *L, yaml_node_t *y, const char *path, int depth, node *t) {
  size_t n = (size_t)(y->data.sequence.items.top - y->data.sequence.items.start);
  if (n && !(t->items = calloc(n, sizeof *t->items))) return oom(L->x);
  for (size_t i = 0; i < n; i++) {
    char kp[KEYLEN];
    yaml_node_t *c;
    bprintf(kp, sizeof kp, "%s[%zu]", path, i);
    if (child(L, y->data.sequence.items.start[i], t->line, kp, &c)) return -1;
    if (copy_node(L, c, kp, depth + 1, &t->items[i])) return -1;
    t->n = i + 1;
  }
  return 0;
}

static int copy_map(loader *L, yaml_node_t *y, const char *path, int depth, node *t) {
  size_t n = (size_t)(y->data.mapping.pairs.top - y->data.mapping.pairs.start);
  if (n && !(t->entries = calloc(n, sizeof *t->entries))) return oom(L->x);
  for (size_t i = 0; i < n; i++) {
    const yaml_node_pair_t *p = &y->data.mapping.pairs.start[i];
    yaml_node_t *k, *v;
    entry *e = &t->entries[i];
    if (child(L, p->key, t->line, path, &k)) return -1;
    e->src = L->src;
    e->line = mark_line(L, k->start_mark);
    if (k->type != YAML_SCALAR_NODE)
      return fail(L->x, e->src, e->line, path, "a mapping key must be a plain name");
    const char *ks = (const char *)k->data.scalar.value;
    char kp[KEYLEN];
    join(kp, sizeof kp, path, ks);
    for (size_t j = 0; j < i; j++)
      if (strcmp(t->entries[j].key, ks) == 0) {
        if (L->src == FROM_FILE)
          return fail(L->x, e->src, e->line, kp, "duplicate key (first given at line %zu)",
                      t->entries[j].line);
        return fail(L->x, e->src, e->line, kp, "duplicate key");
      }
    if (!(e->key = dup_n(ks, k->data.scalar.length))) return oom(L->x);
    t->n = i + 1;
    if (child(L, p->value, e->line, kp, &v)) return -1;
    if (copy_node(L, v, kp, depth + 1, &e->val)) return -1;
  }
  return 0;
}

static int copy_node(loader *L, yaml_node_t *y, const char *path, int depth, node **out) {
  size_t line = mark_line(L, y->start_mark);
  *out = NULL;
  if (depth > MAX_DEPTH)
    return fail(L->x, L->src, line, path, "nested deeper than %d levels", MAX_DEPTH);
  if (!default_tag(y))
    return fail(L->x, L->src, line, path, "tags such as '%s' are not supported",
                (const char *)y->tag);
  node_kind kind = y->type == YAML_SCALAR_NODE     ? NODE_SCALAR
                   : y->type == YAML_SEQUENCE_NODE ? NODE_LIST
                                                   : NODE_MAP;
  node *t = node_new(kind, L->src, line);
  if (!t) return oom(L->x);
  int rc = kind == NODE_SCALAR ? copy_scalar(L, y, path, t)
           : kind == NODE_LIST ? copy_list(L, y, path, depth, t)
                               : copy_map(L, y, path, depth, t);
  if (rc) {
    node_free(t);
    return -1;
  }
  *out = t;
  return 0;
}

/* 1-based line and column of byte `off` of the text. */
static void locate(const char *text, size_t len, size_t off, size_t *line, size_t *col) {
  *line = 1;
  *col = 1;
  for (size_t i = 0; i < off && i < len; i++) {
    if (text[i] == '\n') {
      ++*line;
      *col = 1;
    } else {
      ++*col;
    }
  }
}

static int syntax_error(const ctx *x, const yaml_parser_t *p, const char *text, size_t len, int src,
                        const char *key) {
  const char *problem = p->problem ? p->problem : "cannot be parsed";
  size_t line = p->problem_mark.line + 1, col = p->problem_mark.column + 1;
  char ctxt[256] = "";
  if (p->error == YAML_MEMORY_ERROR) return oom(x);
  if (p->error == YAML_READER_ERROR) locate(text, len, p->problem_offset, &line, &col);
  if (p->context && src == FROM_FILE)
    bprintf(ctxt, sizeof ctxt, " (%s at line %zu, column %zu)", p->context,
            p->context_mark.line + 1, p->context_mark.column + 1);
  else if (p->context)
    bprintf(ctxt, sizeof ctxt, " (%s)", p->context);
  if (src == FROM_FILE)
    return sph_error_set(x->err, "%s:%zu:%zu: YAML syntax error: %s%s", x->origin, line, col,
                         problem, ctxt);
  if (p->problem_mark.index >= len)
    return fail(x, src, 0, key, "YAML syntax error in the value at its end: %s%s", problem, ctxt);
  return fail(x, src, 0, key, "YAML syntax error in the value at column %zu: %s%s", col, problem,
              ctxt);
}

/* The nesting of the text checked event by event before the document is
 * loaded: libyaml's loader takes time quadratic in the depth (200 KB of
 * '[' took 20 s), the event parser stops at the first level too deep
 * (issue 21, D6). 0 if within MAX_DEPTH (or a syntax error, which the
 * loader then reports), else -1 with the message. */
static int check_depth(const ctx *x, const char *text, size_t len, int src, const char *key) {
  yaml_parser_t p;
  if (!yaml_parser_initialize(&p)) return oom(x);
  yaml_parser_set_input_string(&p, (const unsigned char *)text, len);
  int depth = 0, rc = 0;
  for (;;) {
    yaml_event_t e;
    if (!yaml_parser_parse(&p, &e)) break; /* the loader reports it */
    const yaml_event_type_t type = e.type;
    const size_t line = e.start_mark.line + 1;
    yaml_event_delete(&e);
    if (type == YAML_SEQUENCE_START_EVENT || type == YAML_MAPPING_START_EVENT) {
      if (++depth > MAX_DEPTH + 1) {
        rc = fail(x, src, src == FROM_FILE ? line : 0, key ? key : "",
                  "nested deeper than %d levels", MAX_DEPTH);
        break;
      }
    } else if (type == YAML_SEQUENCE_END_EVENT || type == YAML_MAPPING_END_EVENT) {
      depth--;
    } else if (type == YAML_STREAM_END_EVENT) {
      break;
    }
  }
  yaml_parser_delete(&p);
  return rc;
}

/* Parses one YAML document into a tree; an empty document is an empty
 * plain scalar (YAML's null). `key` names a --set value in messages. */
static int parse_yaml(const ctx *x, const char *text, size_t len, int src, const char *key,
                      node **out) {
  yaml_parser_t p;
  yaml_document_t doc;
  int rc = 0;
  *out = NULL;
  if (check_depth(x, text, len, src, key)) return -1;
  if (!yaml_parser_initialize(&p)) return oom(x);
  yaml_parser_set_input_string(&p, (const unsigned char *)text, len);
  if (!yaml_parser_load(&p, &doc)) {
    rc = syntax_error(x, &p, text, len, src, key);
    yaml_parser_delete(&p);
    return rc;
  }
  yaml_node_t *root = yaml_document_get_root_node(&doc);
  if (root) {
    size_t n = (size_t)(doc.nodes.top - doc.nodes.start);
    loader L = {x, &doc, src, calloc(n, 1)};
    if (!L.seen) {
      rc = oom(x);
    } else {
      L.seen[root - doc.nodes.start] = 1;
      rc = copy_node(&L, root, key ? key : "", 0, out);
    }
    free(L.seen);
  } else {
    *out = node_new(NODE_SCALAR, src, src == FROM_FILE ? 1 : 0);
    if (!*out || !((*out)->text = dup_n("", 0))) rc = oom(x);
    if (*out) (*out)->plain = 1;
  }
  yaml_document_delete(&doc);
  if (rc == 0) {
    yaml_document_t more;
    if (!yaml_parser_load(&p, &more)) {
      rc = syntax_error(x, &p, text, len, src, key);
    } else {
      yaml_node_t *r2 = yaml_document_get_root_node(&more);
      if (r2)
        rc = fail(x, src, src == FROM_FILE ? r2->start_mark.line + 1 : 0, key,
                  "only one YAML document is allowed");
      yaml_document_delete(&more);
    }
  }
  if (rc) {
    node_free(*out);
    *out = NULL;
  }
  yaml_parser_delete(&p);
  return rc;
}

/* ---- overrides ------------------------------------------------------------ */

static int valid_dotted_key(const char *k, size_t n) {
  if (n == 0 || k[0] == '.' || k[n - 1] == '.') return 0;
  for (size_t i = 0; i < n; i++) {
    char ch = k[i];
    int ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
             ch == '_' || (ch == '.' && k[i + 1] != '.');
    if (!ok) return 0;
  }
  return 1;
}

static int add_entry(const ctx *x, node *m, const char *key, size_t klen, int src, node *val) {
  entry *e = realloc(m->entries, (m->n + 1) * sizeof *e);
  if (!e) return oom(x);
  m->entries = e;
  e = &m->entries[m->n];
  if (!(e->key = dup_n(key, klen))) return oom(x);
  e->src = src;
  e->line = 0;
  e->val = val;
  m->n++;
  return 0;
}

/* Puts `val` at the dotted key `key` of the mapping root (takes val). */
static int place(const ctx *x, node *root, const char *key, int src, node *val) {
  node *m = root;
  const char *seg = key;
  for (;;) {
    const char *dot = strchr(seg, '.');
    size_t slen = dot ? (size_t)(dot - seg) : strlen(seg);
    char name[KEYLEN];
    bprintf(name, sizeof name, "%.*s", (int)slen, seg);
    entry *e = find(m, name);
    if (!dot) {
      if (e) {
        node_free(e->val);
        e->val = val;
        return 0;
      }
      if (add_entry(x, m, seg, slen, src, val)) {
        node_free(val);
        return -1;
      }
      return 0;
    }
    if (!e) {
      node *sub = node_new(NODE_MAP, src, 0);
      int rc = sub ? add_entry(x, m, seg, slen, src, sub) : oom(x);
      if (rc) {
        node_free(sub);
        node_free(val);
        return rc;
      }
      e = &m->entries[m->n - 1];
    } else if (e->val->kind != NODE_MAP) {
      char at[64] = "", g[96];
      if (e->val->src == FROM_FILE) bprintf(at, sizeof at, " (line %zu)", e->val->line);
      int rc = fail(x, src, 0, NULL, "%.*s: is %s%s, not a mapping, so '%s' cannot be set in it",
                    (int)(dot - key), key, got(e->val, g, sizeof g), at, dot + 1);
      node_free(val);
      return rc;
    }
    m = e->val;
    seg = dot + 1;
  }
}

static int apply_set(const ctx *x, node *root, int i) {
  const char *s = x->set[i];
  const char *eq = s ? strchr(s, '=') : NULL;
  if (!eq || !valid_dotted_key(s, (size_t)(eq - s)))
    return fail(x, i, 0, NULL,
                "expected dotted.key=value (a key such as numerics.dx, then '=', then a YAML "
                "value)");
  char *key = dup_n(s, (size_t)(eq - s));
  node *val;
  if (!key) return oom(x);
  int rc = parse_yaml(x, eq + 1, strlen(eq + 1), i, key, &val);
  if (rc == 0) rc = place(x, root, key, i, val);
  free(key);
  return rc;
}

/* ---- typed readers -------------------------------------------------------- */

/* An interval: kind 0 = unbounded, '[' / ']' closed, '(' / ')' open. `what`,
 * if set, replaces the generated description in messages. */
typedef struct range {
  double lo, hi;
  char lo_kind, hi_kind;
  const char *what;
} range;

static const range R_ANY = {0, 0, 0, 0, NULL};
static const range R_POS = {0, 0, '(', 0, NULL};
static const range R_NONNEG = {0, 0, '[', 0, NULL};
static const range R_UNIT = {0, 1, '[', ']', NULL};

static int in_range(const range *r, double v) {
  if (r->lo_kind == '[' && !(v >= r->lo)) return 0;
  if (r->lo_kind == '(' && !(v > r->lo)) return 0;
  if (r->hi_kind == ']' && !(v <= r->hi)) return 0;
  if (r->hi_kind == ')' && !(v < r->hi)) return 0;
  return 1;
}

static const char *range_text(const range *r, char *buf, size_t n) {
  if (r->what) return r->what;
  if (!r->lo_kind && !r->hi_kind) return "a number";
  if (r->lo_kind == '(' && r->lo == 0 && !r->hi_kind) return "a positive number";
  if (!r->hi_kind)
    bprintf(buf, n, "a number %s %g", r->lo_kind == '[' ? ">=" : ">", r->lo);
  else if (!r->lo_kind)
    bprintf(buf, n, "a number %s %g", r->hi_kind == ']' ? "<=" : "<", r->hi);
  else
    bprintf(buf, n, "a number in %c%g, %g%c", r->lo_kind, r->lo, r->hi, r->hi_kind);
  return buf;
}

/* A finite decimal number spelled with [0-9+-.eE] only, wholly consumed. */
static int parse_number(const char *s, double *v) {
  if (!*s || strspn(s, "0123456789+-.eE") != strlen(s)) return -1;
  char *end;
  errno = 0;
  double d = strtod(s, &end);
  if (*end || end == s || !isfinite(d)) return -1;
  *v = d;
  return 0;
}

static int read_number(const ctx *x, const node *t, const char *kp, const range *r, double *out) {
  double v;
  if (t->kind != NODE_SCALAR || !t->plain || parse_number(t->text, &v) || !in_range(r, v)) {
    char b1[96], b2[96];
    return fail_at(x, t, kp, "expected %s, got %s", range_text(r, b1, sizeof b1),
                   got(t, b2, sizeof b2));
  }
  *out = v;
  return 0;
}

static int read_int(const ctx *x, const node *t, const char *kp, long lo, long hi, int *out) {
  const char *s = t->kind == NODE_SCALAR ? t->text : "";
  const char *digits = (*s == '-' || *s == '+') ? s + 1 : s;
  long v = 0;
  int ok = t->kind == NODE_SCALAR && t->plain && *digits &&
           strspn(digits, "0123456789") == strlen(digits);
  if (ok) {
    errno = 0;
    v = strtol(s, NULL, 10);
    ok = errno == 0 && v >= lo && v <= hi;
  }
  if (!ok) {
    char b[96];
    return fail_at(x, t, kp, "expected an integer in %ld..%ld, got %s", lo, hi,
                   got(t, b, sizeof b));
  }
  *out = (int)v;
  return 0;
}

static int read_bool(const ctx *x, const node *t, const char *kp, int *out) {
  if (t->kind == NODE_SCALAR && t->plain && strcmp(t->text, "true") == 0) {
    *out = 1;
  } else if (t->kind == NODE_SCALAR && t->plain && strcmp(t->text, "false") == 0) {
    *out = 0;
  } else {
    char b[96];
    return fail_at(x, t, kp, "expected true or false, got %s", got(t, b, sizeof b));
  }
  return 0;
}

static void list_names(const char *const *names, char *buf, size_t n) {
  buf[0] = '\0';
  for (int i = 0; names[i]; i++) {
    size_t used = strlen(buf);
    bprintf(buf + used, n - used, "%s%s", i ? ", " : "", names[i]);
  }
}

static int read_choice(const ctx *x, const node *t, const char *kp, const char *const *names,
                       int *out) {
  char valid[256], b[96];
  list_names(names, valid, sizeof valid);
  if (t->kind != NODE_SCALAR)
    return fail_at(x, t, kp, "expected one of: %s, got %s", valid, got(t, b, sizeof b));
  for (int i = 0; names[i]; i++)
    if (strcmp(t->text, names[i]) == 0) {
      *out = i;
      return 0;
    }
  return fail_at(x, t, kp, "unknown choice %s (valid: %s)", got(t, b, sizeof b), valid);
}

/* A list of exactly two numbers; `axis` ('x', 'y') also requires v0 < v1. */
static int read_pair(const ctx *x, const node *t, const char *kp, char axis, double out[2]) {
  char b[96];
  if (t->kind != NODE_LIST || t->n != 2)
    return fail_at(x, t, kp, "expected a list of 2 numbers, got %s", got(t, b, sizeof b));
  for (int i = 0; i < 2; i++) {
    char ik[KEYLEN];
    bprintf(ik, sizeof ik, "%s[%d]", kp, i);
    if (read_number(x, t->items[i], ik, &R_ANY, &out[i])) return -1;
  }
  if (axis && !(out[0] < out[1]))
    return fail_at(x, t, kp, "expected [%c0, %c1] with %c0 < %c1, got [%g, %g]", axis, axis, axis,
                   axis, out[0], out[1]);
  return 0;
}

/* ---- mapping access ------------------------------------------------------- */

/* Unknown keys of mapping m (at dotted path `path`) are errors. */
static int check_keys(const ctx *x, const node *m, const char *path, const char *const *valid) {
  for (size_t i = 0; i < m->n; i++) {
    const entry *e = &m->entries[i];
    int known = 0;
    for (int j = 0; valid[j] && !known; j++)
      known = strcmp(e->key, valid[j]) == 0;
    if (known) continue;
    char list[512], kp[KEYLEN];
    list_names(valid, list, sizeof list);
    join(kp, sizeof kp, path, e->key);
    if (*path)
      return fail(x, e->src, e->line, kp, "unknown key (valid keys in '%s': %s)", path, list);
    return fail(x, e->src, e->line, kp, "unknown key (valid top-level keys: %s)", list);
  }
  return 0;
}

/* The value of `key` in m: 1 found, 0 absent (optional), -1 missing (required). */
static int lookup(const ctx *x, const node *m, const char *path, const char *key, int required,
                  const node **out, char kp[KEYLEN]) {
  const entry *e = find(m, key);
  join(kp, KEYLEN, path, key);
  *out = e ? e->val : NULL;
  if (e) return 1;
  if (!required) return 0;
  return fail(x, m->src, m->line, kp, "required key is missing");
}

static int get_number(const ctx *x, const node *m, const char *path, const char *key, int required,
                      const range *r, double *out) {
  const node *t;
  char kp[KEYLEN];
  int rc = lookup(x, m, path, key, required, &t, kp);
  if (rc <= 0) return rc;
  return read_number(x, t, kp, r, out) ? -1 : 1;
}

static int get_int(const ctx *x, const node *m, const char *path, const char *key, long lo, long hi,
                   int *out) {
  const node *t;
  char kp[KEYLEN];
  int rc = lookup(x, m, path, key, 0, &t, kp);
  if (rc <= 0) return rc;
  return read_int(x, t, kp, lo, hi, out) ? -1 : 1;
}

static int get_bool(const ctx *x, const node *m, const char *path, const char *key, int *out) {
  const node *t;
  char kp[KEYLEN];
  int rc = lookup(x, m, path, key, 0, &t, kp);
  if (rc <= 0) return rc;
  return read_bool(x, t, kp, out) ? -1 : 1;
}

static int get_choice(const ctx *x, const node *m, const char *path, const char *key,
                      const char *const *names, int *out) {
  const node *t;
  char kp[KEYLEN];
  int rc = lookup(x, m, path, key, 0, &t, kp);
  if (rc <= 0) return rc;
  return read_choice(x, t, kp, names, out) ? -1 : 1;
}

static int get_pair(const ctx *x, const node *m, const char *path, const char *key, int required,
                    char axis, double out[2]) {
  const node *t;
  char kp[KEYLEN];
  int rc = lookup(x, m, path, key, required, &t, kp);
  if (rc <= 0) return rc;
  return read_pair(x, t, kp, axis, out) ? -1 : 1;
}

/* A mapping-valued key whose own keys are all in `valid`. */
static int get_section(const ctx *x, const node *m, const char *path, const char *key, int required,
                       const char *const *valid, const node **out) {
  char kp[KEYLEN], b[96];
  int rc = lookup(x, m, path, key, required, out, kp);
  if (rc <= 0) return rc;
  if ((*out)->kind != NODE_MAP)
    return fail_at(x, *out, kp, "expected a mapping, got %s", got(*out, b, sizeof b));
  return check_keys(x, *out, kp, valid) ? -1 : 1;
}

static int get_string(const ctx *x, const node *m, const char *key, int required, char **out) {
  const node *t;
  char kp[KEYLEN], b[96];
  int rc = lookup(x, m, "", key, required, &t, kp);
  if (rc <= 0) return rc;
  if (t->kind != NODE_SCALAR)
    return fail_at(x, t, kp, "expected a string, got %s", got(t, b, sizeof b));
  free(*out);
  *out = dup_n(t->text, strlen(t->text));
  return *out ? 1 : oom(x);
}

/* ---- the schema ----------------------------------------------------------- */

static const char *const top_keys[] = {"name",     "description",  "physics", "numerics", "time",
                                       "geometry", "free_surface", "output",  NULL};
static const char *const fs_keys[] = {"radius_factor", "h_factor", NULL};
static const char *const laminar_keys[] = {"model", "mu", "gradient_correction", NULL};
static const char *const physics_keys[] = {
    "rho0",      "gravity",    "body_force", "sound_speed", "artificial_viscosity",
    "viscosity", "turbulence", "repulsion",  "xsph",        NULL};
static const char *const c0_keys[] = {"factor", "height", "speed", NULL};
static const char *const visc_keys[] = {"alpha", "beta", "eta", NULL};
static const char *const numerics_keys[] = {
    "dx",        "h_factor",       "kernel",        "integrator",        "smoothing_length",
    "time_step", "density_filter", "density_limit", "density_diffusion", "shifting",
    NULL};
static const char *const dt_keys[] = {"rule", "factor", "dt", NULL};
static const char *const filter_keys[] = {"kind", "every", NULL};
static const char *const diffusion_keys[] = {"model", "delta", NULL};
static const char *const shifting_keys[] = {"coefficient", NULL};
static const char *const time_keys[] = {"end", "output_interval", "output_times", "stop", NULL};
static const char *const geometry_keys[] = {"tank", "fluid", "walls", "periodic_x", "domain", NULL};
static const char *const tank_keys[] = {
    "x", "y", "layers", "boundary", "stagger", "extrapolated_velocity", "free_slip", NULL};
static const char *const fluid_keys[] = {"x",       "y",      "velocity", "hydrostatic",
                                         "surface", "jitter", "seed",     NULL};
static const char *const wall_keys[] = {
    "from",      "to", "layers", "boundary", "motion", "stagger", "extrapolated_velocity",
    "free_slip", NULL};
static const char *const motion_keys[] = {"type",   "velocity", "start",       "stop",
                                          "period", "stroke",   "wave_height", "depth",
                                          "ramp",   "hinge",    NULL};
static const char *const motion_names[] = {"none", "translate", "piston", "flap", NULL};
static const char *const turbulence_keys[] = {"model", "cs", "ci", NULL};
static const char *const turbulence_names[] = {"none", "sps", NULL};
static const char *const h_names[] = {"constant", "variable", NULL};
static const char *const domain_keys[] = {"x", "y", NULL};
static const char *const output_keys[] = {"snapshots", "free_surface",   "energy", "gauges",
                                          "probes",    "probe_interval", NULL};
static const char *const probe_keys[] = {"name", "kind", "at", "x", "diameter", "along", NULL};
static const char *const probe_kind_names[] = {"pressure", "level", "velocity", NULL};
static const char *const along_names[] = {"y", "x", NULL};

const char *sph_probe_kind_name(sph_probe_kind k) { return choice_name(probe_kind_names, (int)k); }

static void set_defaults(sph_case *c) {
  c->rho0 = 1000.0;
  c->gravity[0] = 0.0;
  c->gravity[1] = -9.81;
  c->alpha = 0.0;
  c->beta = 0.0;
  c->eta = 0.1;
  c->xsph = 0.0;
  c->h_factor = 1.3;
  c->kernel = SPH_KERNEL_CUBIC_SPLINE;
  c->integrator = SPH_INTEGRATOR_PREDICTOR_CORRECTOR;
  c->dt_rule = SPH_DT_PAPER_B;
  c->dt_factor = 0.3;
  c->dt_fixed = 0.0;
  c->density_limit = 0.3;
  c->stop = SPH_STOP_NONE;
  c->snapshots = 1;
  c->viscosity = SPH_VISCOSITY_NONE;
  c->fs_radius_factor = 1.0;
  c->density_filter = SPH_FILTER_NONE;
  c->filter_every = 30;
  c->diffusion = SPH_DIFFUSION_NONE;
  c->diffusion_delta = SPH_DIFFUSION_DELTA_DEFAULT;
  c->shifting_coefficient = SPH_SHIFTING_COEFFICIENT_DEFAULT;
  c->sps_cs = 0.12;
  c->sps_ci = 0.00066;
}

/* The required key `key` of m (under path) as a name: 1 to 64 characters
 * from [A-Za-z0-9_.-] (a case's name, a probe's); *out points into the
 * tree. */
static int read_plain_name(const ctx *x, const node *m, const char *path, const char *key,
                           const char **out) {
  const node *t;
  char kp[KEYLEN], b[96];
  if (lookup(x, m, path, key, 1, &t, kp) < 0) return -1;
  const char *s = t->kind == NODE_SCALAR ? t->text : "";
  const size_t n = strlen(s);
  if (n < 1 || n > 64 ||
      strspn(s, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_.-") != n)
    return fail_at(x, t, kp, "expected a name of 1 to 64 characters from [A-Za-z0-9_.-], got %s",
                   got(t, b, sizeof b));
  *out = s;
  return 0;
}

static int read_name(const ctx *x, const node *root, sph_case *c) {
  const char *s;
  if (read_plain_name(x, root, "", "name", &s)) return -1;
  c->name = dup_n(s, strlen(s));
  return c->name ? 0 : oom(x);
}

/* c0 = value, or factor*sqrt(2 |g| height), or factor*speed. */
static int read_sound_speed(const ctx *x, const node *m, sph_case *c) {
  static const range what = {0, 0, '(', 0,
                             "a positive number or a mapping {factor, height} or {factor, speed}"};
  const char *kp = "physics.sound_speed";
  const node *t;
  char k[KEYLEN];
  double factor = 0, height = 0, speed = 0;
  if (lookup(x, m, "physics", "sound_speed", 1, &t, k) < 0) return -1;
  if (t->kind != NODE_MAP) return read_number(x, t, kp, &what, &c->sound_speed);
  if (check_keys(x, t, kp, c0_keys)) return -1;
  if (get_number(x, t, kp, "factor", 1, &R_POS, &factor) < 0) return -1;
  int has_h = get_number(x, t, kp, "height", 0, &R_POS, &height);
  if (has_h < 0) return -1;
  int has_s = get_number(x, t, kp, "speed", 0, &R_POS, &speed);
  if (has_s < 0) return -1;
  if (has_h && has_s) return fail_at(x, t, kp, "give either 'height' or 'speed', not both");
  if (!has_h && !has_s)
    return fail_at(x, t, kp,
                   "expected 'height' (c0 = factor*sqrt(2|g|*height)) or 'speed' "
                   "(c0 = factor*speed) next to 'factor'");
  if (has_s) {
    c->sound_speed = factor * speed;
  } else {
    double g = sqrt(c->gravity[0] * c->gravity[0] + c->gravity[1] * c->gravity[1]);
    if (g == 0)
      return fail_at(x, find(t, "height")->val, "physics.sound_speed.height",
                     "c0 = factor*sqrt(2|g|*height) needs a non-zero physics.gravity");
    c->sound_speed = factor * sqrt(2.0 * g * height);
  }
  if (!isfinite(c->sound_speed))
    return fail_at(x, t, kp, "the resulting c0 = %g*%g is not finite", factor,
                   has_s ? speed : height);
  return 0;
}

static int read_physics(const ctx *x, const node *m, sph_case *c) {
  const char *p = "physics";
  const node *v;
  if (get_number(x, m, p, "rho0", 0, &R_POS, &c->rho0) < 0) return -1;
  int has_g = get_pair(x, m, p, "gravity", 0, 0, c->gravity);
  if (has_g < 0) return -1;
  const node *bf;
  char kp[KEYLEN];
  if (lookup(x, m, p, "body_force", 0, &bf, kp) > 0) {
    if (has_g)
      return fail_at(x, bf, kp, "give either physics.gravity or physics.body_force, not both");
    if (read_pair(x, bf, kp, 0, c->gravity)) return -1;
  }
  if (read_sound_speed(x, m, c)) return -1;
  int rc = get_section(x, m, p, "viscosity", 0, laminar_keys, &v);
  if (rc < 0) return -1;
  if (rc > 0) {
    const char *vp = "physics.viscosity";
    int model = (int)SPH_VISCOSITY_NONE;
    if (get_choice(x, v, vp, "model", viscosity_names, &model) < 0) return -1;
    c->viscosity = (sph_viscosity_kind)model;
    int has_mu = get_number(x, v, vp, "mu", c->viscosity != SPH_VISCOSITY_NONE, &R_POS, &c->mu);
    if (has_mu < 0) return -1;
    if (has_mu && c->viscosity == SPH_VISCOSITY_NONE)
      return fail_at(x, find(v, "mu")->val, "physics.viscosity.mu",
                     "only used with a viscosity model (model is 'none')");
    int has_gc = get_bool(x, v, vp, "gradient_correction", &c->gradient_correction);
    if (has_gc < 0) return -1;
    if (has_gc && c->gradient_correction && c->viscosity != SPH_VISCOSITY_STRESS_TENSOR)
      return fail_at(x, find(v, "gradient_correction")->val,
                     "physics.viscosity.gradient_correction",
                     "corrects the stress-tensor viscosity: needs model 'stress_tensor', got '%s'",
                     sph_viscosity_name(c->viscosity));
  }
  rc = get_section(x, m, p, "turbulence", 0, turbulence_keys, &v);
  if (rc < 0) return -1;
  if (rc > 0) {
    const char *tp = "physics.turbulence";
    if (get_choice(x, v, tp, "model", turbulence_names, &c->sps) < 0 ||
        get_number(x, v, tp, "cs", 0, &R_POS, &c->sps_cs) < 0 ||
        get_number(x, v, tp, "ci", 0, &R_NONNEG, &c->sps_ci) < 0)
      return -1;
  }
  if (get_number(x, m, p, "repulsion", 0, &R_POS, &c->repulsion) < 0) return -1;
  rc = get_section(x, m, p, "artificial_viscosity", 0, visc_keys, &v);
  if (rc < 0) return -1;
  if (rc > 0) {
    const char *vp = "physics.artificial_viscosity";
    if (get_number(x, v, vp, "alpha", 0, &R_NONNEG, &c->alpha) < 0) return -1;
    if (get_number(x, v, vp, "beta", 0, &R_NONNEG, &c->beta) < 0) return -1;
    if (get_number(x, v, vp, "eta", 0, &R_POS, &c->eta) < 0) return -1;
  }
  return get_number(x, m, p, "xsph", 0, &R_UNIT, &c->xsph) < 0 ? -1 : 0;
}

static int read_time_step(const ctx *x, const node *m, sph_case *c) {
  static const range factor = {0, 1, '(', ']', NULL};
  const char *p = "numerics.time_step";
  const node *t, *dt;
  char kp[KEYLEN];
  int rule = (int)c->dt_rule;
  int rc = get_section(x, m, "numerics", "time_step", 0, dt_keys, &t);
  if (rc <= 0) return rc;
  if (get_choice(x, t, p, "rule", dt_rule_names, &rule) < 0) return -1;
  c->dt_rule = (sph_dt_rule)rule;
  if (get_number(x, t, p, "factor", 0, &factor, &c->dt_factor) < 0) return -1;
  if (c->dt_rule == SPH_DT_FIXED) {
    if (lookup(x, t, p, "dt", 0, &dt, kp) == 0)
      return fail_at(x, t, kp, "required key is missing (rule 'fixed' needs it)");
    return read_number(x, dt, kp, &R_POS, &c->dt_fixed);
  }
  if (lookup(x, t, p, "dt", 0, &dt, kp) > 0)
    return fail_at(x, dt, kp, "only allowed with rule: fixed (the rule is '%s')",
                   sph_dt_rule_name(c->dt_rule));
  return 0;
}

static int read_numerics(ctx *x, const node *m, sph_case *c) {
  static const range h_factor = {0.5, 4, '[', ']', NULL};
  static const range limit = {0, 1, '(', ')', NULL};
  const char *p = "numerics";
  const node *t;
  char kp[KEYLEN];
  int k = (int)c->kernel, in = (int)c->integrator;
  if (lookup(x, m, p, "dx", 1, &t, kp) < 0) return -1;
  if (read_number(x, t, kp, &R_POS, &c->dx)) return -1;
  x->dx_node = t;
  c->dx_line = t->src == FROM_FILE ? t->line : 0;
  if (get_number(x, m, p, "h_factor", 0, &h_factor, &c->h_factor) < 0) return -1;
  c->h = c->h_factor * c->dx;
  if (!isfinite(c->h)) return fail_at(x, t, kp, "h = h_factor*dx overflows");
  if (get_choice(x, m, p, "smoothing_length", h_names, &c->variable_h) < 0) return -1;
  if (get_choice(x, m, p, "kernel", kernel_names, &k) < 0) return -1;
  c->kernel = (sph_kernel_kind)k;
  if (get_choice(x, m, p, "integrator", integrator_names, &in) < 0) return -1;
  c->integrator = (sph_integrator_kind)in;
  if (read_time_step(x, m, c)) return -1;
  const node *f;
  int rc = get_section(x, m, p, "density_filter", 0, filter_keys, &f);
  if (rc < 0) return -1;
  if (rc > 0) {
    int kind = (int)c->density_filter;
    if (get_choice(x, f, "numerics.density_filter", "kind", sph_filter_kind_names, &kind) < 0 ||
        get_int(x, f, "numerics.density_filter", "every", 1, 1000000, &c->filter_every) < 0)
      return -1;
    c->density_filter = (sph_filter_kind)kind;
  }
  static const range delta = {0, 1, '(', ']', NULL};
  rc = get_section(x, m, p, "density_diffusion", 0, diffusion_keys, &f);
  if (rc < 0) return -1;
  if (rc > 0) {
    int model = (int)c->diffusion;
    if (get_choice(x, f, "numerics.density_diffusion", "model", sph_diffusion_kind_names, &model) <
            0 ||
        get_number(x, f, "numerics.density_diffusion", "delta", 0, &delta, &c->diffusion_delta) < 0)
      return -1;
    c->diffusion = (sph_diffusion_kind)model;
  }
  static const range shift = {0, 10, '(', ']', NULL};
  rc = get_section(x, m, p, "shifting", 0, shifting_keys, &f);
  if (rc < 0) return -1;
  if (rc > 0) {
    c->shifting = 1;
    x->shifting_node = find(m, "shifting")->val;
    if (get_number(x, f, "numerics.shifting", "coefficient", 0, &shift, &c->shifting_coefficient) <
        0)
      return -1;
  }
  return get_number(x, m, p, "density_limit", 0, &limit, &c->density_limit) < 0 ? -1 : 0;
}

static int read_time(ctx *x, const node *m, sph_case *c) {
  const char *p = "time";
  const node *t;
  char kp[KEYLEN], what[96];
  int stop = (int)c->stop;
  if (get_number(x, m, p, "end", 1, &R_POS, &c->t_end) < 0) return -1;
  /* at most SPH_MAX_OUTPUTS output times from the interval: a tiny one
   * would fill the disk with snapshots (issue 21, D7) */
  const double least = c->t_end / SPH_MAX_OUTPUTS;
  bprintf(what, sizeof what, "a number from time.end/%d (%g, at most %d outputs) to time.end (%g)",
          SPH_MAX_OUTPUTS, least, SPH_MAX_OUTPUTS, c->t_end);
  range interval = {least, c->t_end, '[', ']', what};
  const node *ot;
  int has_times = lookup(x, m, p, "output_times", 0, &ot, kp);
  if (get_number(x, m, p, "output_interval", !has_times, &interval, &c->output_interval) < 0)
    return -1;
  if (has_times) {
    char b[96];
    if (ot->kind != NODE_LIST || ot->n == 0)
      return fail_at(x, ot, kp, "expected a non-empty list of increasing times, got %s",
                     got(ot, b, sizeof b));
    if (!(c->output_times = calloc(ot->n, sizeof *c->output_times))) return oom(x);
    c->n_output_times = ot->n;
    for (size_t i = 0; i < ot->n; i++) {
      char ik[KEYLEN];
      bprintf(ik, sizeof ik, "time.output_times[%zu]", i);
      const double lo = i ? c->output_times[i - 1] : 0.0;
      char w2[96];
      bprintf(w2, sizeof w2, "a time > %g (increasing; times after time.end are not reached)", lo);
      range r = {lo, 0, '(', 0, w2};
      if (read_number(x, ot->items[i], ik, &r, &c->output_times[i])) return -1;
    }
  }
  int rc = lookup(x, m, p, "stop", 0, &t, kp);
  if (rc > 0) {
    if (read_choice(x, t, kp, stop_names, &stop)) return -1;
    x->stop_node = t;
  }
  c->stop = (sph_stop_kind)stop;
  return 0;
}

/* Repulsive walls are one layer (paper A §6 a) and mirror walls have no
 * particles: `layers` is fixed for them and an error if given otherwise. */
static int check_layers(const ctx *x, const node *m, const char *p, sph_boundary_kind b,
                        int *layers) {
  const node *t;
  char kp[KEYLEN];
  int given = lookup(x, m, p, "layers", 0, &t, kp);
  if (b == SPH_BOUNDARY_REPULSIVE) {
    if (given && *layers != 1)
      return fail_at(x, t, kp, "repulsive walls have exactly 1 layer, got %d", *layers);
    *layers = 1;
  } else if (b == SPH_BOUNDARY_MIRROR) {
    if (given) return fail_at(x, t, kp, "mirror walls have no particle layers: remove the key");
    *layers = 0;
  }
  return 0;
}

/* The layers of a wall by default: 2 staggered layers dx/2 apart for the
 * dynamic models; for mdbc, whose wall density continues the fluid's
 * field, 3 layers on the fluid's lattice continued (they fill the support
 * 2h = 2.6 dx; in still water the floor particles then carry their
 * hydrostatic load within 3 %, against 42-53 % under it with 2 staggered
 * layers). */
static int default_layers(sph_boundary_kind b) { return b == SPH_BOUNDARY_MDBC ? 3 : 2; }
static int default_stagger(sph_boundary_kind b) { return b != SPH_BOUNDARY_MDBC; }

/* `stagger`, `extrapolated_velocity` and `free_slip` of a wall of
 * particles with a density (dynamic, fixed_layers, mdbc); an error on the
 * others, and the extrapolated velocity only where a strain-rate pass uses
 * it. */
static int read_layout(const ctx *x, const node *m, const char *p, const sph_case *c,
                       sph_boundary_kind b, int *stagger, int *extrapolated, int *free_slip) {
  const node *t;
  char kp[KEYLEN];
  const int evolving =
      b == SPH_BOUNDARY_DYNAMIC || b == SPH_BOUNDARY_FIXED_LAYERS || b == SPH_BOUNDARY_MDBC;
  static const char *const keys[] = {"stagger", "extrapolated_velocity", "free_slip"};
  for (int k = 0; k < 3; k++)
    if (!evolving && lookup(x, m, p, keys[k], 0, &t, kp) > 0)
      return fail_at(x, t, kp,
                     "only for 'dynamic', 'fixed_layers' and 'mdbc' walls (this one is '%s')",
                     sph_boundary_name(b));
  if (get_bool(x, m, p, "stagger", stagger) < 0) return -1;
  if (get_bool(x, m, p, "free_slip", free_slip) < 0) return -1;
  int rc = get_bool(x, m, p, "extrapolated_velocity", extrapolated);
  if (rc < 0) return -1;
  if (rc > 0 && *extrapolated && c->viscosity != SPH_VISCOSITY_STRESS_TENSOR && !c->sps) {
    lookup(x, m, p, "extrapolated_velocity", 0, &t, kp);
    return fail_at(x, t, kp,
                   "acts in the strain-rate pass: needs physics.viscosity.model 'stress_tensor' "
                   "or physics.turbulence (viscosity model is '%s')",
                   sph_viscosity_name(c->viscosity));
  }
  return 0;
}

static int read_tank(const ctx *x, const node *m, sph_case *c) {
  const char *p = "geometry.tank";
  const node *t;
  double v[2];
  int b = (int)SPH_BOUNDARY_DYNAMIC;
  int rc = get_section(x, m, "geometry", "tank", 0, tank_keys, &t);
  if (rc <= 0) return rc;
  c->tank.present = 1;
  if (get_pair(x, t, p, "x", 1, 'x', v) < 0) return -1;
  c->tank.x0 = v[0];
  c->tank.x1 = v[1];
  if (get_pair(x, t, p, "y", 1, 'y', v) < 0) return -1;
  c->tank.y0 = v[0];
  c->tank.y1 = v[1];
  if (get_choice(x, t, p, "boundary", boundary_names, &b) < 0) return -1;
  c->tank.boundary = (sph_boundary_kind)b;
  c->tank.layers = default_layers(c->tank.boundary);
  if (get_int(x, t, p, "layers", 1, 8, &c->tank.layers) < 0) return -1;
  c->tank.stagger = default_stagger(c->tank.boundary);
  if (read_layout(x, t, p, c, c->tank.boundary, &c->tank.stagger, &c->tank.extrapolated,
                  &c->tank.free_slip))
    return -1;
  return check_layers(x, t, p, c->tank.boundary, &c->tank.layers);
}

/* The block must be wider and taller than dx, and inside the tank if any. */
static int check_block(const ctx *x, const node *m, const char *p, const sph_case *c,
                       const sph_fluid_block *f) {
  double w = f->x1 - f->x0, h = f->y1 - f->y0;
  const sph_tank *k = &c->tank;
  char kp[KEYLEN], b[96];
  if (!(c->dx < w && c->dx < h))
    return fail_at(x, x->dx_node, "numerics.dx",
                   "expected a positive number smaller than the width (%g) and height (%g) of "
                   "%s, got %s",
                   w, h, p, got(x->dx_node, b, sizeof b));
  if (k->present && (f->x0 < k->x0 || f->x1 > k->x1)) {
    join(kp, sizeof kp, p, "x");
    return fail_at(x, find(m, "x")->val, kp,
                   "expected a range inside the tank's inner box [%g, %g], got [%g, %g]", k->x0,
                   k->x1, f->x0, f->x1);
  }
  if (k->present && (f->y0 < k->y0 || f->y1 > k->y1)) {
    join(kp, sizeof kp, p, "y");
    return fail_at(x, find(m, "y")->val, kp,
                   "expected a range inside the tank's inner box [%g, %g], got [%g, %g]", k->y0,
                   k->y1, f->y0, f->y1);
  }
  return 0;
}

static int read_block(const ctx *x, const node *m, const char *p, const sph_case *c,
                      sph_fluid_block *f) {
  char what[96], b[96];
  double v[2] = {0, 0};
  if (m->kind != NODE_MAP)
    return fail_at(x, m, p, "expected a mapping, got %s", got(m, b, sizeof b));
  if (check_keys(x, m, p, fluid_keys)) return -1;
  if (get_pair(x, m, p, "x", 1, 'x', v) < 0) return -1;
  f->x0 = v[0];
  f->x1 = v[1];
  if (get_pair(x, m, p, "y", 1, 'y', v) < 0) return -1;
  f->y0 = v[0];
  f->y1 = v[1];
  v[0] = v[1] = 0;
  if (get_pair(x, m, p, "velocity", 0, 0, v) < 0) return -1;
  f->vx = v[0];
  f->vy = v[1];
  f->hydrostatic = 1;
  if (get_bool(x, m, p, "hydrostatic", &f->hydrostatic) < 0) return -1;
  f->surface = f->y1;
  bprintf(what, sizeof what, "a number >= the block's y1 (%g)", f->y1);
  range surface = {f->y1, 0, '[', 0, what};
  if (get_number(x, m, p, "surface", 0, &surface, &f->surface) < 0) return -1;
  static const range jitter = {0, 0.5, '[', ')', NULL};
  const int has_jitter = get_number(x, m, p, "jitter", 0, &jitter, &f->jitter);
  if (has_jitter < 0) return -1;
  f->seed = 1;
  const int has_seed = get_int(x, m, p, "seed", 0, 2147483647L, &f->seed);
  if (has_seed < 0) return -1;
  if (has_seed && !has_jitter) {
    char kp[KEYLEN];
    join(kp, sizeof kp, p, "seed");
    return fail_at(x, find(m, "seed")->val, kp, "expected no seed without %s.jitter, got %s", p,
                   got(find(m, "seed")->val, b, sizeof b));
  }
  return check_block(x, m, p, c, f);
}

static int read_fluid(const ctx *x, const node *m, sph_case *c) {
  const node *t;
  char kp[KEYLEN], b[96];
  if (lookup(x, m, "geometry", "fluid", 1, &t, kp) < 0) return -1;
  if (t->kind != NODE_LIST || t->n == 0)
    return fail_at(x, t, kp, "expected a non-empty list of mappings, got %s", got(t, b, sizeof b));
  if (!(c->fluid = calloc(t->n, sizeof *c->fluid))) return oom(x);
  c->n_fluid = t->n;
  for (size_t i = 0; i < t->n; i++) {
    bprintf(kp, sizeof kp, "geometry.fluid[%zu]", i);
    if (read_block(x, t->items[i], kp, c, &c->fluid[i])) return -1;
    /* blocks that overlap would put particles on top of one another: twice
     * the mass there (issue 21, D5) */
    const sph_fluid_block *a = &c->fluid[i];
    for (size_t k = 0; k < i; k++) {
      const sph_fluid_block *o = &c->fluid[k];
      const double w = fmin(a->x1, o->x1) - fmax(a->x0, o->x0);
      const double hh = fmin(a->y1, o->y1) - fmax(a->y0, o->y0);
      if (w > 1e-9 * c->dx && hh > 1e-9 * c->dx)
        return fail_at(x, t->items[i], kp,
                       "expected a block apart from geometry.fluid[%zu], got one that overlaps "
                       "it in [%g, %g] x [%g, %g] (their particles would coincide)",
                       k, fmax(a->x0, o->x0), fmin(a->x1, o->x1), fmax(a->y0, o->y0),
                       fmin(a->y1, o->y1));
    }
  }
  return 0;
}

/* A paddle: {type: piston|flap, period, stroke | wave_height, depth, ramp,
 * hinge}. With wave_height the stroke comes from the linear transfer
 * function (needs depth); the flap's hinge defaults to the wall's lower end
 * and its depth is required; the ramp defaults to one period. */
static int read_paddle(const ctx *x, const node *t, const char *kp, sph_wall_segment *w) {
  sph_paddle *pd = &w->motion.paddle;
  pd->kind = w->motion.kind == SPH_MOTION_FLAP ? SPH_PADDLE_FLAP : SPH_PADDLE_PISTON;
  if (get_number(x, t, kp, "period", 1, &R_POS, &pd->period) < 0) return -1;
  int has_d = get_number(x, t, kp, "depth", pd->kind == SPH_PADDLE_FLAP, &R_POS, &pd->depth);
  if (has_d < 0) return -1;
  int has_s = get_number(x, t, kp, "stroke", 0, &R_POS, &pd->stroke);
  if (has_s < 0) return -1;
  double H = 0.0;
  int has_h = get_number(x, t, kp, "wave_height", 0, &R_POS, &H);
  if (has_h < 0) return -1;
  if (has_s == has_h) return fail_at(x, t, kp, "expected exactly one of 'stroke' or 'wave_height'");
  if (has_h) {
    if (!has_d) return fail_at(x, t, kp, "'wave_height' needs 'depth' (for the transfer function)");
    sph_error e;
    if (sph_paddle_stroke(pd->kind, H, pd->period, pd->depth, 9.81, &pd->stroke, &e))
      return fail_at(x, t, kp, "%s", e.msg);
  }
  pd->ramp = pd->period;
  if (get_number(x, t, kp, "ramp", 0, &R_NONNEG, &pd->ramp) < 0) return -1;
  double hinge[2] = {w->y0 < w->y1 ? w->x0 : w->x1, w->y0 < w->y1 ? w->y0 : w->y1};
  if (get_pair(x, t, kp, "hinge", 0, 0, hinge) < 0) return -1;
  pd->hinge_x = hinge[0];
  pd->hinge_y = hinge[1];
  w->motion.start = 0.0;
  w->motion.stop = INFINITY;
  sph_error e;
  if (sph_paddle_check(pd, &e)) return fail_at(x, t, kp, "%s", e.msg);
  return 0;
}

/* walls[i].motion: {type: translate, velocity: [vx, vy], start: 0, stop: t} */
static int read_motion(const ctx *x, const node *m, const char *p, sph_wall_segment *w) {
  const node *t;
  char kp[KEYLEN];
  join(kp, sizeof kp, p, "motion");
  memset(&w->motion, 0, sizeof w->motion);
  w->motion.stop = INFINITY;
  int rc = get_section(x, m, p, "motion", 0, motion_keys, &t);
  if (rc <= 0) return rc;
  int kind = 0;
  const node *tt;
  char tk[KEYLEN];
  if (lookup(x, t, kp, "type", 1, &tt, tk) < 0 || read_choice(x, tt, tk, motion_names, &kind))
    return -1;
  w->motion.kind = (sph_motion_kind)kind;
  if (w->motion.kind == SPH_MOTION_NONE) {
    if (t->n > 1) return fail_at(x, t, kp, "type 'none' takes no other keys");
    return 0;
  }
  if (w->boundary == SPH_BOUNDARY_MIRROR)
    return fail_at(x, t, kp, "a mirror wall has no particles to move");
  if (w->motion.kind == SPH_MOTION_PISTON || w->motion.kind == SPH_MOTION_FLAP)
    return read_paddle(x, t, kp, w);
  double v[2];
  if (get_pair(x, t, kp, "velocity", 1, 0, v) < 0) return -1;
  w->motion.vx = v[0];
  w->motion.vy = v[1];
  if (get_number(x, t, kp, "start", 0, &R_NONNEG, &w->motion.start) < 0) return -1;
  char what[96];
  bprintf(what, sizeof what, "a number > start (%g)", w->motion.start);
  range after = {w->motion.start, 0, '(', 0, what};
  return get_number(x, t, kp, "stop", 0, &after, &w->motion.stop) < 0 ? -1 : 0;
}

static int read_wall(const ctx *x, const node *m, const char *p, const sph_case *c,
                     sph_wall_segment *w) {
  char b[96];
  double from[2], to[2];
  int bnd = (int)SPH_BOUNDARY_DYNAMIC;
  if (m->kind != NODE_MAP)
    return fail_at(x, m, p, "expected a mapping, got %s", got(m, b, sizeof b));
  if (check_keys(x, m, p, wall_keys)) return -1;
  if (get_pair(x, m, p, "from", 1, 0, from) < 0) return -1;
  if (get_pair(x, m, p, "to", 1, 0, to) < 0) return -1;
  if (from[0] == to[0] && from[1] == to[1]) {
    char kp[KEYLEN];
    join(kp, sizeof kp, p, "to");
    return fail_at(x, find(m, "to")->val, kp,
                   "expected a point different from 'from', got [%g, %g]", to[0], to[1]);
  }
  w->x0 = from[0];
  w->y0 = from[1];
  w->x1 = to[0];
  w->y1 = to[1];
  if (get_choice(x, m, p, "boundary", boundary_names, &bnd) < 0) return -1;
  w->boundary = (sph_boundary_kind)bnd;
  w->layers = default_layers(w->boundary);
  if (get_int(x, m, p, "layers", 1, 8, &w->layers) < 0) return -1;
  if (check_layers(x, m, p, w->boundary, &w->layers)) return -1;
  w->stagger = default_stagger(w->boundary);
  if (read_layout(x, m, p, c, w->boundary, &w->stagger, &w->extrapolated, &w->free_slip)) return -1;
  if (read_motion(x, m, p, w)) return -1;
  if ((w->extrapolated || w->free_slip) && w->motion.kind == SPH_MOTION_FLAP) {
    const node *t;
    char kp[KEYLEN];
    const char *key = w->extrapolated ? "extrapolated_velocity" : "free_slip";
    lookup(x, m, p, key, 0, &t, kp);
    return fail_at(x, t, kp,
                   "not on a turning wall (motion type 'flap'): its mirror points and "
                   "normals would turn with it");
  }
  return 0;
}

static int read_walls(const ctx *x, const node *m, sph_case *c) {
  const node *t;
  char kp[KEYLEN], b[96];
  int rc = lookup(x, m, "geometry", "walls", 0, &t, kp);
  if (rc <= 0) return rc;
  if (t->kind != NODE_LIST)
    return fail_at(x, t, kp, "expected a list of mappings, got %s", got(t, b, sizeof b));
  if (t->n == 0) return 0;
  if (!(c->walls = calloc(t->n, sizeof *c->walls))) return oom(x);
  c->n_walls = t->n;
  for (size_t i = 0; i < t->n; i++) {
    bprintf(kp, sizeof kp, "geometry.walls[%zu]", i);
    if (read_wall(x, t->items[i], kp, c, &c->walls[i])) return -1;
  }
  return 0;
}

static int read_geometry(const ctx *x, const node *m, sph_case *c) {
  const node *d;
  if (read_tank(x, m, c) || read_fluid(x, m, c) || read_walls(x, m, c)) return -1;
  int pr = get_pair(x, m, "geometry", "periodic_x", 0, 'x', c->periodic_x);
  if (pr < 0) return -1;
  c->periodic = pr > 0;
  if (c->periodic && c->tank.present)
    return fail_at(x, find(m, "periodic_x")->val, "geometry.periodic_x",
                   "a periodic domain cannot have a tank (use geometry.walls for the bed)");
  if (c->periodic && !(c->periodic_x[1] - c->periodic_x[0] >= 6.0 * c->h))
    return fail_at(x, find(m, "periodic_x")->val, "geometry.periodic_x",
                   "expected a period of at least 6 h = %g m, got %g", 6.0 * c->h,
                   c->periodic_x[1] - c->periodic_x[0]);
  int rc = get_section(x, m, "geometry", "domain", 0, domain_keys, &d);
  if (rc <= 0) return rc;
  c->domain_set = 1;
  if (get_pair(x, d, "geometry.domain", "x", 1, 'x', &c->domain[0]) < 0) return -1;
  return get_pair(x, d, "geometry.domain", "y", 1, 'y', &c->domain[2]) < 0 ? -1 : 0;
}

/* The particles the geometry makes at dx, from above, in floating point (a
 * tiny dx gives a huge or infinite count, never an overflow): the fluid
 * blocks' lattices, and for the tank and each wall segment a row of
 * particles dx apart per layer along its length, plus the corners. */
static void estimate_particles(sph_case *c) {
  const double dx = c->dx;
  double fluid = 0.0, wall = 0.0;
  for (size_t b = 0; b < c->n_fluid; b++) {
    const sph_fluid_block *f = &c->fluid[b];
    fluid += floor((f->x1 - f->x0) / dx + 1e-9) * floor((f->y1 - f->y0) / dx + 1e-9);
  }
  if (c->tank.present) {
    const sph_tank *k = &c->tank;
    const double per_layer = (k->x1 - k->x0 + 2.0 * (k->y1 - k->y0)) / dx + 8.0 * k->layers;
    wall += k->layers * per_layer;
  }
  for (size_t i = 0; i < c->n_walls; i++) {
    const sph_wall_segment *w = &c->walls[i];
    const double len = hypot(w->x1 - w->x0, w->y1 - w->y0);
    wall += w->layers * (len / dx + 2.0);
  }
  int mirror = c->tank.present && c->tank.boundary == SPH_BOUNDARY_MIRROR;
  for (size_t i = 0; i < c->n_walls; i++)
    mirror |= c->walls[i].boundary == SPH_BOUNDARY_MIRROR;
  c->est_fluid = fluid;
  c->est_wall = wall + (mirror ? fluid : 0.0); /* mirror images of the fluid, at most */
}

double sph_case_default_max(void) {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  double bytes = pages > 0 && page > 0 ? (double)pages * (double)page : 4e9;
  const double max = 0.5 * bytes / SPH_BYTES_PER_PARTICLE;
  return max < SPH_MAX_PARTICLES_HARD ? max : SPH_MAX_PARTICLES_HARD;
}

int sph_case_check_size(const sph_case *c, double max, sph_error *err) {
  const int given = max > 0.0;
  if (!given) max = sph_case_default_max();
  if (max > SPH_MAX_PARTICLES_HARD) max = SPH_MAX_PARTICLES_HARD;
  const double n = c->est_fluid + c->est_wall;
  if (n <= max) return 0;
  char where[4200];
  if (c->dx_line)
    snprintf(where, sizeof where, "%s:%zu: numerics.dx", c->path ? c->path : "", c->dx_line);
  else
    snprintf(where, sizeof where, "--set numerics.dx");
  return sph_error_set(err,
                       "%s: %g makes about %.3g particles (fluid %.3g, walls %.3g), about %.3g "
                       "GB; the bound is %.0f particles (%s; sph run --max-particles N changes "
                       "it): expected a larger dx",
                       where, c->dx, n, c->est_fluid, c->est_wall, n * SPH_BYTES_PER_PARTICLE / 1e9,
                       max,
                       max >= SPH_MAX_PARTICLES_HARD ? "what 32-bit indices reach"
                       : given                       ? "the bound asked for"
                                                     : "half this machine's memory");
}

/* One entry of output.probes (p its key, output.probes[i]). */
static int read_probe(const ctx *x, const node *m, const char *p, sph_probe *pr) {
  const node *t;
  char kp[KEYLEN], b[96];
  if (m->kind != NODE_MAP)
    return fail_at(x, m, p, "expected a mapping, got %s", got(m, b, sizeof b));
  if (check_keys(x, m, p, probe_keys)) return -1;
  const char *s;
  if (read_plain_name(x, m, p, "name", &s)) return -1;
  memcpy(pr->name, s, strlen(s) + 1);
  int kind = -1;
  if (lookup(x, m, p, "kind", 1, &t, kp) < 0 || read_choice(x, t, kp, probe_kind_names, &kind))
    return -1;
  pr->kind = (sph_probe_kind)kind;
  const int level = pr->kind == SPH_PROBE_LEVEL, pressure = pr->kind == SPH_PROBE_PRESSURE;
  /* the keys each kind takes */
  static const char *const only[] = {"at", "x", "diameter", "along"};
  const int allowed[3][4] = {{1, 0, 1, 1}, {0, 1, 0, 0}, {1, 0, 0, 0}};
  for (int k = 0; k < 4; k++)
    if (!allowed[kind][k] && lookup(x, m, p, only[k], 0, &t, kp) > 0)
      return fail_at(x, t, kp, "not a key of a %s probe", probe_kind_names[kind]);
  if (level) {
    if (get_number(x, m, p, "x", 1, &R_ANY, &pr->x) < 0) return -1;
    return 0;
  }
  double v[2] = {0, 0};
  if (get_pair(x, m, p, "at", 1, 0, v) < 0) return -1;
  pr->x = v[0];
  pr->y = v[1];
  if (pressure) {
    static const range dia = {0, 0, '[', 0, NULL};
    int along = 0;
    if (get_number(x, m, p, "diameter", 0, &dia, &pr->diameter) < 0 ||
        get_choice(x, m, p, "along", along_names, &along) < 0)
      return -1;
    pr->along_x = along;
  }
  return 0;
}

/* output.probes and output.probe_interval. */
static int read_probes(const ctx *x, const node *s, sph_case *c) {
  const node *t;
  char kp[KEYLEN], b[96];
  if (lookup(x, s, "output", "probes", 0, &t, kp) <= 0) {
    if (lookup(x, s, "output", "probe_interval", 0, &t, kp) > 0)
      return fail_at(x, t, kp, "expected output.probes alongside it");
    return 0;
  }
  if (t->kind != NODE_LIST || t->n == 0)
    return fail_at(x, t, kp, "expected a non-empty list of probes, got %s", got(t, b, sizeof b));
  if (t->n > 1000) return fail_at(x, t, kp, "expected at most 1000 probes, got %zu", t->n);
  if (!(c->probes = calloc(t->n, sizeof *c->probes))) return oom(x);
  c->n_probes = t->n;
  for (size_t i = 0; i < t->n; i++) {
    bprintf(kp, sizeof kp, "output.probes[%zu]", i);
    if (read_probe(x, t->items[i], kp, &c->probes[i])) return -1;
    for (size_t k = 0; k < i; k++)
      if (strcmp(c->probes[k].name, c->probes[i].name) == 0) {
        char nk[KEYLEN];
        bprintf(nk, sizeof nk, "%s.name", kp);
        return fail_at(x, find(t->items[i], "name")->val, nk,
                       "expected a name of its own, got '%s' (the name of output.probes[%zu])",
                       c->probes[i].name, k);
      }
  }
  char what[128];
  bprintf(what, sizeof what, "a number from 0 (every step) to time.end (%g)", c->t_end);
  const range iv = {0, c->t_end, '[', ']', what};
  return get_number(x, s, "output", "probe_interval", 0, &iv, &c->probe_interval) < 0 ? -1 : 0;
}

/* Reads every section of the (overridden) tree into c, in schema order. */
static int read_case(ctx *x, const node *root, sph_case *c) {
  const node *s;
  if (check_keys(x, root, "", top_keys) || read_name(x, root, c)) return -1;
  if (get_string(x, root, "description", 0, &c->description) < 0) return -1;
  if (c->description && strlen(c->description) > MAX_DESCRIPTION)
    return fail_at(x, find(root, "description")->val, "description",
                   "expected at most %d characters (it is stored in every snapshot), got %zu",
                   MAX_DESCRIPTION, strlen(c->description));
  if (get_section(x, root, "", "physics", 1, physics_keys, &s) < 0 || read_physics(x, s, c))
    return -1;
  if (get_section(x, root, "", "numerics", 1, numerics_keys, &s) < 0 || read_numerics(x, s, c))
    return -1;
  if (get_section(x, root, "", "time", 1, time_keys, &s) < 0 || read_time(x, s, c)) return -1;
  if (get_section(x, root, "", "geometry", 1, geometry_keys, &s) < 0 || read_geometry(x, s, c))
    return -1;
  if (c->repulsion == 0.0) { /* D = 5 |g| H, paper A eq. (22), H the deepest block */
    double H = 0.0;
    for (size_t i = 0; i < c->n_fluid; i++)
      if (c->fluid[i].surface - c->fluid[i].y0 > H) H = c->fluid[i].surface - c->fluid[i].y0;
    c->repulsion = 5.0 * sqrt(c->gravity[0] * c->gravity[0] + c->gravity[1] * c->gravity[1]) * H;
  }
  if (c->shifting && c->variable_h)
    return fail_at(x, x->shifting_node, "numerics.shifting",
                   "cannot be combined with numerics.smoothing_length: variable");
  if (c->shifting && sph_case_has_boundary(c, SPH_BOUNDARY_MIRROR))
    return fail_at(x, x->shifting_node, "numerics.shifting",
                   "needs wall particles to count the wall as full, and mirror walls have none "
                   "(use boundary: mdbc)");
  if (c->stop == SPH_STOP_FRONT_AT_WALL && !c->tank.present)
    return fail_at(x, x->stop_node, "time.stop", "'front_at_wall' needs a geometry.tank");
  int rc = get_section(x, root, "", "free_surface", 0, fs_keys, &s);
  if (rc < 0) return -1;
  if (rc > 0) {
    static const range rf = {0.5, 1.0, '[', ']', NULL};
    static const range hf = {1.0, 4.0, '[', ']', NULL};
    if (get_number(x, s, "free_surface", "radius_factor", 0, &rf, &c->fs_radius_factor) < 0 ||
        get_number(x, s, "free_surface", "h_factor", 0, &hf, &c->fs_h_factor) < 0)
      return -1;
  }
  if (c->variable_h && c->fs_h_factor > 0.0)
    return fail(x, FROM_FILE, 0, "free_surface.h_factor",
                "cannot be combined with numerics.smoothing_length: variable");
  if (c->periodic && c->fs_h_factor > 1.0 &&
      !(c->periodic_x[1] - c->periodic_x[0] >= 6.0 * c->fs_h_factor * c->h))
    return fail(x, FROM_FILE, 0, "geometry.periodic_x",
                "expected a period of at least 6 k h = %g m with free_surface.h_factor k = %g, "
                "got %g",
                6.0 * c->fs_h_factor * c->h, c->fs_h_factor, c->periodic_x[1] - c->periodic_x[0]);
  rc = get_section(x, root, "", "output", 0, output_keys, &s);
  if (rc > 0) rc = get_bool(x, s, "output", "snapshots", &c->snapshots);
  if (rc >= 0 && s) rc = get_bool(x, s, "output", "free_surface", &c->output_free_surface);
  if (rc >= 0 && s) rc = get_bool(x, s, "output", "energy", &c->energy);
  const node *gl;
  char gk[KEYLEN];
  if (rc >= 0 && s && lookup(x, s, "output", "gauges", 0, &gl, gk) > 0) {
    char b[96];
    if (gl->kind != NODE_LIST || gl->n == 0)
      return fail_at(x, gl, gk, "expected a non-empty list of x positions, got %s",
                     got(gl, b, sizeof b));
    if (!(c->gauges = calloc(gl->n, sizeof *c->gauges))) return oom(x);
    c->n_gauges = gl->n;
    for (size_t i = 0; i < gl->n; i++) {
      char ik[KEYLEN];
      bprintf(ik, sizeof ik, "output.gauges[%zu]", i);
      if (read_number(x, gl->items[i], ik, &R_ANY, &c->gauges[i])) return -1;
    }
  }
  if (rc >= 0 && s && read_probes(x, s, c)) return -1;
  if (rc >= 0) estimate_particles(c);
  return rc < 0 ? -1 : 0;
}

/* "a\nb\nc" from the overrides. */
static char *join_overrides(const char *const *set, size_t n) {
  size_t len = 0;
  for (size_t i = 0; i < n; i++)
    len += strlen(set[i]) + 1;
  char *s = malloc(len + 1), *p = s;
  if (!s) return NULL;
  for (size_t i = 0; i < n; i++) {
    size_t k = strlen(set[i]);
    if (i) *p++ = '\n';
    memcpy(p, set[i], k);
    p += k;
  }
  *p = '\0';
  return s;
}

static int parse_into(ctx *x, const char *text, size_t len, size_t n_set, sph_case *c) {
  node *root = NULL;
  int rc = parse_yaml(x, text, len, FROM_FILE, NULL, &root);
  if (rc) return rc;
  if (root->kind != NODE_MAP) {
    char b[96];
    rc = fail_at(x, root, NULL, "expected a mapping of case keys at the top level, got %s",
                 got(root, b, sizeof b));
  }
  for (size_t i = 0; rc == 0 && i < n_set; i++)
    rc = apply_set(x, root, (int)i);
  set_defaults(c);
  if (rc == 0) rc = read_case(x, root, c);
  node_free(root);
  if (rc) return rc;
  if (!c->description) c->description = dup_n("", 0);
  c->path = dup_n(x->origin, strlen(x->origin));
  c->text = dup_n(text, len);
  c->overrides = join_overrides(x->set, n_set);
  if (!c->description || !c->path || !c->text || !c->overrides) return oom(x);
  return 0;
}

/* ---- public --------------------------------------------------------------- */

int sph_case_parse(const char *text, size_t len, const char *origin, const char *const *set,
                   size_t n_set, sph_case *c, sph_error *err) {
  ctx x = {
      origin ? origin : "<text>", text ? text : "", text ? len : 0, set, err, NULL, NULL, NULL};
  memset(c, 0, sizeof *c);
  for (size_t i = 0; i < n_set; i++)
    if (!set || !set[i]) return sph_error_set(err, "%s: an empty --set override", x.origin);
  if (n_set > (size_t)0x7fffffff) return sph_error_set(err, "%s: too many overrides", x.origin);
  if (parse_into(&x, x.text, x.len, n_set, c)) {
    sph_case_free(c);
    return -1;
  }
  return 0;
}

int sph_case_load(const char *path, const char *const *set, size_t n_set, sph_case *c,
                  sph_error *err) {
  memset(c, 0, sizeof *c);
  if (!path) return sph_error_set(err, "no case file given");
  FILE *f = fopen(path, "rb");
  if (!f) return sph_error_set(err, "%s: cannot open the case file: %s", path, strerror(errno));
  size_t len = 0, cap = 4096;
  char *buf = malloc(cap);
  int bad = buf == NULL, saved = ENOMEM;
  while (!bad) {
    if (len == cap) {
      char *nb = cap > ((size_t)-1) / 2 ? NULL : realloc(buf, cap * 2);
      if (!nb) {
        bad = 1;
        break;
      }
      buf = nb;
      cap *= 2;
    }
    size_t got_n = fread(buf + len, 1, cap - len, f);
    len += got_n;
    if (len > MAX_CASE_BYTES) { /* /dev/zero would never end (issue 21, D8) */
      fclose(f);
      free(buf);
      return sph_error_set(err,
                           "%s: the case file is larger than %u bytes (1 MiB): not a case file",
                           path, MAX_CASE_BYTES);
    }
    if (got_n == 0) {
      if (ferror(f)) {
        saved = errno;
        bad = 1;
      }
      break;
    }
  }
  fclose(f);
  if (bad) {
    free(buf);
    return sph_error_set(err, "%s: cannot read the case file: %s", path, strerror(saved));
  }
  int rc = sph_case_parse(buf, len, path, set, n_set, c, err);
  free(buf);
  return rc;
}

void sph_case_free(sph_case *c) {
  if (!c) return;
  free(c->name);
  free(c->description);
  free(c->path);
  free(c->text);
  free(c->overrides);
  free(c->fluid);
  free(c->walls);
  free(c->output_times);
  free(c->gauges);
  free(c->probes);
  memset(c, 0, sizeof *c);
}

/* ---- describe ------------------------------------------------------------- */

typedef struct sbuf {
  char *s;
  size_t len, cap;
  int failed;
} sbuf;

static void sb_add(sbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void sb_add(sbuf *b, const char *fmt, ...) {
  va_list ap;
  if (b->failed) return;
  va_start(ap, fmt);
  int n = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  if (n < 0) {
    b->failed = 1;
    return;
  }
  if (b->len + (size_t)n + 1 > b->cap) {
    size_t cap = b->cap ? b->cap : 1024;
    while (b->len + (size_t)n + 1 > cap)
      cap *= 2;
    char *s = realloc(b->s, cap);
    if (!s) {
      b->failed = 1;
      return;
    }
    b->s = s;
    b->cap = cap;
  }
  va_start(ap, fmt);
  vsnprintf(b->s + b->len, b->cap - b->len, fmt, ap);
  va_end(ap);
  b->len += (size_t)n;
}

/* A double-quoted, escaped string, so any description stays on one line. */
static void sb_quoted(sbuf *b, const char *s) {
  sb_add(b, "\"");
  for (; s && *s; s++) {
    unsigned char ch = (unsigned char)*s;
    if (ch == '"' || ch == '\\')
      sb_add(b, "\\%c", ch);
    else if (ch == '\n')
      sb_add(b, "\\n");
    else if (ch == '\t')
      sb_add(b, "\\t");
    else if (ch < 0x20 || ch == 0x7f)
      sb_add(b, "\\x%02x", ch);
    else
      sb_add(b, "%c", ch);
  }
  sb_add(b, "\"\n");
}

static void sb_pair(sbuf *b, const char *key, double v0, double v1) {
  sb_add(b, "%s: [%.17g, %.17g]\n", key, v0, v1);
}

static void describe_geometry(sbuf *b, const sph_case *c) {
  char k[KEYLEN];
  if (c->tank.present) {
    sb_pair(b, "geometry.tank.x", c->tank.x0, c->tank.x1);
    sb_pair(b, "geometry.tank.y", c->tank.y0, c->tank.y1);
    sb_add(b, "geometry.tank.layers: %d\n", c->tank.layers);
    sb_add(b, "geometry.tank.boundary: %s\n", sph_boundary_name(c->tank.boundary));
    /* written only when not the default, so that older records still match */
    if (!c->tank.stagger) sb_add(b, "geometry.tank.stagger: false\n");
    if (c->tank.extrapolated) sb_add(b, "geometry.tank.extrapolated_velocity: true\n");
    if (c->tank.free_slip) sb_add(b, "geometry.tank.free_slip: true\n");
  } else {
    sb_add(b, "geometry.tank: none\n");
  }
  for (size_t i = 0; i < c->n_fluid; i++) {
    const sph_fluid_block *f = &c->fluid[i];
    bprintf(k, sizeof k, "geometry.fluid[%zu]", i);
    sb_add(b, "%s.x: [%.17g, %.17g]\n", k, f->x0, f->x1);
    sb_add(b, "%s.y: [%.17g, %.17g]\n", k, f->y0, f->y1);
    sb_add(b, "%s.velocity: [%.17g, %.17g]\n", k, f->vx, f->vy);
    sb_add(b, "%s.hydrostatic: %s\n", k, f->hydrostatic ? "true" : "false");
    sb_add(b, "%s.surface: %.17g\n", k, f->surface);
    sb_add(b, "%s.jitter: %.17g\n", k, f->jitter);
    sb_add(b, "%s.seed: %d\n", k, f->seed);
  }
  if (c->n_walls == 0) sb_add(b, "geometry.walls: []\n");
  for (size_t i = 0; i < c->n_walls; i++) {
    const sph_wall_segment *w = &c->walls[i];
    bprintf(k, sizeof k, "geometry.walls[%zu]", i);
    sb_add(b, "%s.from: [%.17g, %.17g]\n", k, w->x0, w->y0);
    sb_add(b, "%s.to: [%.17g, %.17g]\n", k, w->x1, w->y1);
    sb_add(b, "%s.layers: %d\n", k, w->layers);
    sb_add(b, "%s.boundary: %s\n", k, sph_boundary_name(w->boundary));
    if (!w->stagger) sb_add(b, "%s.stagger: false\n", k);
    if (w->extrapolated) sb_add(b, "%s.extrapolated_velocity: true\n", k);
    if (w->free_slip) sb_add(b, "%s.free_slip: true\n", k);
    if (w->motion.kind == SPH_MOTION_PISTON || w->motion.kind == SPH_MOTION_FLAP) {
      const sph_paddle *pd = &w->motion.paddle;
      sb_add(b, "%s.motion.type: %s\n", k, motion_names[w->motion.kind]);
      sb_add(b, "%s.motion.period: %.17g\n", k, pd->period);
      sb_add(b, "%s.motion.stroke: %.17g\n", k, pd->stroke);
      sb_add(b, "%s.motion.depth: %.17g\n", k, pd->depth);
      sb_add(b, "%s.motion.ramp: %.17g\n", k, pd->ramp);
      sb_add(b, "%s.motion.hinge: [%.17g, %.17g]\n", k, pd->hinge_x, pd->hinge_y);
    }
    if (w->motion.kind == SPH_MOTION_TRANSLATE) {
      sb_add(b, "%s.motion.type: translate\n", k);
      sb_add(b, "%s.motion.velocity: [%.17g, %.17g]\n", k, w->motion.vx, w->motion.vy);
      sb_add(b, "%s.motion.start: %.17g\n", k, w->motion.start);
      sb_add(b, "%s.motion.stop: %.17g\n", k, w->motion.stop);
    }
  }
  if (c->periodic) sb_pair(b, "geometry.periodic_x", c->periodic_x[0], c->periodic_x[1]);
  if (c->domain_set) {
    sb_pair(b, "geometry.domain.x", c->domain[0], c->domain[1]);
    sb_pair(b, "geometry.domain.y", c->domain[2], c->domain[3]);
  } else {
    sb_add(b, "geometry.domain: none\n");
  }
}

char *sph_case_describe(const sph_case *c) {
  sbuf b = {NULL, 0, 0, 0};
  if (!c) return NULL;
  sb_add(&b, "name: %s\n", c->name ? c->name : "");
  sb_add(&b, "description: ");
  sb_quoted(&b, c->description);
  sb_add(&b, "physics.rho0: %.17g\n", c->rho0);
  sb_pair(&b, "physics.gravity", c->gravity[0], c->gravity[1]);
  sb_add(&b, "physics.sound_speed: %.17g\n", c->sound_speed);
  sb_add(&b, "physics.artificial_viscosity.alpha: %.17g\n", c->alpha);
  sb_add(&b, "physics.artificial_viscosity.beta: %.17g\n", c->beta);
  sb_add(&b, "physics.artificial_viscosity.eta: %.17g\n", c->eta);
  sb_add(&b, "physics.xsph: %.17g\n", c->xsph);
  sb_add(&b, "physics.viscosity.model: %s\n", sph_viscosity_name(c->viscosity));
  if (c->viscosity != SPH_VISCOSITY_NONE) sb_add(&b, "physics.viscosity.mu: %.17g\n", c->mu);
  if (c->gradient_correction) sb_add(&b, "physics.viscosity.gradient_correction: true\n");
  sb_add(&b, "physics.turbulence.model: %s\n", c->sps ? "sps" : "none");
  if (c->sps) {
    sb_add(&b, "physics.turbulence.cs: %.17g\n", c->sps_cs);
    sb_add(&b, "physics.turbulence.ci: %.17g\n", c->sps_ci);
  }
  sb_add(&b, "physics.repulsion: %.17g\n", c->repulsion);
  sb_add(&b, "numerics.dx: %.17g\n", c->dx);
  sb_add(&b, "numerics.h_factor: %.17g\n", c->h_factor);
  sb_add(&b, "numerics.h: %.17g\n", c->h);
  sb_add(&b, "numerics.smoothing_length: %s\n", h_names[c->variable_h]);
  sb_add(&b, "numerics.kernel: %s\n", sph_kernel_name(c->kernel));
  sb_add(&b, "numerics.integrator: %s\n", sph_integrator_name(c->integrator));
  sb_add(&b, "numerics.time_step.rule: %s\n", sph_dt_rule_name(c->dt_rule));
  sb_add(&b, "numerics.time_step.factor: %.17g\n", c->dt_factor);
  if (c->dt_rule == SPH_DT_FIXED) sb_add(&b, "numerics.time_step.dt: %.17g\n", c->dt_fixed);
  sb_add(&b, "numerics.density_filter.kind: %s\n", sph_filter_name(c->density_filter));
  sb_add(&b, "numerics.density_filter.every: %d\n", c->filter_every);
  sb_add(&b, "numerics.density_diffusion.model: %s\n", sph_diffusion_name(c->diffusion));
  sb_add(&b, "numerics.density_diffusion.delta: %.17g\n", c->diffusion_delta);
  if (c->shifting) sb_add(&b, "numerics.shifting.coefficient: %.17g\n", c->shifting_coefficient);
  sb_add(&b, "numerics.density_limit: %.17g\n", c->density_limit);
  sb_add(&b, "time.end: %.17g\n", c->t_end);
  sb_add(&b, "time.output_interval: %.17g\n", c->output_interval);
  for (size_t i = 0; i < c->n_output_times; i++)
    sb_add(&b, "time.output_times[%zu]: %.17g\n", i, c->output_times[i]);
  sb_add(&b, "time.stop: %s\n", sph_stop_name(c->stop));
  describe_geometry(&b, c);
  sb_add(&b, "free_surface.radius_factor: %.17g\n", c->fs_radius_factor);
  sb_add(&b, "free_surface.h_factor: %.17g\n", c->fs_h_factor);
  sb_add(&b, "output.snapshots: %s\n", c->snapshots ? "true" : "false");
  sb_add(&b, "output.free_surface: %s\n", c->output_free_surface ? "true" : "false");
  sb_add(&b, "output.energy: %s\n", c->energy ? "true" : "false");
  for (size_t i = 0; i < c->n_gauges; i++)
    sb_add(&b, "output.gauges[%zu]: %.17g\n", i, c->gauges[i]);
  for (size_t i = 0; i < c->n_probes; i++) {
    const sph_probe *q = &c->probes[i];
    sb_add(&b, "output.probes[%zu]: %s %s", i, q->name, sph_probe_kind_name(q->kind));
    if (q->kind == SPH_PROBE_LEVEL)
      sb_add(&b, " x %.17g\n", q->x);
    else if (q->kind == SPH_PROBE_VELOCITY)
      sb_add(&b, " at [%.17g, %.17g]\n", q->x, q->y);
    else
      sb_add(&b, " at [%.17g, %.17g] diameter %.17g along %s\n", q->x, q->y, q->diameter,
             q->along_x ? "x" : "y");
  }
  if (c->n_probes) sb_add(&b, "output.probe_interval: %.17g\n", c->probe_interval);
  if (b.failed) {
    free(b.s);
    return NULL;
  }
  return b.s;
}
