/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * yaml_tree.c - the strict YAML reader (see yaml_tree.h).
 *
 * Algorithm. The text is parsed with libyaml's document API
 * (yaml_parser_load) and copied into a small private tree of scalars, lists
 * and mappings in which every node and every mapping key remembers where it
 * came from: the file and its 1-based line, or the index of the override
 * that produced it. While copying, duplicate keys, non-scalar keys,
 * aliases, explicit tags and extra documents are rejected; nesting is
 * measured on the text before libyaml sees it (a deep document would
 * exhaust its stack). Each override `dotted.key=value` is split at its
 * first '='; its value is parsed as a YAML document of its own and
 * replaces the node at that path, or is added there (creating intermediate
 * mappings). The typed readers then report the first violation.
 */
#include "config.h"

#include "case/yaml_tree.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <yaml.h>

void sph_yaml_free(sph_yaml_node *t) {
  if (!t) return;
  for (size_t i = 0; i < t->n; i++) {
    if (t->kind == SPH_YAML_LIST) {
      sph_yaml_free(t->items[i]);
    } else if (t->kind == SPH_YAML_MAP) {
      free(t->entries[i].key);
      sph_yaml_free(t->entries[i].val);
    }
  }
  free(t->text);
  free(t->items);
  free(t->entries);
  free(t);
}

static sph_yaml_node *node_new(sph_yaml_kind kind, int src, size_t line) {
  sph_yaml_node *t = calloc(1, sizeof *t);
  if (!t) return NULL;
  t->kind = kind;
  t->src = src;
  t->line = line;
  return t;
}

char *sph_yaml_dup(const char *s, size_t n) {
  char *d = malloc(n + 1);
  if (!d) return NULL;
  if (n) memcpy(d, s, n);
  d[n] = '\0';
  return d;
}

/* snprintf into a fixed buffer where truncation is harmless (names, messages). */
void sph_yaml_bprintf(char *buf, size_t n, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, n, fmt, ap);
  va_end(ap);
}

sph_yaml_entry *sph_yaml_find(const sph_yaml_node *m, const char *key) {
  for (size_t i = 0; i < m->n; i++)
    if (strcmp(m->entries[i].key, key) == 0) return &m->entries[i];
  return NULL;
}

/* ---- errors --------------------------------------------------------------- */

/* "origin[:line]: key: message"; the origin of a --set node is the --set. */
static int failv(const sph_yaml_ctx *x, int src, size_t line, const char *key, const char *fmt,
                 va_list ap) {
  char where[512], msg[768];
  if (src >= 0)
    sph_yaml_bprintf(where, sizeof where, "--set %s", x->set[src]);
  else if (src == SPH_YAML_FROM_SCHEME)
    sph_yaml_bprintf(where, sizeof where, "%s: numerics.scheme %s (its default)", x->origin,
                     x->scheme ? x->scheme : "?");
  else if (line > 0)
    sph_yaml_bprintf(where, sizeof where, "%s:%zu", x->origin, line);
  else
    sph_yaml_bprintf(where, sizeof where, "%s", x->origin);
  vsnprintf(msg, sizeof msg, fmt, ap);
  if (key && *key) return sph_error_set(x->err, "%s: %s: %s", where, key, msg);
  return sph_error_set(x->err, "%s: %s", where, msg);
}

int sph_yaml_fail(const sph_yaml_ctx *x, int src, size_t line, const char *key, const char *fmt,
                  ...) {
  va_list ap;
  va_start(ap, fmt);
  int rc = failv(x, src, line, key, fmt, ap);
  va_end(ap);
  return rc;
}

int sph_yaml_fail_at(const sph_yaml_ctx *x, const sph_yaml_node *t, const char *key,
                     const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int rc = failv(x, t->src, t->line, key, fmt, ap);
  va_end(ap);
  return rc;
}

int sph_yaml_oom(const sph_yaml_ctx *x) {
  return sph_error_set(x->err, "%s: out of memory", x->origin);
}

/* What a node is, for "got ...": a quoted, shortened, printable scalar. */
const char *sph_yaml_got(const sph_yaml_node *t, char *buf, size_t n) {
  if (t->kind == SPH_YAML_MAP) return "a mapping";
  if (t->kind == SPH_YAML_LIST) {
    if (t->n == 0) return "an empty list";
    sph_yaml_bprintf(buf, n, "a list of %zu item%s", t->n, t->n == 1 ? "" : "s");
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
  sph_yaml_bprintf(buf, n, "%s'%s%s'", t->plain ? "" : "the string ", s, k < len ? "..." : "");
  return buf;
}

void sph_yaml_join(char *buf, size_t n, const char *prefix, const char *key) {
  if (prefix && *prefix)
    sph_yaml_bprintf(buf, n, "%s.%s", prefix, key);
  else
    sph_yaml_bprintf(buf, n, "%s", key);
}

/* ---- YAML text to tree ---------------------------------------------------- */

typedef struct loader {
  const sph_yaml_ctx *x;
  yaml_document_t *doc;
  int src;
  unsigned char *seen; /* per document node: copied already (so an alias) */
} loader;

static int copy_node(loader *L, yaml_node_t *y, const char *path, int depth, sph_yaml_node **out);

static size_t mark_line(const loader *L, yaml_mark_t m) {
  return L->src == SPH_YAML_FROM_FILE ? m.line + 1 : 0;
}

/* The document node `id`, which must not have been copied before. */
static int child(loader *L, int id, size_t line, const char *path, yaml_node_t **out) {
  yaml_node_t *y = yaml_document_get_node(L->doc, id);
  *out = NULL;
  if (!y) return sph_yaml_fail(L->x, L->src, line, path, "malformed YAML document");
  size_t k = (size_t)(y - L->doc->nodes.start);
  if (L->seen[k])
    return sph_yaml_fail(L->x, L->src, line, path, "aliases (*name) are not supported");
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

static int copy_scalar(loader *L, yaml_node_t *y, const char *path, sph_yaml_node *t) {
  const char *v = (const char *)y->data.scalar.value;
  size_t len = y->data.scalar.length;
  if (memchr(v, '\0', len))
    return sph_yaml_fail_at(L->x, t, path, "a NUL character is not allowed");
  t->plain = y->data.scalar.style == YAML_PLAIN_SCALAR_STYLE;
  t->text = sph_yaml_dup(v, len);
  return t->text ? 0 : sph_yaml_oom(L->x);
}

static int copy_list(loader *L, yaml_node_t *y, const char *path, int depth, sph_yaml_node *t) {
  size_t n = (size_t)(y->data.sequence.items.top - y->data.sequence.items.start);
  if (n && !(t->items = calloc(n, sizeof *t->items))) return sph_yaml_oom(L->x);
  for (size_t i = 0; i < n; i++) {
    char kp[SPH_YAML_KEYLEN];
    yaml_node_t *c;
    sph_yaml_bprintf(kp, sizeof kp, "%s[%zu]", path, i);
    if (child(L, y->data.sequence.items.start[i], t->line, kp, &c)) return -1;
    if (copy_node(L, c, kp, depth + 1, &t->items[i])) return -1;
    t->n = i + 1;
  }
  return 0;
}

static int copy_map(loader *L, yaml_node_t *y, const char *path, int depth, sph_yaml_node *t) {
  size_t n = (size_t)(y->data.mapping.pairs.top - y->data.mapping.pairs.start);
  if (n && !(t->entries = calloc(n, sizeof *t->entries))) return sph_yaml_oom(L->x);
  for (size_t i = 0; i < n; i++) {
    const yaml_node_pair_t *p = &y->data.mapping.pairs.start[i];
    yaml_node_t *k, *v;
    sph_yaml_entry *e = &t->entries[i];
    if (child(L, p->key, t->line, path, &k)) return -1;
    e->src = L->src;
    e->line = mark_line(L, k->start_mark);
    if (k->type != YAML_SCALAR_NODE)
      return sph_yaml_fail(L->x, e->src, e->line, path, "a mapping key must be a plain name");
    const char *ks = (const char *)k->data.scalar.value;
    char kp[SPH_YAML_KEYLEN];
    sph_yaml_join(kp, sizeof kp, path, ks);
    for (size_t j = 0; j < i; j++)
      if (strcmp(t->entries[j].key, ks) == 0) {
        if (L->src == SPH_YAML_FROM_FILE)
          return sph_yaml_fail(L->x, e->src, e->line, kp, "duplicate key (first given at line %zu)",
                               t->entries[j].line);
        return sph_yaml_fail(L->x, e->src, e->line, kp, "duplicate key");
      }
    if (!(e->key = sph_yaml_dup(ks, k->data.scalar.length))) return sph_yaml_oom(L->x);
    t->n = i + 1;
    if (child(L, p->value, e->line, kp, &v)) return -1;
    if (copy_node(L, v, kp, depth + 1, &e->val)) return -1;
  }
  return 0;
}

static int copy_node(loader *L, yaml_node_t *y, const char *path, int depth, sph_yaml_node **out) {
  size_t line = mark_line(L, y->start_mark);
  *out = NULL;
  if (depth > SPH_YAML_MAX_DEPTH)
    return sph_yaml_fail(L->x, L->src, line, path, "nested deeper than %d levels",
                         SPH_YAML_MAX_DEPTH);
  if (!default_tag(y))
    return sph_yaml_fail(L->x, L->src, line, path, "tags such as '%s' are not supported",
                         (const char *)y->tag);
  sph_yaml_kind kind = y->type == YAML_SCALAR_NODE     ? SPH_YAML_SCALAR
                       : y->type == YAML_SEQUENCE_NODE ? SPH_YAML_LIST
                                                       : SPH_YAML_MAP;
  sph_yaml_node *t = node_new(kind, L->src, line);
  if (!t) return sph_yaml_oom(L->x);
  int rc = kind == SPH_YAML_SCALAR ? copy_scalar(L, y, path, t)
           : kind == SPH_YAML_LIST ? copy_list(L, y, path, depth, t)
                                   : copy_map(L, y, path, depth, t);
  if (rc) {
    sph_yaml_free(t);
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

static int syntax_error(const sph_yaml_ctx *x, const yaml_parser_t *p, const char *text, size_t len,
                        int src, const char *key) {
  const char *problem = p->problem ? p->problem : "cannot be parsed";
  size_t line = p->problem_mark.line + 1, col = p->problem_mark.column + 1;
  char ctxt[256] = "";
  if (p->error == YAML_MEMORY_ERROR) return sph_yaml_oom(x);
  if (p->error == YAML_READER_ERROR) locate(text, len, p->problem_offset, &line, &col);
  if (p->context && src == SPH_YAML_FROM_FILE)
    sph_yaml_bprintf(ctxt, sizeof ctxt, " (%s at line %zu, column %zu)", p->context,
                     p->context_mark.line + 1, p->context_mark.column + 1);
  else if (p->context)
    sph_yaml_bprintf(ctxt, sizeof ctxt, " (%s)", p->context);
  if (src == SPH_YAML_FROM_FILE)
    return sph_error_set(x->err, "%s:%zu:%zu: YAML syntax error: %s%s", x->origin, line, col,
                         problem, ctxt);
  if (p->problem_mark.index >= len)
    return sph_yaml_fail(x, src, 0, key, "YAML syntax error in the value at its end: %s%s", problem,
                         ctxt);
  return sph_yaml_fail(x, src, 0, key, "YAML syntax error in the value at column %zu: %s%s", col,
                       problem, ctxt);
}

/* The nesting of the text checked event by event before the document is
 * loaded: libyaml's loader takes time quadratic in the depth (200 KB of
 * '[' took 20 s), the event parser stops at the first level too deep
 * (issue 21, D6). 0 if within SPH_YAML_MAX_DEPTH (or a syntax error, which the
 * loader then reports), else -1 with the message. */
static int check_depth(const sph_yaml_ctx *x, const char *text, size_t len, int src,
                       const char *key) {
  yaml_parser_t p;
  if (!yaml_parser_initialize(&p)) return sph_yaml_oom(x);
  yaml_parser_set_input_string(&p, (const unsigned char *)text, len);
  int depth = 0, rc = 0;
  for (;;) {
    yaml_event_t e;
    if (!yaml_parser_parse(&p, &e)) break; /* the loader reports it */
    const yaml_event_type_t type = e.type;
    const size_t line = e.start_mark.line + 1;
    yaml_event_delete(&e);
    if (type == YAML_SEQUENCE_START_EVENT || type == YAML_MAPPING_START_EVENT) {
      if (++depth > SPH_YAML_MAX_DEPTH + 1) {
        rc = sph_yaml_fail(x, src, src == SPH_YAML_FROM_FILE ? line : 0, key ? key : "",
                           "nested deeper than %d levels", SPH_YAML_MAX_DEPTH);
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
int sph_yaml_parse(const sph_yaml_ctx *x, const char *text, size_t len, int src, const char *key,
                   sph_yaml_node **out) {
  yaml_parser_t p;
  yaml_document_t doc;
  int rc = 0;
  *out = NULL;
  if (check_depth(x, text, len, src, key)) return -1;
  if (!yaml_parser_initialize(&p)) return sph_yaml_oom(x);
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
      rc = sph_yaml_oom(x);
    } else {
      L.seen[root - doc.nodes.start] = 1;
      rc = copy_node(&L, root, key ? key : "", 0, out);
    }
    free(L.seen);
  } else {
    *out = node_new(SPH_YAML_SCALAR, src, src == SPH_YAML_FROM_FILE ? 1 : 0);
    if (!*out || !((*out)->text = sph_yaml_dup("", 0))) rc = sph_yaml_oom(x);
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
        rc = sph_yaml_fail(x, src, src == SPH_YAML_FROM_FILE ? r2->start_mark.line + 1 : 0, key,
                           "only one YAML document is allowed");
      yaml_document_delete(&more);
    }
  }
  if (rc) {
    sph_yaml_free(*out);
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

static int add_entry(const sph_yaml_ctx *x, sph_yaml_node *m, const char *key, size_t klen, int src,
                     sph_yaml_node *val) {
  sph_yaml_entry *e = realloc(m->entries, (m->n + 1) * sizeof *e);
  if (!e) return sph_yaml_oom(x);
  m->entries = e;
  e = &m->entries[m->n];
  if (!(e->key = sph_yaml_dup(key, klen))) return sph_yaml_oom(x);
  e->src = src;
  e->line = 0;
  e->val = val;
  m->n++;
  return 0;
}

/* Puts `val` at the dotted key `key` of the mapping root (takes val). */
static int place(const sph_yaml_ctx *x, sph_yaml_node *root, const char *key, int src,
                 sph_yaml_node *val) {
  sph_yaml_node *m = root;
  const char *seg = key;
  for (;;) {
    const char *dot = strchr(seg, '.');
    size_t slen = dot ? (size_t)(dot - seg) : strlen(seg);
    char name[SPH_YAML_KEYLEN];
    sph_yaml_bprintf(name, sizeof name, "%.*s", (int)slen, seg);
    sph_yaml_entry *e = sph_yaml_find(m, name);
    if (!dot) {
      if (e) {
        sph_yaml_free(e->val);
        e->val = val;
        return 0;
      }
      if (add_entry(x, m, seg, slen, src, val)) {
        sph_yaml_free(val);
        return -1;
      }
      return 0;
    }
    if (!e) {
      sph_yaml_node *sub = node_new(SPH_YAML_MAP, src, 0);
      int rc = sub ? add_entry(x, m, seg, slen, src, sub) : sph_yaml_oom(x);
      if (rc) {
        sph_yaml_free(sub);
        sph_yaml_free(val);
        return rc;
      }
      e = &m->entries[m->n - 1];
    } else if (e->val->kind != SPH_YAML_MAP) {
      char at[64] = "", g[96];
      if (e->val->src == SPH_YAML_FROM_FILE)
        sph_yaml_bprintf(at, sizeof at, " (line %zu)", e->val->line);
      int rc = sph_yaml_fail(x, src, 0, NULL,
                             "%.*s: is %s%s, not a mapping, so '%s' cannot be set in it",
                             (int)(dot - key), key, sph_yaml_got(e->val, g, sizeof g), at, dot + 1);
      sph_yaml_free(val);
      return rc;
    }
    m = e->val;
    seg = dot + 1;
  }
}

int sph_yaml_apply_set(const sph_yaml_ctx *x, sph_yaml_node *root, int i) {
  const char *s = x->set[i];
  const char *eq = s ? strchr(s, '=') : NULL;
  if (!eq || !valid_dotted_key(s, (size_t)(eq - s)))
    return sph_yaml_fail(
        x, i, 0, NULL,
        "expected dotted.key=value (a key such as numerics.dx, then '=', then a YAML "
        "value)");
  char *key = sph_yaml_dup(s, (size_t)(eq - s));
  sph_yaml_node *val;
  if (!key) return sph_yaml_oom(x);
  int rc = sph_yaml_parse(x, eq + 1, strlen(eq + 1), i, key, &val);
  if (rc == 0) rc = place(x, root, key, i, val);
  free(key);
  return rc;
}

int sph_yaml_put_default(const sph_yaml_ctx *x, sph_yaml_node *root, const char *key,
                         const char *value) {
  sph_yaml_node *val;
  int rc = sph_yaml_parse(x, value, strlen(value), SPH_YAML_FROM_SCHEME, key, &val);
  if (rc == 0) rc = place(x, root, key, SPH_YAML_FROM_SCHEME, val);
  return rc;
}

/* ---- typed readers -------------------------------------------------------- */

const sph_yaml_range SPH_YAML_ANY = {0, 0, 0, 0, NULL};
const sph_yaml_range SPH_YAML_POS = {0, 0, '(', 0, NULL};
const sph_yaml_range SPH_YAML_NONNEG = {0, 0, '[', 0, NULL};
const sph_yaml_range SPH_YAML_UNIT = {0, 1, '[', ']', NULL};

static int in_range(const sph_yaml_range *r, double v) {
  if (r->lo_kind == '[' && !(v >= r->lo)) return 0;
  if (r->lo_kind == '(' && !(v > r->lo)) return 0;
  if (r->hi_kind == ']' && !(v <= r->hi)) return 0;
  if (r->hi_kind == ')' && !(v < r->hi)) return 0;
  return 1;
}

static const char *range_text(const sph_yaml_range *r, char *buf, size_t n) {
  if (r->what) return r->what;
  if (!r->lo_kind && !r->hi_kind) return "a number";
  if (r->lo_kind == '(' && r->lo == 0 && !r->hi_kind) return "a positive number";
  if (!r->hi_kind)
    sph_yaml_bprintf(buf, n, "a number %s %g", r->lo_kind == '[' ? ">=" : ">", r->lo);
  else if (!r->lo_kind)
    sph_yaml_bprintf(buf, n, "a number %s %g", r->hi_kind == ']' ? "<=" : "<", r->hi);
  else
    sph_yaml_bprintf(buf, n, "a number in %c%g, %g%c", r->lo_kind, r->lo, r->hi, r->hi_kind);
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

int sph_yaml_read_number(const sph_yaml_ctx *x, const sph_yaml_node *t, const char *kp,
                         const sph_yaml_range *r, double *out) {
  double v;
  if (t->kind != SPH_YAML_SCALAR || !t->plain || parse_number(t->text, &v) || !in_range(r, v)) {
    char b1[96], b2[96];
    return sph_yaml_fail_at(x, t, kp, "expected %s, got %s", range_text(r, b1, sizeof b1),
                            sph_yaml_got(t, b2, sizeof b2));
  }
  *out = v;
  return 0;
}

int sph_yaml_read_int(const sph_yaml_ctx *x, const sph_yaml_node *t, const char *kp, long lo,
                      long hi, int *out) {
  const char *s = t->kind == SPH_YAML_SCALAR ? t->text : "";
  const char *digits = (*s == '-' || *s == '+') ? s + 1 : s;
  long v = 0;
  int ok = t->kind == SPH_YAML_SCALAR && t->plain && *digits &&
           strspn(digits, "0123456789") == strlen(digits);
  if (ok) {
    errno = 0;
    v = strtol(s, NULL, 10);
    ok = errno == 0 && v >= lo && v <= hi;
  }
  if (!ok) {
    char b[96];
    return sph_yaml_fail_at(x, t, kp, "expected an integer in %ld..%ld, got %s", lo, hi,
                            sph_yaml_got(t, b, sizeof b));
  }
  *out = (int)v;
  return 0;
}

int sph_yaml_read_bool(const sph_yaml_ctx *x, const sph_yaml_node *t, const char *kp, int *out) {
  if (t->kind == SPH_YAML_SCALAR && t->plain && strcmp(t->text, "true") == 0) {
    *out = 1;
  } else if (t->kind == SPH_YAML_SCALAR && t->plain && strcmp(t->text, "false") == 0) {
    *out = 0;
  } else {
    char b[96];
    return sph_yaml_fail_at(x, t, kp, "expected true or false, got %s",
                            sph_yaml_got(t, b, sizeof b));
  }
  return 0;
}

void sph_yaml_list_names(const char *const *names, char *buf, size_t n) {
  buf[0] = '\0';
  for (int i = 0; names[i]; i++) {
    size_t used = strlen(buf);
    sph_yaml_bprintf(buf + used, n - used, "%s%s", i ? ", " : "", names[i]);
  }
}

int sph_yaml_read_choice(const sph_yaml_ctx *x, const sph_yaml_node *t, const char *kp,
                         const char *const *names, int *out) {
  char valid[256], b[96];
  sph_yaml_list_names(names, valid, sizeof valid);
  if (t->kind != SPH_YAML_SCALAR)
    return sph_yaml_fail_at(x, t, kp, "expected one of: %s, got %s", valid,
                            sph_yaml_got(t, b, sizeof b));
  for (int i = 0; names[i]; i++)
    if (strcmp(t->text, names[i]) == 0) {
      *out = i;
      return 0;
    }
  return sph_yaml_fail_at(x, t, kp, "unknown choice %s (valid: %s)", sph_yaml_got(t, b, sizeof b),
                          valid);
}

int sph_yaml_read_vector(const sph_yaml_ctx *x, const sph_yaml_node *t, const char *kp, int n,
                         double *out) {
  char b[96];
  if (t->kind != SPH_YAML_LIST || t->n != (size_t)n)
    return sph_yaml_fail_at(x, t, kp, "expected a list of %d numbers, got %s", n,
                            sph_yaml_got(t, b, sizeof b));
  for (int i = 0; i < n; i++) {
    char ik[SPH_YAML_KEYLEN];
    sph_yaml_bprintf(ik, sizeof ik, "%s[%d]", kp, i);
    if (sph_yaml_read_number(x, t->items[i], ik, &SPH_YAML_ANY, &out[i])) return -1;
  }
  return 0;
}

/* A list of exactly two numbers; `axis` ('x', 'y', 'z') also requires v0 < v1. */
int sph_yaml_read_pair(const sph_yaml_ctx *x, const sph_yaml_node *t, const char *kp, char axis,
                       double out[2]) {
  if (sph_yaml_read_vector(x, t, kp, 2, out)) return -1;
  if (axis && !(out[0] < out[1]))
    return sph_yaml_fail_at(x, t, kp, "expected [%c0, %c1] with %c0 < %c1, got [%g, %g]", axis,
                            axis, axis, axis, out[0], out[1]);
  return 0;
}

/* ---- mapping access ------------------------------------------------------- */

/* Unknown keys of mapping m (at dotted path `path`) are errors. */
int sph_yaml_check_keys(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *path,
                        const char *const *valid) {
  for (size_t i = 0; i < m->n; i++) {
    const sph_yaml_entry *e = &m->entries[i];
    int known = 0;
    for (int j = 0; valid[j] && !known; j++)
      known = strcmp(e->key, valid[j]) == 0;
    if (known) continue;
    char list[512], kp[SPH_YAML_KEYLEN];
    sph_yaml_list_names(valid, list, sizeof list);
    sph_yaml_join(kp, sizeof kp, path, e->key);
    if (*path)
      return sph_yaml_fail(x, e->src, e->line, kp, "unknown key (valid keys in '%s': %s)", path,
                           list);
    return sph_yaml_fail(x, e->src, e->line, kp, "unknown key (valid top-level keys: %s)", list);
  }
  return 0;
}

/* The value of `key` in m: 1 found, 0 absent (optional), -1 missing (required). */
int sph_yaml_lookup(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *path,
                    const char *key, int required, const sph_yaml_node **out,
                    char kp[SPH_YAML_KEYLEN]) {
  const sph_yaml_entry *e = sph_yaml_find(m, key);
  sph_yaml_join(kp, SPH_YAML_KEYLEN, path, key);
  *out = e ? e->val : NULL;
  if (e) return 1;
  if (!required) return 0;
  return sph_yaml_fail(x, m->src, m->line, kp, "required key is missing");
}

int sph_yaml_get_number(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *path,
                        const char *key, int required, const sph_yaml_range *r, double *out) {
  const sph_yaml_node *t;
  char kp[SPH_YAML_KEYLEN];
  int rc = sph_yaml_lookup(x, m, path, key, required, &t, kp);
  if (rc <= 0) return rc;
  return sph_yaml_read_number(x, t, kp, r, out) ? -1 : 1;
}

int sph_yaml_get_int(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *path,
                     const char *key, long lo, long hi, int *out) {
  const sph_yaml_node *t;
  char kp[SPH_YAML_KEYLEN];
  int rc = sph_yaml_lookup(x, m, path, key, 0, &t, kp);
  if (rc <= 0) return rc;
  return sph_yaml_read_int(x, t, kp, lo, hi, out) ? -1 : 1;
}

int sph_yaml_get_bool(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *path,
                      const char *key, int *out) {
  const sph_yaml_node *t;
  char kp[SPH_YAML_KEYLEN];
  int rc = sph_yaml_lookup(x, m, path, key, 0, &t, kp);
  if (rc <= 0) return rc;
  return sph_yaml_read_bool(x, t, kp, out) ? -1 : 1;
}

int sph_yaml_get_choice(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *path,
                        const char *key, const char *const *names, int *out) {
  const sph_yaml_node *t;
  char kp[SPH_YAML_KEYLEN];
  int rc = sph_yaml_lookup(x, m, path, key, 0, &t, kp);
  if (rc <= 0) return rc;
  return sph_yaml_read_choice(x, t, kp, names, out) ? -1 : 1;
}

int sph_yaml_get_pair(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *path,
                      const char *key, int required, char axis, double out[2]) {
  const sph_yaml_node *t;
  char kp[SPH_YAML_KEYLEN];
  int rc = sph_yaml_lookup(x, m, path, key, required, &t, kp);
  if (rc <= 0) return rc;
  return sph_yaml_read_pair(x, t, kp, axis, out) ? -1 : 1;
}

int sph_yaml_get_vector(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *path,
                        const char *key, int required, int n, double *out) {
  const sph_yaml_node *t;
  char kp[SPH_YAML_KEYLEN];
  int rc = sph_yaml_lookup(x, m, path, key, required, &t, kp);
  if (rc <= 0) return rc;
  return sph_yaml_read_vector(x, t, kp, n, out) ? -1 : 1;
}

/* A mapping-valued key whose own keys are all in `valid`. */
int sph_yaml_get_section(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *path,
                         const char *key, int required, const char *const *valid,
                         const sph_yaml_node **out) {
  char kp[SPH_YAML_KEYLEN], b[96];
  int rc = sph_yaml_lookup(x, m, path, key, required, out, kp);
  if (rc <= 0) return rc;
  if ((*out)->kind != SPH_YAML_MAP)
    return sph_yaml_fail_at(x, *out, kp, "expected a mapping, got %s",
                            sph_yaml_got(*out, b, sizeof b));
  return sph_yaml_check_keys(x, *out, kp, valid) ? -1 : 1;
}

int sph_yaml_get_string(const sph_yaml_ctx *x, const sph_yaml_node *m, const char *key,
                        int required, char **out) {
  const sph_yaml_node *t;
  char kp[SPH_YAML_KEYLEN], b[96];
  int rc = sph_yaml_lookup(x, m, "", key, required, &t, kp);
  if (rc <= 0) return rc;
  if (t->kind != SPH_YAML_SCALAR)
    return sph_yaml_fail_at(x, t, kp, "expected a string, got %s", sph_yaml_got(t, b, sizeof b));
  free(*out);
  *out = sph_yaml_dup(t->text, strlen(t->text));
  return *out ? 1 : sph_yaml_oom(x);
}
