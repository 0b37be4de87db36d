/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_yaml_tree.c - the strict YAML reader (case/yaml_tree.h) on its own,
 * without the case schema: the tree and where each node came from, what
 * it refuses, overrides, and the typed readers' values and messages. Each
 * error is compared as a whole message ("origin:line: key: ..."), so the
 * origin, the 1-based line, the dotted key and the expectation are checked
 * at once.
 */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case/yaml_tree.h"
#include "core/error.h"
#include "testutil.h"

/* A context for text under the origin "t.yaml" with the overrides set. */
static sph_yaml_ctx ctx_of(const char *text, const char *const *set, sph_error *err) {
  sph_yaml_ctx x = {"t.yaml", text, strlen(text), set, err, NULL};
  return x;
}

/* Parses text; NULL (and the message in err) on failure. */
static sph_yaml_node *parse(const char *text, sph_error *err) {
  sph_yaml_ctx x = ctx_of(text, NULL, err);
  sph_yaml_node *root = NULL;
  if (sph_yaml_parse(&x, text, strlen(text), SPH_YAML_FROM_FILE, NULL, &root)) return NULL;
  return root;
}

/* The parse of text fails with exactly the message want. */
static void expect_parse_error(const char *text, const char *want) {
  sph_error err = {0};
  sph_yaml_node *root = parse(text, &err);
  CU_ASSERT_PTR_NULL(root);
  if (strcmp(err.msg, want) != 0) printf("\n  got:  %s\n  want: %s\n", err.msg, want);
  CU_ASSERT_STRING_EQUAL(err.msg, want);
  sph_yaml_free(root);
}

static const char DOC[] = "name: tank\n"          /* 1 */
                          "size: [1.5, 2]\n"      /* 2 */
                          "walls:\n"              /* 3 */
                          "  left: {layers: 3}\n" /* 4 */
                          "  quoted: '12'\n"      /* 5 */
                          "empty:\n";             /* 6 */

static void test_tree(void) {
  sph_error err = {0};
  sph_yaml_node *root = parse(DOC, &err);
  CU_ASSERT_PTR_NOT_NULL_FATAL(root);
  CU_ASSERT_EQUAL(root->kind, SPH_YAML_MAP);
  CU_ASSERT_EQUAL(root->n, 4);
  const char *keys[] = {"name", "size", "walls", "empty"};
  const size_t lines[] = {1, 2, 3, 6};
  for (size_t i = 0; i < 4; i++) { /* in the order written, with their lines */
    CU_ASSERT_STRING_EQUAL(root->entries[i].key, keys[i]);
    CU_ASSERT_EQUAL(root->entries[i].line, lines[i]);
    CU_ASSERT_EQUAL(root->entries[i].src, SPH_YAML_FROM_FILE);
  }
  const sph_yaml_entry *size = sph_yaml_find(root, "size");
  CU_ASSERT_PTR_NOT_NULL_FATAL(size);
  CU_ASSERT_EQUAL(size->val->kind, SPH_YAML_LIST);
  CU_ASSERT_EQUAL(size->val->n, 2);
  CU_ASSERT_STRING_EQUAL(size->val->items[1]->text, "2");
  CU_ASSERT_TRUE(size->val->items[1]->plain);
  const sph_yaml_node *walls = sph_yaml_find(root, "walls")->val;
  const sph_yaml_node *left = sph_yaml_find(walls, "left")->val;
  CU_ASSERT_EQUAL(left->line, 4);
  CU_ASSERT_STRING_EQUAL(sph_yaml_find(left, "layers")->val->text, "3");
  const sph_yaml_node *quoted = sph_yaml_find(walls, "quoted")->val;
  CU_ASSERT_FALSE(quoted->plain); /* '12' is a string, not a number */
  const sph_yaml_node *empty = sph_yaml_find(root, "empty")->val;
  CU_ASSERT_EQUAL(empty->kind, SPH_YAML_SCALAR);
  CU_ASSERT_STRING_EQUAL(empty->text, "");
  CU_ASSERT_PTR_NULL(sph_yaml_find(root, "nothing"));
  sph_yaml_free(root);

  /* an empty document is YAML's null: an empty plain scalar at line 1 */
  root = parse("", &err);
  CU_ASSERT_PTR_NOT_NULL_FATAL(root);
  CU_ASSERT_EQUAL(root->kind, SPH_YAML_SCALAR);
  CU_ASSERT_TRUE(root->plain);
  CU_ASSERT_STRING_EQUAL(root->text, "");
  CU_ASSERT_EQUAL(root->line, 1);
  sph_yaml_free(root);
}

static void test_refused(void) {
  expect_parse_error("a: 1\nb: 2\na: 3\n", "t.yaml:3: a: duplicate key (first given at line 1)");
  expect_parse_error("a: &x 1\nb: *x\n", "t.yaml:2: b: aliases (*name) are not supported");
  expect_parse_error("a: !point 1\n", "t.yaml:1: a: tags such as '!point' are not supported");
  expect_parse_error("a: 1\n---\nb: 2\n", "t.yaml:3: only one YAML document is allowed");
  expect_parse_error("? [a, b]\n: 1\n", "t.yaml:1: a mapping key must be a plain name");
  expect_parse_error("a: [1, 2\nb: 3\n", "t.yaml:2:2: YAML syntax error: did not find expected "
                                         "',' or ']' (while parsing a flow sequence at line 1, "
                                         "column 4)");
  /* nesting: the top and 64 levels below it are read, one more is refused */
  char deep[400] = "";
  for (int i = 0; i < 65; i++)
    strcat(deep, "[");
  for (int i = 0; i < 65; i++)
    strcat(deep, "]");
  sph_error err = {0};
  sph_yaml_node *root = parse(deep, &err);
  CU_ASSERT_PTR_NOT_NULL(root);
  sph_yaml_free(root);
  char deeper[400] = "[";
  strcat(deeper, deep);
  strcat(deeper, "]");
  expect_parse_error(deeper, "t.yaml:1: nested deeper than 64 levels");
}

static void test_overrides(void) {
  const char *set[] = {"walls.left.layers=4", "walls.right.layers=2", "name.x=1", "noequals",
                       "size=[1, "};
  sph_error err = {0};
  sph_yaml_ctx x = ctx_of(DOC, set, &err);
  sph_yaml_node *root = NULL;
  CU_ASSERT_EQUAL_FATAL(sph_yaml_parse(&x, DOC, strlen(DOC), SPH_YAML_FROM_FILE, NULL, &root), 0);
  /* replaces a value: the new node says which override it came from */
  CU_ASSERT_EQUAL(sph_yaml_apply_set(&x, root, 0), 0);
  const sph_yaml_node *walls = sph_yaml_find(root, "walls")->val;
  const sph_yaml_node *layers = sph_yaml_find(sph_yaml_find(walls, "left")->val, "layers")->val;
  CU_ASSERT_STRING_EQUAL(layers->text, "4");
  CU_ASSERT_EQUAL(layers->src, 0);
  CU_ASSERT_EQUAL(layers->line, 0);
  /* adds a key, creating the mapping on the way */
  CU_ASSERT_EQUAL(sph_yaml_apply_set(&x, root, 1), 0);
  const sph_yaml_entry *right = sph_yaml_find(walls, "right");
  CU_ASSERT_PTR_NOT_NULL_FATAL(right);
  CU_ASSERT_EQUAL(right->src, 1);
  CU_ASSERT_EQUAL(right->val->kind, SPH_YAML_MAP);
  CU_ASSERT_STRING_EQUAL(sph_yaml_find(right->val, "layers")->val->text, "2");
  /* what cannot be set */
  CU_ASSERT_NOT_EQUAL(sph_yaml_apply_set(&x, root, 2), 0);
  CU_ASSERT_STRING_EQUAL(err.msg, "--set name.x=1: name: is 'tank' (line 1), not a mapping, so "
                                  "'x' cannot be set in it");
  CU_ASSERT_NOT_EQUAL(sph_yaml_apply_set(&x, root, 3), 0);
  CU_ASSERT_STRING_EQUAL(err.msg, "--set noequals: expected dotted.key=value (a key such as "
                                  "numerics.dx, then '=', then a YAML value)");
  CU_ASSERT_NOT_EQUAL(sph_yaml_apply_set(&x, root, 4), 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "--set size=[1, : size: YAML syntax error in the value"));
  sph_yaml_free(root);
}

static void test_readers(void) {
  static const char TEXT[] = "pos: 2.5\n"          /* 1 */
                             "neg: -1\n"           /* 2 */
                             "big: 1e400\n"        /* 3 */
                             "hex: 0x10\n"         /* 4 */
                             "str: '7'\n"          /* 5 */
                             "n: 12\n"             /* 6 */
                             "on: true\n"          /* 7 */
                             "yes: yes\n"          /* 8 */
                             "kind: flap\n"        /* 9 */
                             "x: [2, 1]\n"         /* 10 */
                             "y: [0, 1, 2]\n"      /* 11 */
                             "sub: {a: 1, b: 2}\n" /* 12 */
                             "list: [1, 2, 3]\n";  /* 13 */
  sph_error err = {0};
  sph_yaml_ctx x = ctx_of(TEXT, NULL, &err);
  sph_yaml_node *m = parse(TEXT, &err);
  CU_ASSERT_PTR_NOT_NULL_FATAL(m);
  double v = 0.0, pair[2];
  int k = 0;
  CU_ASSERT_EQUAL(sph_yaml_get_number(&x, m, "", "pos", 1, &SPH_YAML_POS, &v), 1);
  CU_ASSERT_DOUBLE_EQUAL(v, 2.5, 0.0);
  CU_ASSERT_EQUAL(sph_yaml_get_number(&x, m, "", "absent", 0, &SPH_YAML_POS, &v), 0);
  CU_ASSERT_EQUAL(sph_yaml_get_number(&x, m, "sec", "absent", 1, &SPH_YAML_POS, &v), -1);
  CU_ASSERT_STRING_EQUAL(err.msg, "t.yaml:1: sec.absent: required key is missing");
  CU_ASSERT_EQUAL(sph_yaml_get_number(&x, m, "", "neg", 1, &SPH_YAML_POS, &v), -1);
  CU_ASSERT_STRING_EQUAL(err.msg, "t.yaml:2: neg: expected a positive number, got '-1'");
  CU_ASSERT_EQUAL(sph_yaml_get_number(&x, m, "", "neg", 1, &SPH_YAML_UNIT, &v), -1);
  CU_ASSERT_STRING_EQUAL(err.msg, "t.yaml:2: neg: expected a number in [0, 1], got '-1'");
  CU_ASSERT_EQUAL(sph_yaml_get_number(&x, m, "", "big", 1, &SPH_YAML_ANY, &v), -1);
  CU_ASSERT_STRING_EQUAL(err.msg, "t.yaml:3: big: expected a number, got '1e400'");
  CU_ASSERT_EQUAL(sph_yaml_get_number(&x, m, "", "hex", 1, &SPH_YAML_ANY, &v), -1);
  CU_ASSERT_EQUAL(sph_yaml_get_number(&x, m, "", "str", 1, &SPH_YAML_ANY, &v), -1);
  CU_ASSERT_STRING_EQUAL(err.msg, "t.yaml:5: str: expected a number, got the string '7'");
  CU_ASSERT_EQUAL(sph_yaml_get_int(&x, m, "", "n", 0, 20, &k), 1);
  CU_ASSERT_EQUAL(k, 12);
  CU_ASSERT_EQUAL(sph_yaml_get_int(&x, m, "", "n", 0, 10, &k), -1);
  CU_ASSERT_STRING_EQUAL(err.msg, "t.yaml:6: n: expected an integer in 0..10, got '12'");
  CU_ASSERT_EQUAL(sph_yaml_get_int(&x, m, "", "pos", 0, 10, &k), -1);
  CU_ASSERT_EQUAL(sph_yaml_get_bool(&x, m, "", "on", &k), 1);
  CU_ASSERT_EQUAL(k, 1);
  CU_ASSERT_EQUAL(sph_yaml_get_bool(&x, m, "", "yes", &k), -1);
  CU_ASSERT_STRING_EQUAL(err.msg, "t.yaml:8: yes: expected true or false, got 'yes'");
  const char *kinds[] = {"piston", "flap", NULL};
  CU_ASSERT_EQUAL(sph_yaml_get_choice(&x, m, "", "kind", kinds, &k), 1);
  CU_ASSERT_EQUAL(k, 1);
  const char *others[] = {"none", "translate", NULL};
  CU_ASSERT_EQUAL(sph_yaml_get_choice(&x, m, "", "kind", others, &k), -1);
  CU_ASSERT_STRING_EQUAL(err.msg, "t.yaml:9: kind: unknown choice 'flap' (valid: none, translate)");
  CU_ASSERT_EQUAL(sph_yaml_get_pair(&x, m, "", "x", 1, 0, pair), 1);
  CU_ASSERT_DOUBLE_EQUAL(pair[0], 2.0, 0.0);
  CU_ASSERT_EQUAL(sph_yaml_get_pair(&x, m, "", "x", 1, 'x', pair), -1);
  CU_ASSERT_STRING_EQUAL(err.msg, "t.yaml:10: x: expected [x0, x1] with x0 < x1, got [2, 1]");
  CU_ASSERT_EQUAL(sph_yaml_get_pair(&x, m, "", "y", 1, 'y', pair), -1);
  CU_ASSERT_STRING_EQUAL(err.msg, "t.yaml:11: y: expected a list of 2 numbers, got a list of 3 "
                                  "items");
  const char *sub_keys[] = {"a", NULL};
  const sph_yaml_node *sub = NULL;
  CU_ASSERT_EQUAL(sph_yaml_get_section(&x, m, "", "sub", 1, sub_keys, &sub), -1);
  CU_ASSERT_STRING_EQUAL(err.msg, "t.yaml:12: sub.b: unknown key (valid keys in 'sub': a)");
  CU_ASSERT_EQUAL(sph_yaml_get_section(&x, m, "", "list", 1, sub_keys, &sub), -1);
  CU_ASSERT_STRING_EQUAL(err.msg, "t.yaml:13: list: expected a mapping, got a list of 3 items");
  char *s = NULL;
  CU_ASSERT_EQUAL(sph_yaml_get_string(&x, m, "str", 1, &s), 1);
  CU_ASSERT_STRING_EQUAL(s, "7");
  CU_ASSERT_EQUAL(sph_yaml_get_string(&x, m, "sub", 1, &s), -1);
  CU_ASSERT_STRING_EQUAL(err.msg, "t.yaml:12: sub: expected a string, got a mapping");
  free(s);
  const char *top[] = {"pos", NULL};
  CU_ASSERT_EQUAL(sph_yaml_check_keys(&x, m, "", top), -1);
  CU_ASSERT_STRING_EQUAL(err.msg, "t.yaml:2: neg: unknown key (valid top-level keys: pos)");
  sph_yaml_free(m);
}

/* What "got ..." says of a node. */
static void test_got(void) {
  sph_error err = {0};
  sph_yaml_node *m = parse("a: {}\n"
                           "b: []\n"
                           "c: [1]\n"
                           "d:\n"
                           "e: \"tab\\there\"\n"
                           "f: 0123456789012345678901234567890123456789012345678901234567890123\n",
                           &err);
  CU_ASSERT_PTR_NOT_NULL_FATAL(m);
  char b[128];
  CU_ASSERT_STRING_EQUAL(sph_yaml_got(sph_yaml_find(m, "a")->val, b, sizeof b), "a mapping");
  CU_ASSERT_STRING_EQUAL(sph_yaml_got(sph_yaml_find(m, "b")->val, b, sizeof b), "an empty list");
  CU_ASSERT_STRING_EQUAL(sph_yaml_got(sph_yaml_find(m, "c")->val, b, sizeof b), "a list of 1 item");
  CU_ASSERT_STRING_EQUAL(sph_yaml_got(sph_yaml_find(m, "d")->val, b, sizeof b), "nothing");
  CU_ASSERT_STRING_EQUAL(sph_yaml_got(sph_yaml_find(m, "e")->val, b, sizeof b),
                         "the string 'tab?here'");
  CU_ASSERT_STRING_EQUAL(sph_yaml_got(sph_yaml_find(m, "f")->val, b, sizeof b),
                         "'012345678901234567890123456789012345678901234567890123456789...'");
  sph_yaml_free(m);
}

/* Every message is one line of valid UTF-8 (core/error.c; issue 39, D8):
 * control bytes become spaces, a byte that is not UTF-8 becomes \xNN,
 * while UTF-8 (two, three and four bytes) passes as it is. */
static void test_message_text(void) {
  sph_error err;
  sph_error_set(&err, "%s: got '%s'", "caf\xe9.yaml",
                "a\nb\x7f\xc3\xa9\xe2\x82\xac\xf0\x9f\x8c\x8a\xff");
  CU_ASSERT_STRING_EQUAL(err.msg,
                         "caf\\xe9.yaml: got 'a b \xc3\xa9\xe2\x82\xac\xf0\x9f\x8c\x8a\\xff'");
  /* sequences cut short, overlong forms and surrogates are not UTF-8 */
  sph_error_set(&err, "%s", "\xc3|\xe2\x82|\xc0\xaf|\xed\xa0\x80|\xf4\x90\x80\x80");
  CU_ASSERT_STRING_EQUAL(err.msg, "\\xc3|\\xe2\\x82|\\xc0\\xaf|\\xed\\xa0\\x80|"
                                  "\\xf4\\x90\\x80\\x80");
  if (strchr(err.msg, '\n')) CU_FAIL("a newline in a message");
}

int main(void) {
  CU_TestInfo tests[] = {
      {"messages: one line of UTF-8, other bytes as \\xNN", test_message_text},
      {"the tree: kinds, order, lines, plain or quoted", test_tree},
      {"refused: duplicates, aliases, tags, documents, keys, depth, syntax", test_refused},
      {"overrides: replace, add, refuse", test_overrides},
      {"typed readers: values and messages", test_readers},
      {"what a node is, for messages", test_got},
      CU_TEST_INFO_NULL};
  return sph_test_main("yaml_tree", tests);
}
