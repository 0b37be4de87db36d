/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * vtk_out.c - legacy VTK polydata files of triangle meshes (see vtk_out.h).
 */
#include "config.h"

#include "vtk_out.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "atomic_file.h"

/* Big-endian bytes of a 32-bit unsigned integer and of a float, on any host. */
static void put_be32(uint8_t *b, uint32_t v) {
  for (int k = 0; k < 4; k++)
    b[k] = (uint8_t)(v >> (8 * (3 - k)));
}
static void put_be_float(uint8_t *b, float f) {
  uint32_t v;
  memcpy(&v, &f, sizeof v);
  put_be32(b, v);
}

typedef struct vtk_job {
  const rmesh *m;
  const char *field;
  const char *title;
} vtk_job;

/* n floats of a as big-endian bytes. */
static int put_floats(FILE *fp, const float *a, size_t n, char *why, size_t why_size) {
  uint8_t b[4];
  for (size_t i = 0; i < n; i++) {
    put_be_float(b, a[i]);
    if (fwrite(b, 4, 1, fp) != 1) {
      snprintf(why, why_size, "%s", strerror(errno));
      return -1;
    }
  }
  return 0;
}

static int write_body(FILE *fp, const void *ctx, char *why, size_t why_size) {
  const vtk_job *j = ctx;
  const rmesh *m = j->m;
  fprintf(fp,
          "# vtk DataFile Version 3.0\n%.255s\nBINARY\nDATASET UNSTRUCTURED_GRID\n"
          "POINTS %zu float\n",
          j->title, m->nv);
  if (put_floats(fp, m->p, 3 * m->nv, why, why_size)) return -1;
  fprintf(fp, "\nCELLS %zu %zu\n", m->nt, 4 * m->nt);
  uint8_t b[16];
  for (size_t t = 0; t < m->nt; t++) {
    put_be32(b, 3);
    for (int v = 0; v < 3; v++)
      put_be32(b + 4 + 4 * v, m->tri[3 * t + v]);
    if (fwrite(b, 16, 1, fp) != 1) {
      snprintf(why, why_size, "%s", strerror(errno));
      return -1;
    }
  }
  fprintf(fp, "\nCELL_TYPES %zu\n", m->nt);
  for (size_t t = 0; t < m->nt; t++) {
    put_be32(b, 5); /* VTK_TRIANGLE */
    if (fwrite(b, 4, 1, fp) != 1) {
      snprintf(why, why_size, "%s", strerror(errno));
      return -1;
    }
  }
  fprintf(fp, "\nPOINT_DATA %zu\nVECTORS Normals float\n", m->nv);
  if (put_floats(fp, m->normal, 3 * m->nv, why, why_size)) return -1;
  if (j->field && m->val) {
    fprintf(fp, "\nSCALARS %s float 1\nLOOKUP_TABLE default\n", j->field);
    if (put_floats(fp, m->val, m->nv, why, why_size)) return -1;
  }
  fprintf(fp, "\n");
  return 0;
}

int rvtk_write(const char *path, const rmesh *m, const char *field, const char *title,
               sph_error *err) {
  for (const char *c = field; c && *c; c++)
    if (*c == ' ' || *c == '\n' || *c == '\t')
      return sph_error_set(err, "%s: the field's name '%s' cannot be a VTK array's", path, field);
  for (const char *c = title; *c; c++)
    if (*c == '\n') return sph_error_set(err, "%s: a VTK title is one line", path);
  const vtk_job j = {m, field, title};
  return ratomic_write(path, "VTK", write_body, &j, err);
}
