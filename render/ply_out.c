/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ply_out.c - binary PLY files of triangle meshes (see ply_out.h).
 */
#include "config.h"

#include "ply_out.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "atomic_file.h"

/* Little-endian bytes of a float and of a 32-bit unsigned integer, on
 * any host. */
static void put_u32(uint8_t *b, uint32_t v) {
  for (int k = 0; k < 4; k++)
    b[k] = (uint8_t)(v >> (8 * k));
}
static void put_float(uint8_t *b, float f) {
  uint32_t v;
  memcpy(&v, &f, sizeof v);
  put_u32(b, v);
}

static int failed(char *why, size_t why_size) {
  snprintf(why, why_size, "%s", strerror(errno));
  return -1;
}

typedef struct ply_job {
  const rmesh *m;
  const char *field;
  const char *const *comments;
  int n_comments;
} ply_job;

static int write_body(FILE *fp, const void *ctx, char *why, size_t why_size) {
  const ply_job *j = ctx;
  const rmesh *m = j->m;
  const char *field = j->field;
  fprintf(fp, "ply\nformat binary_little_endian 1.0\n");
  for (int c = 0; c < j->n_comments; c++)
    fprintf(fp, "comment %s\n", j->comments[c]);
  fprintf(fp,
          "element vertex %zu\nproperty float x\nproperty float y\nproperty float z\n"
          "property float nx\nproperty float ny\nproperty float nz\n",
          m->nv);
  const int with_val = field && m->val;
  if (with_val) fprintf(fp, "property float %s\n", field);
  fprintf(fp, "element face %zu\nproperty list uchar uint vertex_indices\nend_header\n", m->nt);
  uint8_t b[28];
  for (size_t i = 0; i < m->nv; i++) {
    for (int a = 0; a < 3; a++) {
      put_float(b + 4 * a, m->p[3 * i + a]);
      put_float(b + 12 + 4 * a, m->normal[3 * i + a]);
    }
    if (with_val) put_float(b + 24, m->val[i]);
    if (fwrite(b, with_val ? 28 : 24, 1, fp) != 1) return failed(why, why_size);
  }
  for (size_t t = 0; t < m->nt; t++) {
    b[0] = 3;
    for (int v = 0; v < 3; v++)
      put_u32(b + 1 + 4 * v, m->tri[3 * t + v]);
    if (fwrite(b, 13, 1, fp) != 1) return failed(why, why_size);
  }
  return 0;
}

int rply_write(const char *path, const rmesh *m, const char *field, const char *const *comments,
               int n_comments, sph_error *err) {
  for (const char *c = field; c && *c; c++)
    if (*c == ' ' || *c == '\n')
      return sph_error_set(err, "%s: the field's name '%s' cannot be a PLY property", path, field);
  const ply_job j = {m, field, comments, n_comments};
  return ratomic_write(path, "PLY", write_body, &j, err);
}
