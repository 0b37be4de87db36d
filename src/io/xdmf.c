/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * xdmf.c - the XDMF 3 index of a series of snapshots (see snapshot.h).
 *
 * The index is plain XML that ParaView and VisIt open to see a whole run:
 * one temporal collection holding, per snapshot, a Uniform grid with a
 * Time, a Polyvertex topology (one vertex cell per particle, its
 * connectivity the dataset /particles/id, which is 0..n-1: readers such as
 * ParaView's count cells from the connectivity array and would make none
 * without it), an XY geometry, the n x 2 dataset /vectors/position (one
 * array, as meshio's reader wants: it refused the two-array X_Y), the
 * node-centred Vector Attribute "velocity" (/vectors/velocity, n x 3 with
 * z = 0: ParaView's glyphs take it as it is), and every field (x and y
 * included) as a node-centred scalar Attribute that references
 * "<snapshot>:/particles/<field>". The data stay in the HDF5 files; only
 * their names, particle counts (each snapshot its own: fluid that leaves
 * the domain may be taken out of a run) and times are written here.
 *
 * Invariants: the field list and number types below mirror the snapshot
 * writer (snapshot.c); the file is written to "<path>.tmp" and renamed, and
 * the tmp file is removed on any failure; names are XML-escaped; times are
 * printed with %.17g (round-trip exact) and must be finite. The output
 * depends only on the arguments.
 */
#include "config.h"

#include "io/snapshot.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/snapshot_fields.h"

/* Writes s with the five XML special characters escaped. */
static void put_escaped(FILE *f, const char *s) {
  for (; *s; s++) {
    switch (*s) {
    case '&': fputs("&amp;", f); break;
    case '<': fputs("&lt;", f); break;
    case '>': fputs("&gt;", f); break;
    case '"': fputs("&quot;", f); break;
    case '\'': fputs("&apos;", f); break;
    default: fputc(*s, f);
    }
  }
}

/* A DataItem referencing /particles/<field> of snapshot h5. */
static void put_item(FILE *f, const char *indent, const char *h5, const field_spec *x, size_t n) {
  fprintf(f, "%s<DataItem Dimensions=\"%zu\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">",
          indent, n, field_xdmf_type(x->type), field_bytes(x->type));
  put_escaped(f, h5);
  fprintf(f, ":/particles/%s</DataItem>\n", x->name);
}

/* A DataItem referencing /vectors/<name> (n x cols doubles) of snapshot h5. */
static void put_vector(FILE *f, const char *indent, const char *h5, const char *name, size_t n,
                       int cols) {
  fprintf(f,
          "%s<DataItem Dimensions=\"%zu %d\" NumberType=\"Float\" Precision=\"8\" "
          "Format=\"HDF\">",
          indent, n, cols);
  put_escaped(f, h5);
  fprintf(f, ":/vectors/%s</DataItem>\n", name);
}

/* %.17g whatever LC_NUMERIC says (XML wants a decimal point). */
static void format_time(char *buf, size_t len, double t) {
  snprintf(buf, len, "%.17g", t);
  for (char *c = buf; *c; c++)
    if (*c == ',') *c = '.';
}

static void put_grid(FILE *f, const char *h5, double time, size_t n, int optional) {
  char t[64];
  format_time(t, sizeof t, time);
  fputs("      <Grid Name=\"", f);
  put_escaped(f, h5);
  fputs("\" GridType=\"Uniform\">\n", f);
  fprintf(f, "        <Time Value=\"%s\"/>\n", t);
  fprintf(f,
          "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%zu\" "
          "NodesPerElement=\"1\">\n",
          n);
  put_item(f, "          ", h5, &FIELDS[ID_FIELD], n); /* vertex i is point id[i] = i */
  fputs("        </Topology>\n", f);
  fputs(SPH_DIM == 2 ? "        <Geometry GeometryType=\"XY\">\n"
                     : "        <Geometry GeometryType=\"XYZ\">\n",
        f);
  put_vector(f, "          ", h5, "position", n, SPH_DIM);
  fputs("        </Geometry>\n", f);
  fputs("        <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">\n", f);
  put_vector(f, "          ", h5, "velocity", n, 3);
  fputs("        </Attribute>\n", f);
  for (size_t i = 0; i < N_FIELDS; i++) {
    if ((i == FREE_SURFACE_FIELD && !(optional & SPH_XDMF_FREE_SURFACE)) ||
        (i == PHASE_FIELD && !(optional & SPH_XDMF_PHASE)))
      continue;
    fprintf(f, "        <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Node\">\n",
            FIELDS[i].name);
    put_item(f, "          ", h5, &FIELDS[i], n);
    fputs("        </Attribute>\n", f);
  }
  fputs("      </Grid>\n", f);
}

static void put_document(FILE *f, size_t n_snap, const char *const *h5_names, const double *times,
                         const size_t *n, int optional) {
  fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n", f);
  fputs("<Xdmf Version=\"3.0\">\n", f);
  fputs("  <Domain>\n", f);
  fputs("    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n", f);
  for (size_t i = 0; i < n_snap; i++)
    put_grid(f, h5_names[i], times[i], n[i], optional);
  fputs("    </Grid>\n", f);
  fputs("  </Domain>\n", f);
  fputs("</Xdmf>\n", f);
}

/* Names must be non-empty and free of ':' (which separates the file from
 * the dataset in a DataItem); times must be finite. */
static int check_inputs(const char *xmf_path, size_t n_snap, const char *const *h5_names,
                        const double *times, sph_error *err) {
  for (size_t i = 0; i < n_snap; i++) {
    const char *h5 = h5_names[i];
    if (!h5 || !*h5) return sph_error_set(err, "%s: snapshot %zu has no file name", xmf_path, i);
    if (strchr(h5, ':'))
      return sph_error_set(err,
                           "%s: snapshot file name \"%s\" contains ':', which XDMF "
                           "cannot reference",
                           xmf_path, h5);
    if (!isfinite(times[i]))
      return sph_error_set(err, "%s: snapshot %s has a non-finite time", xmf_path, h5);
  }
  return 0;
}

int sph_xdmf_write(const char *xmf_path, size_t n_snap, const char *const *h5_names,
                   const double *times, const size_t *n_particles, int optional, sph_error *err) {
  if (!xmf_path || !*xmf_path) return sph_error_set(err, "xdmf: empty file name");
  if (check_inputs(xmf_path, n_snap, h5_names, times, err)) return -1;
  size_t len = strlen(xmf_path);
  char *tmp = malloc(len + 5);
  if (!tmp) return sph_error_set(err, "%s: out of memory", xmf_path);
  memcpy(tmp, xmf_path, len);
  memcpy(tmp + len, ".tmp", 5);
  int rc = 0;
  FILE *f = fopen(tmp, "w");
  if (!f) {
    rc = sph_error_set(err, "%s: cannot create %s: %s", xmf_path, tmp, strerror(errno));
    free(tmp);
    return rc;
  }
  put_document(f, n_snap, h5_names, times, n_particles, optional);
  int failed = ferror(f);
  if (fclose(f) != 0 || failed)
    rc = sph_error_set(err, "%s: cannot write %s: %s", xmf_path, tmp, strerror(errno));
  else if (rename(tmp, xmf_path) != 0)
    rc = sph_error_set(err, "%s: cannot rename %s to it: %s", xmf_path, tmp, strerror(errno));
  if (rc != 0) remove(tmp);
  free(tmp);
  return rc;
}
