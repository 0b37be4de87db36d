/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * snapshot.c - HDF5 snapshot files: the writer and the reader (snapshot.h).
 *
 * Writing gathers every field into id order (out[id[i]] = field[i]) through
 * one scratch buffer, writes "<path>.tmp" and renames it over path, so a
 * reader never sees a half-written file; on any failure the tmp file is
 * removed. Files are byte-identical for identical inputs: object
 * modification times are switched off for the file, every group and every
 * dataset, file types are fixed little-endian types whatever the host, and
 * nothing about the host, the date or the file name is stored (the bytes
 * may differ between HDF5 library versions, never between runs).
 *
 * A team (the processes of an MPI run, sph_snapshot_write_team) writes one
 * file together through parallel HDF5: each process its rows of every
 * particle dataset, whole chunks in rank order, gathered into id order for
 * those rows only; the file is the bytes a lone writer's serial library
 * writes, because nothing in it depends on when the library places an
 * object (chunks allocated when their dataset is made, attributes and
 * links kept in their object's header; doc/parallel.md).
 *
 * Strings (root and dataset attributes) are scalar fixed-length UTF-8
 * strings in the objects' checksummed headers (a case text longer than a
 * header message holds goes to dense attribute storage). The reader also
 * accepts variable-length strings (earlier files). /particles tracks and
 * indexes link creation order, so its datasets are listed in the order
 * they were written (x y vx vy rho p mass h u kind id [phase] [free_surface]); a
 * file whose group lacks that index is listed in name order.
 *
 * The group /restart (snapshot.h) is written after /particles; its arrays
 * are in storage order, raw. The reader checks everything a restart will
 * index with: the shape of each array, and that order is a permutation.
 *
 * HDF5 error printing is switched off inside every public function (and
 * restored on return); each HDF5 failure becomes one sph_error line naming
 * the file, the object and, in brackets, HDF5's innermost reason. The
 * serial HDF5 library is not thread-safe: call these from one thread.
 */
#include "config.h"

#include "io/snapshot.h"

#include <errno.h>
#include <hdf5.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/version.h"

/* ------------------------------------------------------------------------ */
/* The fields of a snapshot and where they live in the particle store.      */

#include "io/geometry_group.h"
#include "io/snapshot_fields.h"

/* The string attributes of "/" the reader keeps (snapshot.h). */
static const char *const TEXTS[] = {"case_name", "case_text",      "overrides", "parameters",
                                    "version",   "configure_args", "compiler",  "kernel"};
#define N_TEXTS (sizeof TEXTS / sizeof TEXTS[0])

static hid_t file_type(field_type t) {
  switch (t) {
  case FT_F64: return H5T_IEEE_F64LE;
  case FT_I32: return H5T_STD_I32LE;
  case FT_I64: return H5T_STD_I64LE;
  case FT_U8: return H5T_STD_U8LE;
  }
  return -1;
}

static hid_t mem_type(field_type t) {
  switch (t) {
  case FT_F64: return H5T_NATIVE_DOUBLE;
  case FT_I32: return H5T_NATIVE_INT32;
  case FT_I64: return H5T_NATIVE_INT64;
  case FT_U8: return H5T_NATIVE_UINT8;
  }
  return -1;
}

/* The store's array for field f (as void *: its type is f->type). */
static void *member_array(const sph_particles *p, const field_spec *f) {
  const void *slot = (const char *)p + f->member;
  switch (f->type) {
  case FT_F64: return *(double *const *)slot;
  case FT_I32: return *(int32_t *const *)slot;
  case FT_I64: return *(int64_t *const *)slot;
  case FT_U8: return *(uint8_t *const *)slot;
  }
  return NULL;
}

/* ------------------------------------------------------------------------ */
/* HDF5 error handling.                                                     */

typedef struct h5_quiet {
  H5E_auto2_t func;
  void *data;
} h5_quiet;

static void quiet_begin(h5_quiet *q) {
  q->func = NULL;
  q->data = NULL;
  H5Eget_auto2(H5E_DEFAULT, &q->func, &q->data);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
}

static void quiet_end(const h5_quiet *q) { H5Eset_auto2(H5E_DEFAULT, q->func, q->data); }

#define REASON_LEN 200

/* The innermost HDF5 error's description, made readable: a low-level I/O
 * failure ("file write failed: time = ..., filename = ..., file descriptor
 * = 4, errno = 27, error message = 'File too large', buf = 0x...") becomes
 * "file write failed: File too large" (issue 21, D10). */
static herr_t take_innermost(unsigned n, const H5E_error2_t *e, void *data) {
  if (n != 0 || !e->desc || !e->desc[0]) return 0;
  char *out = data;
  snprintf(out, REASON_LEN, "%s", e->desc);
  char *t = strstr(out, "time = ");
  if (!t) return 0;
  while (t > out && (t[-1] == ' ' || t[-1] == ',' || t[-1] == ':'))
    t--;
  *t = '\0';
  const char *m = strstr(e->desc, "error message = '");
  if (m) {
    m += strlen("error message = '");
    const size_t len = strcspn(m, "'");
    const size_t used = strlen(out);
    snprintf(out + used, REASON_LEN - used, ": %.*s", (int)len, m);
  }
  return 0;
}

/* HDF5 cleans up at exit; after a close that failed (a full disk) it
 * tries to flush the file again there and crashes (SIGSEGV in
 * H5_term_library, issue 21, D1). Every file this library opens is closed
 * or abandoned (its .tmp removed) before it returns, so the clean-up at
 * exit has nothing to do: it is switched off before the first HDF5 call. */
__attribute__((constructor)) static void no_hdf5_cleanup_at_exit(void) { H5dont_atexit(); }

/* Formats "<path>: <what> (HDF5: <reason>)" from the error stack of the
 * HDF5 call that just failed; returns -1. */
static int h5_fail(sph_error *err, const char *path, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static int h5_fail(sph_error *err, const char *path, const char *fmt, ...) {
  char what[600], reason[REASON_LEN] = "";
  va_list ap;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, take_innermost, reason);
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  if (reason[0]) return sph_error_set(err, "%s: %s (HDF5: %s)", path, what, reason);
  return sph_error_set(err, "%s: %s", path, what);
}

static void close_id(hid_t id) {
  if (id >= 0) H5Idec_ref(id);
}

/* ------------------------------------------------------------------------ */
/* Writing.                                                                 */

typedef struct writer {
  const char *path; /* the final name, used in messages */
  hid_t file;
  sph_error *err;
  /* with a team (sph_snapshot_write_team), this process's rows k0..k1 of
   * every particle dataset and the collective transfer; alone, 0..n and
   * the default transfer */
  const sph_snapshot_team *team;
  size_t k0, k1;
  hid_t xfer;
  void *buf; /* room for rows k0..k1 of any dataset */
} writer;

/* Attributes and links an object keeps in its own header (compact) before
 * it moves them to dense storage. Dense storage is a fractal heap, which
 * the serial HDF5 library places in the file when it closes it and the
 * parallel one when it makes the heap: the same objects at other
 * addresses, so a team's file would not be a lone writer's bytes. No
 * object of a snapshot has this many, and a text too long for a header
 * (SPH_SNAPSHOT_TEXT_MAX) makes the team's first process write alone. */
#define SPH_SNAPSHOT_COMPACT 64
#define SPH_SNAPSHOT_TEXT_MAX (65536 - 1024)

/* A creation property list of class cls that records no times and keeps
 * its object's attributes (and a group's links) compact. */
static hid_t timeless(hid_t cls) {
  hid_t pl = H5Pcreate(cls);
  if (pl >= 0 &&
      (H5Pset_obj_track_times(pl, 0) < 0 ||
       H5Pset_attr_phase_change(pl, SPH_SNAPSHOT_COMPACT, 0) < 0 ||
       (cls != H5P_DATASET_CREATE && H5Pset_link_phase_change(pl, SPH_SNAPSHOT_COMPACT, 0) < 0))) {
    H5Pclose(pl);
    return -1;
  }
  return pl;
}

/* With a team, rc agreed in one collective step: 0 on every process, or
 * -1 on every one with the message of the first that failed. Alone, rc. */
static int agreed(const writer *w, int rc) { return w->team ? w->team->agree(rc, w->err) : rc; }

/* A text attribute as a fixed-length, NUL-terminated UTF-8 string, which
 * HDF5 keeps in the object's (checksummed) header or dense attribute
 * storage: a variable-length string would live in the global heap, which
 * has no checksum, and a damaged heap can crash HDF5 while it reads
 * (issue 21, D9). */
static int put_text(writer *w, hid_t obj, const char *where, const char *name, const char *value) {
  const size_t len = strlen(value);
  hid_t type = H5Tcopy(H5T_C_S1);
  if (type >= 0 && (H5Tset_size(type, len + 1) < 0 || H5Tset_cset(type, H5T_CSET_UTF8) < 0 ||
                    H5Tset_strpad(type, H5T_STR_NULLTERM) < 0)) {
    close_id(type);
    type = -1;
  }
  hid_t space = type < 0 ? -1 : H5Screate(H5S_SCALAR);
  hid_t attr = space < 0 ? -1 : H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  int rc = 0;
  if (attr < 0 || H5Awrite(attr, type, value) < 0)
    rc = h5_fail(w->err, w->path, "cannot write attribute \"%s\" of %s", name, where);
  close_id(attr);
  close_id(space);
  close_id(type);
  return rc;
}

/* n values of memory type mtype, stored as ftype: a scalar when n == 1. */
static int put_numbers(writer *w, hid_t obj, const char *where, const char *name, hid_t ftype,
                       hid_t mtype, const void *values, size_t n) {
  hsize_t dims[1] = {n};
  hid_t space = n == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, dims, NULL);
  hid_t attr = space < 0 ? -1 : H5Acreate2(obj, name, ftype, space, H5P_DEFAULT, H5P_DEFAULT);
  int rc = 0;
  if (attr < 0 || H5Awrite(attr, mtype, values) < 0)
    rc = h5_fail(w->err, w->path, "cannot write attribute \"%s\" of %s", name, where);
  close_id(attr);
  close_id(space);
  return rc;
}

static int put_double(writer *w, const char *name, double v) {
  return put_numbers(w, w->file, "/", name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &v, 1);
}

static int put_int64(writer *w, const char *name, int64_t v) {
  return put_numbers(w, w->file, "/", name, H5T_STD_I64LE, H5T_NATIVE_INT64, &v, 1);
}

static const char *or_empty(const char *s) { return s ? s : ""; }

/* The root's text attributes, in the order of TEXTS. */
static void root_texts(const sph_snapshot_meta *meta, const char *texts[N_TEXTS]) {
  const char *t[N_TEXTS] = {meta->case_name,
                            or_empty(meta->case_text),
                            or_empty(meta->overrides),
                            or_empty(meta->parameters),
                            sph_version(),
                            sph_configure_args(),
                            sph_compiler(),
                            or_empty(meta->kernel)};
  memcpy(texts, t, sizeof t);
}

static int write_header(writer *w, const sph_snapshot_meta *meta, size_t n) {
  if (put_double(w, "time", meta->time) || put_int64(w, "step", meta->step) ||
      put_double(w, "dt", meta->dt) || put_int64(w, "particle_count", (int64_t)n))
    return -1;
  const char *texts[N_TEXTS];
  root_texts(meta, texts);
  for (size_t i = 0; i < N_TEXTS; i++)
    if (put_text(w, w->file, "/", TEXTS[i], texts[i])) return -1;
  if (put_double(w, "dx", meta->dx) || put_double(w, "h", meta->h) ||
      put_double(w, "rho0", meta->rho0))
    return -1;
#if SPH_DIM == 3 /* (absent: 2, as every file written before 3-D ones existed) */
  if (put_int64(w, "dimension", 3)) return -1;
#endif
  return put_numbers(w, w->file, "/", "view", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, meta->view,
                     2 * SPH_DIM);
}

/* pos[k] = storage index of the particle with id k; checks that id is a
 * permutation of 0..n-1. */
static int id_positions(const sph_particles *p, const char *path, size_t **out, sph_error *err) {
  size_t n = p->n;
  size_t *pos = malloc((n ? n : 1) * sizeof *pos);
  if (!pos) return sph_error_set(err, "%s: out of memory for %zu particles", path, n);
  for (size_t k = 0; k < n; k++)
    pos[k] = (size_t)-1;
  for (size_t i = 0; i < n; i++) {
    int64_t id = p->id[i];
    const char *bad = NULL;
    if (id < 0 || (uint64_t)id >= n)
      bad = "outside 0..n-1";
    else if (pos[id] != (size_t)-1)
      bad = "a duplicate";
    if (bad) {
      free(pos);
      return sph_error_set(err, "%s: particle at storage index %zu has id %lld, %s (n = %zu)", path,
                           i, (long long)id, bad, n);
    }
    pos[id] = i;
  }
  *out = pos;
  return 0;
}

/* buf[k - k0] = field f of the particle with id k, k = k0..k1. */
static void gather(const sph_particles *p, const field_spec *f, const size_t *pos, size_t k0,
                   size_t k1, void *buf) {
  const void *src = member_array(p, f);
  switch (f->type) {
  case FT_F64:
    for (size_t k = k0; k < k1; k++)
      ((double *)buf)[k - k0] = ((const double *)src)[pos[k]];
    break;
  case FT_I32:
    for (size_t k = k0; k < k1; k++)
      ((int32_t *)buf)[k - k0] = ((const int32_t *)src)[pos[k]];
    break;
  case FT_I64:
    for (size_t k = k0; k < k1; k++)
      ((int64_t *)buf)[k - k0] = ((const int64_t *)src)[pos[k]];
    break;
  case FT_U8: { /* free_surface: flags bit 0; phase as it is */
    const uint8_t mask = f->member == offsetof(sph_particles, flags) ? 1u : 0xffu;
    for (size_t k = k0; k < k1; k++)
      ((uint8_t *)buf)[k - k0] = ((const uint8_t *)src)[pos[k]] & mask;
    break;
  }
  }
}

/* The creation properties of a dataset of n rows of cols values (cols =
 * 0: a 1-D dataset): no times, and for n > 0 chunked with HDF5's
 * Fletcher-32 checksum, which every read checks, so damage to the data is
 * an error rather than a changed value (issue 21, D9). Chunks of up to
 * SPH_SNAPSHOT_CHUNK rows. The chunks' space is taken when the dataset is
 * made (the parallel library's only way): a lone writer then places them
 * where a team does. */
#define SPH_SNAPSHOT_CHUNK 65536
static hid_t data_properties(size_t n, size_t cols) {
  hid_t dcpl = timeless(H5P_DATASET_CREATE);
  if (dcpl < 0 || n == 0) return dcpl;
  const hsize_t chunk[2] = {n < SPH_SNAPSHOT_CHUNK ? n : SPH_SNAPSHOT_CHUNK, cols};
  if (H5Pset_chunk(dcpl, cols ? 2 : 1, chunk) < 0 || H5Pset_fletcher32(dcpl) < 0 ||
      H5Pset_alloc_time(dcpl, H5D_ALLOC_TIME_EARLY) < 0) {
    H5Pclose(dcpl);
    return -1;
  }
  return dcpl;
}

/* Writes dataset dset (n rows of cols values, cols = 0 for a 1-D one)
 * from buf, which holds this writer's rows k0..k1: alone all of them;
 * with a team, each process its own rows in one collective step (a
 * process without rows takes part with none). */
static int write_rows(const writer *w, hid_t dset, hid_t mtype, const void *buf, size_t cols,
                      const char *where) {
  int rc = 0;
  if (!w->team) {
    if (H5Dwrite(dset, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0)
      rc = h5_fail(w->err, w->path, "cannot write dataset %s", where);
    return rc;
  }
  const int dims = cols ? 2 : 1;
  const hsize_t start[2] = {w->k0, 0}, count[2] = {w->k1 - w->k0, cols};
  hid_t file_space = H5Dget_space(dset);
  hid_t mem_space = H5Screate_simple(dims, count, NULL);
  if (file_space < 0 || mem_space < 0 ||
      (count[0] == 0
           ? H5Sselect_none(file_space) < 0 || H5Sselect_none(mem_space) < 0
           : H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start, NULL, count, NULL) < 0))
    rc = h5_fail(w->err, w->path, "cannot select the rows of dataset %s", where);
  if (agreed(w, rc) == 0 && H5Dwrite(dset, mtype, mem_space, file_space, w->xfer, buf) < 0)
    rc = h5_fail(w->err, w->path, "cannot write dataset %s", where);
  close_id(mem_space);
  close_id(file_space);
  return agreed(w, rc);
}

/* Makes dataset name of group (n rows of cols values of file type ftype;
 * cols = 0: 1-D) and writes it from rows, this writer's rows k0..k1 in
 * memory type mtype; *dset is the open dataset (the caller closes it) or
 * -1. With a team each step is agreed: its processes go on or stop
 * together, none left waiting in a collective step. */
static int put_dataset(writer *w, hid_t group, const char *name, const char *where, hid_t ftype,
                       hid_t mtype, const void *rows, size_t n, size_t cols, hid_t *dset) {
  const hsize_t dims[2] = {n, cols};
  hid_t dcpl = data_properties(n, cols);
  hid_t space = dcpl < 0 ? -1 : H5Screate_simple(cols ? 2 : 1, dims, NULL);
  *dset = space < 0 ? -1 : H5Dcreate2(group, name, ftype, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  /* (HDF5's reason read before the next call clears it) */
  int rc = *dset < 0 ? h5_fail(w->err, w->path, "cannot create dataset %s", where) : 0;
  close_id(space);
  close_id(dcpl);
  if (agreed(w, rc)) return -1;
  return n > 0 ? write_rows(w, *dset, mtype, rows, cols, where) : 0;
}

static int write_field(writer *w, hid_t group, const field_spec *f, const void *buf, size_t n) {
  char where[64];
  snprintf(where, sizeof where, "/particles/%s", f->name);
  hid_t dset;
  int rc = put_dataset(w, group, f->name, where, file_type(f->type), mem_type(f->type), buf, n, 0,
                       &dset);
  if (rc == 0 && (put_text(w, dset, where, "units", f->units) ||
                  put_text(w, dset, where, "description", f->description)))
    rc = -1;
  close_id(dset);
  return rc;
}

static int write_particles(writer *w, const sph_particles *p, int free_surface, int phase,
                           const size_t *pos) {
  const size_t n = p->n;
  void *buf = w->buf;
  /* links kept in the group's header (compact, up to 32), in creation order */
  hid_t gcpl = timeless(H5P_GROUP_CREATE);
  if (gcpl >= 0 &&
      (H5Pset_link_creation_order(gcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED) < 0 ||
       H5Pset_link_phase_change(gcpl, 32, 24) < 0)) {
    H5Pclose(gcpl);
    gcpl = -1;
  }
  hid_t group = gcpl < 0 ? -1 : H5Gcreate2(w->file, "particles", H5P_DEFAULT, gcpl, H5P_DEFAULT);
  int rc = 0;
  if (agreed(w, group < 0 ? h5_fail(w->err, w->path, "cannot create group /particles") : 0))
    rc = -1;
  for (size_t i = 0; rc == 0 && i < N_FIELDS; i++) {
    if ((i == FREE_SURFACE_FIELD && !free_surface) || (i == PHASE_FIELD && !phase)) continue;
    gather(p, &FIELDS[i], pos, w->k0, w->k1, buf);
    rc = write_field(w, group, &FIELDS[i], buf, n);
  }
  close_id(group);
  close_id(gcpl);
  return rc;
}

/* The group /vectors: position (n x 2: x, y; n x 3 in 3-D) and velocity
 * (n x 3: vx, vy, 0; vx, vy, vz in 3-D), the values of /particles/x, y, vx,
 * vy (z, vz) in the same (id) order, as the readers that take vectors want
 * them: the XDMF index's XY (XYZ) geometry and
 * velocity vector (ParaView's glyphs need three components; meshio reads
 * one dataset per geometry). Chunked and checksummed like the fields. */
static int write_vectors(writer *w, const sph_particles *p, const size_t *pos) {
  const size_t n = p->n;
  double *buf = w->buf;
  hid_t gcpl = timeless(H5P_GROUP_CREATE);
  hid_t g = gcpl < 0 ? -1 : H5Gcreate2(w->file, "vectors", H5P_DEFAULT, gcpl, H5P_DEFAULT);
  close_id(gcpl);
  int rc = agreed(w, g < 0 ? h5_fail(w->err, w->path, "cannot create group /vectors") : 0);
  static const char *const name[2] = {"position", "velocity"};
  static const char *const units[2] = {"m", "m/s"};
#if SPH_DIM == 2
  static const char *const what[2] = {"position (x, y): /particles/x and y as one array",
                                      "velocity (vx, vy, 0): /particles/vx and vy as one "
                                      "array, z = 0"};
#else
  static const char *const what[2] = {"position (x, y, z): /particles/x, y and z as one array",
                                      "velocity (vx, vy, vz): /particles/vx, vy and vz as one "
                                      "array"};
#endif
  for (int v = 0; rc == 0 && v < 2; v++) {
    const hsize_t cols = v == 0 ? SPH_DIM : 3;
    double *const *src = v == 0 ? p->pos : p->vel;
    for (size_t k = w->k0; k < w->k1; k++)
      for (hsize_t d = 0; d < cols; d++)
        buf[(k - w->k0) * cols + d] = d < SPH_DIM ? src[d][pos[k]] : 0.0;
    char where[64];
    snprintf(where, sizeof where, "/vectors/%s", name[v]);
    hid_t dset;
    rc = put_dataset(w, g, name[v], where, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, buf, n, cols, &dset);
    if (rc == 0 && (put_text(w, dset, where, "units", units[v]) ||
                    put_text(w, dset, where, "description", what[v])))
      rc = -1;
    close_id(dset);
  }
  close_id(g);
  return rc;
}

/* A 1-D dataset of n raw values (storage order) in the /restart group,
 * of size bytes each (this writer's rows of them: from k0 on). */
static int write_raw(writer *w, hid_t group, const char *name, hid_t ftype, hid_t mtype,
                     const void *values, size_t size, size_t n) {
  char where[64];
  snprintf(where, sizeof where, "/restart/%s", name);
  hid_t dset;
  const int rc = put_dataset(w, group, name, where, ftype, mtype,
                             (const char *)values + w->k0 * size, n, 0, &dset);
  close_id(dset);
  return rc;
}

/* The group /restart (snapshot.h, sph_snapshot_restart). */
static int write_restart(writer *w, const sph_snapshot_restart *r, size_t n) {
  hid_t gcpl = timeless(H5P_GROUP_CREATE);
  hid_t g = gcpl < 0 ? -1 : H5Gcreate2(w->file, "restart", H5P_DEFAULT, gcpl, H5P_DEFAULT);
  close_id(gcpl);
  if (agreed(w, g < 0 ? h5_fail(w->err, w->path, "cannot create group /restart") : 0)) {
    close_id(g);
    return -1;
  }
  const int64_t format = 1;
  int rc = put_numbers(w, g, "/restart", "format", H5T_STD_I64LE, H5T_NATIVE_INT64, &format, 1) ||
           put_numbers(w, g, "/restart", "output_index", H5T_STD_I64LE, H5T_NATIVE_INT64,
                       &r->output_index, 1) ||
           put_numbers(w, g, "/restart", "first_step", H5T_STD_I64LE, H5T_NATIVE_INT64,
                       &r->first_step, 1) ||
           put_numbers(w, g, "/restart", "ledger", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, r->ledger,
                       2 + SPH_DIM);
  if (rc == 0 && r->has_diffusion)
    rc = put_numbers(w, g, "/restart", "ledger_diffusion", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                     &r->ledger_diffusion, 1);
  if (rc == 0 && r->has_shifting)
    rc = put_numbers(w, g, "/restart", "ledger_shifting", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                     &r->ledger_shifting, 1);
  if (rc == 0 && r->n_levels > 0)
    rc = put_numbers(w, g, "/restart", "gauge_levels", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, r->levels,
                     r->n_levels);
  if (rc == 0 && r->n_filters > 0)
    rc = put_numbers(w, g, "/restart", "probe_filters", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                     r->filters, r->n_filters);
  if (rc == 0 && r->has_outflow)
    rc = put_numbers(w, g, "/restart", "outflow", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, r->outflow,
                     3 + SPH_DIM);
  rc = agreed(w, rc);
  if (rc == 0 && r->origin)
    rc = write_raw(w, g, "origin", H5T_STD_I64LE, H5T_NATIVE_INT64, r->origin, sizeof(int64_t), n);
  if (rc == 0 && !r->order)
    rc = sph_error_set(w->err, "%s: restart record without the storage order", w->path);
  if (rc == 0)
    rc = write_raw(w, g, "order", H5T_STD_I64LE, H5T_NATIVE_INT64, r->order, sizeof(int64_t), n);
  const char *names[] = {"vxh", "vyh", "rhoh", "uh", SPH_IF3("vzh")};
  const double *half[] = {r->vxh, r->vyh, r->rhoh, r->uh, SPH_IF3(r->vzh)};
  for (int k = 0; rc == 0 && k < (int)(sizeof half / sizeof half[0]); k++)
    if (half[k])
      rc = write_raw(w, g, names[k], H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, half[k], sizeof(double), n);
  close_id(g);
  return rc ? -1 : 0;
}

/* Creates the tmp file and writes everything; closes it. */
static int write_file(writer *w, const char *tmp, const sph_snapshot_meta *meta,
                      const sph_particles *p, const size_t *pos) {
  hid_t fcpl = timeless(H5P_FILE_CREATE);
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  /* the HDF5 1.10 file format: object headers, links and the chunk
   * indexes carry checksums of their own (readable by HDF5 1.10 and later:
   * Debian 12 ships 1.10.8) */
  int rc = fcpl < 0 || fapl < 0 || H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG) < 0 ||
                   H5Pset_libver_bounds(fapl, H5F_LIBVER_V110, H5F_LIBVER_V110) < 0
               ? h5_fail(w->err, w->path, "cannot set up HDF5 property lists")
               : 0;
#ifdef H5_HAVE_PARALLEL
  /* a team: the file opened by all its processes through MPI-IO, and every
   * particle dataset written by all of them at once */
  if (rc == 0 && w->team &&
      (H5Pset_fapl_mpio(fapl, MPI_COMM_WORLD, MPI_INFO_NULL) < 0 ||
       (w->xfer = H5Pcreate(H5P_DATASET_XFER)) < 0 ||
       H5Pset_dxpl_mpio(w->xfer, H5FD_MPIO_COLLECTIVE) < 0))
    rc = h5_fail(w->err, w->path, "cannot set up the processes' HDF5 property lists");
#endif
  if (rc == 0) w->file = H5Fcreate(tmp, H5F_ACC_TRUNC, fcpl, fapl);
  if (rc == 0 && w->file < 0) rc = h5_fail(w->err, w->path, "cannot create %s", tmp);
  close_id(fcpl);
  close_id(fapl);
  if (agreed(w, rc)) return -1;
  rc = agreed(w, write_header(w, meta, p->n));
  if (rc == 0)
    rc = write_particles(w, p, meta->free_surface, (p->live & SPH_ARRAYS_PHASE) != 0, pos);
  if (rc == 0) rc = write_vectors(w, p, pos);
  if (rc == 0 && meta->restart) rc = write_restart(w, meta->restart, p->n);
  if (rc == 0 && meta->geometry)
    rc = agreed(w, sph_geometry_group_write(w->file, meta->geometry, w->path,
                                            !w->team || w->team->rank == 0, w->err));
  if (H5Fclose(w->file) < 0 && rc == 0) rc = h5_fail(w->err, w->path, "cannot close %s", tmp);
  return agreed(w, rc);
}

/* Whether some root text is too long for an attribute in the root's
 * header (SPH_SNAPSHOT_TEXT_MAX). */
static int long_texts(const sph_snapshot_meta *meta) {
  const char *texts[N_TEXTS];
  root_texts(meta, texts);
  for (size_t i = 0; i < N_TEXTS; i++)
    if (strlen(texts[i]) >= SPH_SNAPSHOT_TEXT_MAX) return 1;
  return 0;
}

/* This process's rows of n with a team of count: the processes' shares
 * of whole chunks (SPH_SNAPSHOT_CHUNK), in rank order. */
static void team_rows(size_t n, int rank, int count, size_t *k0, size_t *k1) {
  const size_t chunks = (n + SPH_SNAPSHOT_CHUNK - 1) / SPH_SNAPSHOT_CHUNK;
  const size_t c0 = chunks * (size_t)rank / (size_t)count;
  const size_t c1 = chunks * ((size_t)rank + 1) / (size_t)count;
  *k0 = c0 * SPH_SNAPSHOT_CHUNK < n ? c0 * SPH_SNAPSHOT_CHUNK : n;
  *k1 = c1 * SPH_SNAPSHOT_CHUNK < n ? c1 * SPH_SNAPSHOT_CHUNK : n;
}

int sph_snapshot_write(const char *path, const sph_snapshot_meta *meta, const sph_particles *p,
                       sph_error *err) {
  return sph_snapshot_write_team(path, meta, p, NULL, err);
}

int sph_snapshot_write_team(const char *path, const sph_snapshot_meta *meta, const sph_particles *p,
                            const sph_snapshot_team *team, sph_error *err) {
  if (team && team->count <= 1) team = NULL;
  /* the arguments are every process's same (the store is whole on each) */
  if (!path || !*path) return sph_error_set(err, "snapshot: empty file name");
  if (!p) return sph_error_set(err, "%s: no particles to write", path);
  if (!meta || !meta->case_name)
    return sph_error_set(err, "%s: snapshot metadata without a case name", path);
  int lone = team && long_texts(meta); /* the team's first process writes alone */
#ifndef H5_HAVE_PARALLEL
  lone = team != NULL;
#endif
  if (lone && team->rank != 0) return 0;
  if (lone) team = NULL;
  writer w = {path, -1, err, team, 0, p->n, H5P_DEFAULT, NULL};
  if (team) team_rows(p->n, team->rank, team->count, &w.k0, &w.k1);
  const size_t len = strlen(path), rows = w.k1 - w.k0;
  char *tmp = malloc(len + 5);
  size_t *pos = NULL;
  int rc = tmp ? id_positions(p, path, &pos, err) : sph_error_set(err, "%s: out of memory", path);
  /* room for this writer's rows of the widest dataset (a vector's 3 doubles) */
  if (rc == 0 && !(w.buf = malloc((rows ? rows : 1) * 3 * sizeof(double))))
    rc = sph_error_set(err, "%s: out of memory for %zu particles", path, rows);
  if (agreed(&w, rc) == 0) {
    memcpy(tmp, path, len);
    memcpy(tmp + len, ".tmp", 5);
    h5_quiet q;
    quiet_begin(&q);
    rc = write_file(&w, tmp, meta, p, pos);
    if (w.xfer != H5P_DEFAULT) close_id(w.xfer);
    quiet_end(&q);
    const int first = !team || team->rank == 0; /* renames or removes the file */
    if (first && rc == 0 && rename(tmp, path) != 0)
      rc = sph_error_set(err, "%s: cannot rename %s to it: %s", path, tmp, strerror(errno));
    if (first && rc != 0) remove(tmp);
  } else
    rc = -1;
  free(w.buf);
  free(pos);
  free(tmp);
  return rc;
}

/* ------------------------------------------------------------------------ */
/* Reading.                                                                 */

struct sph_snapshot {
  char *path;
  hid_t file, group; /* the file and its /particles */
  double time, dt;
  int64_t step;
  size_t count;
  char *text[N_TEXTS]; /* NULL when absent */
  size_t n_fields;
  char **fields; /* dataset names in file order */
  int dim;       /* its attribute "dimension" (2 when absent) */
};

static char *dup_string(const char *s) {
  size_t len = strlen(s) + 1;
  char *d = malloc(len);
  if (d) memcpy(d, s, len);
  return d;
}

static int is_numeric(hid_t type) {
  H5T_class_t c = H5Tget_class(type);
  return c == H5T_INTEGER || c == H5T_FLOAT;
}

/* Reads the numeric attribute name of obj (called where in messages;
 * exactly n values) as mtype. */
static int get_numbers_of(const sph_snapshot *s, hid_t obj, const char *where, const char *name,
                          hid_t mtype, void *out, size_t n, sph_error *err) {
  htri_t there = H5Aexists(obj, name);
  if (there < 0)
    return h5_fail(err, s->path, "cannot look for attribute \"%s\" on %s", name, where);
  if (there == 0)
    return sph_error_set(err, "%s: missing attribute \"%s\" on %s", s->path, name, where);
  hid_t attr = H5Aopen(obj, name, H5P_DEFAULT);
  hid_t type = attr < 0 ? -1 : H5Aget_type(attr);
  hid_t space = attr < 0 ? -1 : H5Aget_space(attr);
  int rc = 0;
  if (type < 0 || space < 0) {
    rc = h5_fail(err, s->path, "cannot open attribute \"%s\" on %s", name, where);
  } else if (!is_numeric(type)) {
    rc = sph_error_set(err, "%s: attribute \"%s\" on %s is not a number", s->path, name, where);
  } else {
    hssize_t got = H5Sget_simple_extent_npoints(space);
    if (got != (hssize_t)n)
      rc = sph_error_set(err, "%s: attribute \"%s\" on %s has %lld values, expected %zu", s->path,
                         name, where, (long long)got, n);
    else if (H5Aread(attr, mtype, out) < 0)
      rc = h5_fail(err, s->path, "cannot read attribute \"%s\" on %s", name, where);
  }
  close_id(space);
  close_id(type);
  close_id(attr);
  return rc;
}

static int get_numbers(const sph_snapshot *s, const char *name, hid_t mtype, void *out, size_t n,
                       sph_error *err) {
  return get_numbers_of(s, s->file, "/", name, mtype, out, n, err);
}

/* A string attribute's value, variable- or fixed-length, into a malloc'd
 * string. */
static int read_string(const sph_snapshot *s, hid_t attr, hid_t type, const char *where,
                       const char *name, char **out, sph_error *err) {
  if (H5Tis_variable_str(type) > 0) {
    hid_t mtype = H5Tcopy(H5T_C_S1);
    hid_t space = H5Aget_space(attr);
    char *v = NULL;
    int rc = 0;
    if (mtype < 0 || space < 0 || H5Tset_size(mtype, H5T_VARIABLE) < 0 ||
        H5Tset_cset(mtype, H5Tget_cset(type)) < 0 || H5Aread(attr, mtype, &v) < 0)
      rc = h5_fail(err, s->path, "cannot read attribute \"%s\" on %s", name, where);
    else if (!(*out = dup_string(v ? v : "")))
      rc = sph_error_set(err, "%s: out of memory", s->path);
    if (v) H5Dvlen_reclaim(mtype, space, H5P_DEFAULT, &v);
    close_id(space);
    close_id(mtype);
    return rc;
  }
  size_t size = H5Tget_size(type);
  char *buf = calloc(size + 1, 1);
  if (!buf) return sph_error_set(err, "%s: out of memory", s->path);
  if (H5Aread(attr, type, buf) < 0) {
    free(buf);
    return h5_fail(err, s->path, "cannot read attribute \"%s\" on %s", name, where);
  }
  if (H5Tget_strpad(type) == H5T_STR_SPACEPAD)
    for (size_t k = size; k > 0 && buf[k - 1] == ' '; k--)
      buf[k - 1] = '\0';
  *out = buf;
  return 0;
}

/* Reads the string attribute name of obj (called where in messages) into
 * *out (NULL if absent and not required). */
static int get_text_of(const sph_snapshot *s, hid_t obj, const char *where, const char *name,
                       int required, char **out, sph_error *err) {
  *out = NULL;
  htri_t there = H5Aexists(obj, name);
  if (there < 0)
    return h5_fail(err, s->path, "cannot look for attribute \"%s\" on %s", name, where);
  if (there == 0)
    return required ? sph_error_set(err, "%s: missing attribute \"%s\" on %s", s->path, name, where)
                    : 0;
  hid_t attr = H5Aopen(obj, name, H5P_DEFAULT);
  hid_t type = attr < 0 ? -1 : H5Aget_type(attr);
  hid_t space = attr < 0 ? -1 : H5Aget_space(attr);
  int rc = 0;
  if (type < 0 || space < 0)
    rc = h5_fail(err, s->path, "cannot open attribute \"%s\" on %s", name, where);
  else if (H5Tget_class(type) != H5T_STRING || H5Sget_simple_extent_npoints(space) != 1)
    rc = sph_error_set(err, "%s: attribute \"%s\" on %s is not a single string", s->path, name,
                       where);
  else
    rc = read_string(s, attr, type, where, name, out, err);
  close_id(space);
  close_id(type);
  close_id(attr);
  return rc;
}

static int get_text(const sph_snapshot *s, const char *name, int required, char **out,
                    sph_error *err) {
  return get_text_of(s, s->file, "/", name, required, out, err);
}

/* The file's attribute "dimension" into *dim: 2 when absent (every 2-D file). */
static int read_dimension(const sph_snapshot *s, int64_t *dim, sph_error *err) {
  *dim = 2;
  const htri_t has_dim = H5Aexists(s->file, "dimension");
  if (has_dim < 0) return h5_fail(err, s->path, "cannot look for attribute \"dimension\"");
  if (has_dim > 0 && get_numbers(s, "dimension", H5T_NATIVE_INT64, dim, 1, err)) return -1;
  if (*dim != 2 && *dim != 3)
    return sph_error_set(err, "%s: attribute \"dimension\" is %lld, expected 2 or 3", s->path,
                         (long long)*dim);
  return 0;
}

static int read_header(sph_snapshot *s, int any, sph_error *err) {
  int64_t count;
  if (get_numbers(s, "time", H5T_NATIVE_DOUBLE, &s->time, 1, err) ||
      get_numbers(s, "dt", H5T_NATIVE_DOUBLE, &s->dt, 1, err) ||
      get_numbers(s, "step", H5T_NATIVE_INT64, &s->step, 1, err) ||
      get_numbers(s, "particle_count", H5T_NATIVE_INT64, &count, 1, err))
    return -1;
  if (count < 0)
    return sph_error_set(err, "%s: attribute \"particle_count\" on / is negative (%lld)", s->path,
                         (long long)count);
  s->count = (size_t)count;
  int64_t dim;
  if (read_dimension(s, &dim, err)) return -1;
  s->dim = (int)dim;
  if (!any && dim != SPH_DIM)
    return sph_error_set(err,
                         "%s: a %lld-D snapshot; this program reads %d-D ones (the %lld-D build "
                         "does: doc/dimensions.md)",
                         s->path, (long long)dim, SPH_DIM, (long long)dim);
  for (size_t i = 0; i < N_TEXTS; i++)
    if (get_text(s, TEXTS[i], i == 0, &s->text[i], err)) return -1;
  return 0;
}

typedef struct lister {
  sph_snapshot *s;
  sph_error *err;
} lister;

static int add_field(sph_snapshot *s, const char *name, sph_error *err) {
  char **grown = realloc(s->fields, (s->n_fields + 1) * sizeof *grown);
  if (!grown) return sph_error_set(err, "%s: out of memory", s->path);
  s->fields = grown;
  if (!(s->fields[s->n_fields] = dup_string(name)))
    return sph_error_set(err, "%s: out of memory", s->path);
  s->n_fields++;
  return 0;
}

/* Checks that the dataset is 1-D with one value per particle. */
static int check_length(const sph_snapshot *s, hid_t dset, const char *name, sph_error *err) {
  hid_t space = H5Dget_space(dset);
  hsize_t dims[1] = {0};
  int rank = space < 0 ? -1 : H5Sget_simple_extent_ndims(space);
  int rc = 0;
  if (rank < 0)
    rc = h5_fail(err, s->path, "cannot get the shape of dataset /particles/%s", name);
  else if (rank != 1)
    rc = sph_error_set(err, "%s: dataset /particles/%s has rank %d, expected 1", s->path, name,
                       rank);
  else if (H5Sget_simple_extent_dims(space, dims, NULL) < 0)
    rc = h5_fail(err, s->path, "cannot get the shape of dataset /particles/%s", name);
  else if (dims[0] != (hsize_t)s->count)
    rc = sph_error_set(err,
                       "%s: dataset /particles/%s has %llu values, expected %zu "
                       "(particle_count)",
                       s->path, name, (unsigned long long)dims[0], s->count);
  close_id(space);
  return rc;
}

/* H5Literate callback: records each dataset (other objects are skipped);
 * returns 1 to stop on an error (already in l->err). */
static herr_t list_one(hid_t group, const char *name, const H5L_info_t *info, void *data) {
  lister *l = data;
  if (info->type != H5L_TYPE_HARD) return 0;
  hid_t obj = H5Oopen(group, name, H5P_DEFAULT);
  if (obj < 0) {
    h5_fail(l->err, l->s->path, "cannot open /particles/%s", name);
    return 1;
  }
  int rc = 0;
  if (H5Iget_type(obj) == H5I_DATASET)
    rc = check_length(l->s, obj, name, l->err) || add_field(l->s, name, l->err);
  close_id(obj);
  return rc ? 1 : 0;
}

static int list_fields(sph_snapshot *s, sph_error *err) {
  htri_t there = H5Lexists(s->file, "particles", H5P_DEFAULT);
  if (there <= 0) return sph_error_set(err, "%s: missing group /particles", s->path);
  s->group = H5Gopen2(s->file, "particles", H5P_DEFAULT);
  if (s->group < 0) return h5_fail(err, s->path, "cannot open group /particles");
  unsigned order = 0;
  hid_t gcpl = H5Gget_create_plist(s->group);
  if (gcpl < 0 || H5Pget_link_creation_order(gcpl, &order) < 0) order = 0;
  close_id(gcpl);
  H5_index_t index = (order & H5P_CRT_ORDER_INDEXED) ? H5_INDEX_CRT_ORDER : H5_INDEX_NAME;
  lister l = {s, err};
  hsize_t at = 0;
  herr_t rc = H5Literate(s->group, index, H5_ITER_INC, &at, list_one, &l);
  if (rc < 0) return h5_fail(err, s->path, "cannot list group /particles");
  return rc == 0 ? 0 : -1;
}

/* Opens the file, after checking it exists and is HDF5 at all. */
static int open_file(sph_snapshot *s, sph_error *err) {
  FILE *f = fopen(s->path, "rb");
  if (!f) return sph_error_set(err, "%s: cannot open: %s", s->path, strerror(errno));
  fclose(f);
  htri_t is = H5Fis_hdf5(s->path);
  if (is < 0) return h5_fail(err, s->path, "cannot read the file");
  if (is == 0) return sph_error_set(err, "%s: not an HDF5 file", s->path);
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  if (fapl < 0 || H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG) < 0) {
    close_id(fapl);
    return h5_fail(err, s->path, "cannot set up the HDF5 file access list");
  }
  s->file = H5Fopen(s->path, H5F_ACC_RDONLY, fapl);
  int rc = s->file < 0 ? h5_fail(err, s->path, "cannot open the HDF5 file") : 0;
  close_id(fapl);
  return rc;
}

static void release(sph_snapshot *s) {
  close_id(s->group);
  if (s->file >= 0) H5Fclose(s->file);
  for (size_t i = 0; i < N_TEXTS; i++)
    free(s->text[i]);
  for (size_t i = 0; i < s->n_fields; i++)
    free(s->fields[i]);
  free(s->fields);
  free(s->path);
  free(s);
}

int sph_snapshot_file_dimension(const char *path, int *dim, sph_error *err) {
  *dim = 2;
  h5_quiet q;
  quiet_begin(&q);
  sph_snapshot s = {0};
  s.path = (char *)path; /* (read only: the messages name it) */
  s.file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  int64_t d = 2;
  int rc = s.file < 0 ? sph_error_set(err, "%s: cannot open as an HDF5 snapshot", path)
                      : read_dimension(&s, &d, err);
  if (rc == 0) *dim = (int)d;
  if (s.file >= 0) H5Fclose(s.file);
  quiet_end(&q);
  return rc;
}

static int open_snapshot(const char *path, int any, sph_snapshot **out, sph_error *err) {
  *out = NULL;
  if (!path || !*path) return sph_error_set(err, "snapshot: empty file name");
  sph_snapshot *s = calloc(1, sizeof *s);
  if (!s || !(s->path = dup_string(path))) {
    free(s);
    return sph_error_set(err, "%s: out of memory", path);
  }
  s->file = s->group = -1;
  h5_quiet q;
  quiet_begin(&q);
  int rc = open_file(s, err);
  if (rc == 0) rc = read_header(s, any, err);
  if (rc == 0) rc = list_fields(s, err);
  if (rc != 0) release(s);
  quiet_end(&q);
  if (rc == 0) *out = s;
  return rc;
}

int sph_snapshot_open(const char *path, sph_snapshot **out, sph_error *err) {
  return open_snapshot(path, 0, out, err);
}

int sph_snapshot_open_any(const char *path, sph_snapshot **out, sph_error *err) {
  return open_snapshot(path, 1, out, err);
}

int sph_snapshot_dimension(const sph_snapshot *s) { return s->dim; }

hid_t sph_snapshot_hdf5_file(const sph_snapshot *s) { return s->file; }

/* The error for reading particles or a restart record of a snapshot of the
 * other dimension (opened with sph_snapshot_open_any). */
static int other_dimension(const sph_snapshot *s, sph_error *err) {
  return sph_error_set(err, "%s: a %d-D snapshot; this library reads %d-D particles", s->path,
                       s->dim, SPH_DIM);
}

void sph_snapshot_close(sph_snapshot *s) {
  if (!s) return;
  h5_quiet q;
  quiet_begin(&q);
  release(s);
  quiet_end(&q);
}

const char *sph_snapshot_path(const sph_snapshot *s) { return s->path; }
double sph_snapshot_time(const sph_snapshot *s) { return s->time; }
double sph_snapshot_dt(const sph_snapshot *s) { return s->dt; }
int64_t sph_snapshot_step(const sph_snapshot *s) { return s->step; }
size_t sph_snapshot_count(const sph_snapshot *s) { return s->count; }

const char *sph_snapshot_text(const sph_snapshot *s, const char *name) {
  for (size_t i = 0; i < N_TEXTS; i++)
    if (strcmp(TEXTS[i], name) == 0) return s->text[i];
  return NULL;
}

int sph_snapshot_number(const sph_snapshot *s, const char *name, double *out, size_t n,
                        sph_error *err) {
  h5_quiet q;
  quiet_begin(&q);
  int rc = get_numbers(s, name, H5T_NATIVE_DOUBLE, out, n, err);
  quiet_end(&q);
  return rc;
}

size_t sph_snapshot_field_count(const sph_snapshot *s) { return s->n_fields; }

const char *sph_snapshot_field_name(const sph_snapshot *s, size_t i) {
  return i < s->n_fields ? s->fields[i] : NULL;
}

int sph_snapshot_has_field(const sph_snapshot *s, const char *name) {
  for (size_t i = 0; i < s->n_fields; i++)
    if (strcmp(s->fields[i], name) == 0) return 1;
  return 0;
}

int sph_snapshot_field_units(const sph_snapshot *s, const char *name, char *buf, size_t size) {
  if (size) buf[0] = '\0';
  if (!sph_snapshot_has_field(s, name)) return -1;
  h5_quiet q;
  quiet_begin(&q);
  hid_t dset = H5Dopen2(s->group, name, H5P_DEFAULT);
  char *units = NULL, where[300];
  snprintf(where, sizeof where, "/particles/%s", name);
  sph_error err;
  int rc = dset < 0 ? -1 : get_text_of(s, dset, where, "units", 0, &units, &err);
  if (rc == 0 && !units) rc = -1;
  if (rc == 0 && size) snprintf(buf, size, "%s", units);
  free(units);
  close_id(dset);
  quiet_end(&q);
  return rc;
}

/* Reads dataset /particles/name, converted to mtype, into out. */
static int read_dataset(const sph_snapshot *s, const char *name, hid_t mtype, void *out,
                        sph_error *err) {
  if (!sph_snapshot_has_field(s, name))
    return sph_error_set(err, "%s: no dataset /particles/%s", s->path, name);
  hid_t dset = H5Dopen2(s->group, name, H5P_DEFAULT);
  hid_t type = dset < 0 ? -1 : H5Dget_type(dset);
  int rc = 0;
  if (type < 0)
    rc = h5_fail(err, s->path, "cannot open dataset /particles/%s", name);
  else if (!is_numeric(type))
    rc = sph_error_set(err, "%s: dataset /particles/%s is not numeric", s->path, name);
  else if (s->count > 0 && H5Dread(dset, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) < 0)
    rc = h5_fail(err, s->path, "cannot read dataset /particles/%s", name);
  close_id(type);
  close_id(dset);
  return rc;
}

int sph_snapshot_read_field(const sph_snapshot *s, const char *name, double *out, sph_error *err) {
  h5_quiet q;
  quiet_begin(&q);
  int rc = read_dataset(s, name, H5T_NATIVE_DOUBLE, out, err);
  quiet_end(&q);
  return rc;
}

static int read_store(const sph_snapshot *s, sph_particles *p, sph_error *err) {
  for (size_t i = 0; i < N_FIELDS; i++) {
    const field_spec *f = &FIELDS[i];
    if ((i == FREE_SURFACE_FIELD || i == PHASE_FIELD) && !sph_snapshot_has_field(s, f->name))
      continue;
    if (i == PHASE_FIELD) sph_particles_use(p, SPH_ARRAYS_PHASE);
    if (read_dataset(s, f->name, mem_type(f->type), member_array(p, f), err)) return -1;
  }
  for (size_t k = 0; k < p->n; k++) {
    p->flags[k] = p->flags[k] ? 1u : 0u;
    if (p->id[k] != (int64_t)k)
      return sph_error_set(err, "%s: dataset /particles/id holds %lld at row %zu, expected %zu",
                           s->path, (long long)p->id[k], k, k);
  }
  return 0;
}

int sph_snapshot_read_particles(const sph_snapshot *s, sph_particles *p, sph_error *err) {
  if (s->dim != SPH_DIM) return other_dimension(s, err);
  if (sph_particles_init(p, s->count, err)) return -1;
  p->n = s->count;
  h5_quiet q;
  quiet_begin(&q);
  int rc = read_store(s, p, err);
  quiet_end(&q);
  if (rc) sph_particles_free(p);
  return rc;
}

/* ------------------------------------------------------------------------ */
/* The restart record.                                                      */

/* The number of values of attribute name on obj, 0 if absent, -1 on error. */
static long long attribute_length(const sph_snapshot *s, hid_t obj, const char *name,
                                  sph_error *err) {
  htri_t there = H5Aexists(obj, name);
  if (there < 0) return h5_fail(err, s->path, "cannot look for attribute \"%s\" on /restart", name);
  if (there == 0) return 0;
  hid_t attr = H5Aopen(obj, name, H5P_DEFAULT);
  hid_t space = attr < 0 ? -1 : H5Aget_space(attr);
  hssize_t n = space < 0 ? -1 : H5Sget_simple_extent_npoints(space);
  close_id(space);
  close_id(attr);
  if (n < 0) return h5_fail(err, s->path, "cannot open attribute \"%s\" on /restart", name);
  return (long long)n;
}

/* Dataset /restart/name: 1-D, count values, numeric, read as mtype into a
 * new array (*out; NULL and no error when absent and not required). */
static int read_restart_array(const sph_snapshot *s, hid_t g, const char *name, int required,
                              hid_t mtype, size_t size, void **out, sph_error *err) {
  *out = NULL;
  htri_t there = H5Lexists(g, name, H5P_DEFAULT);
  if (there < 0) return h5_fail(err, s->path, "cannot look for dataset /restart/%s", name);
  if (there == 0)
    return required ? sph_error_set(err, "%s: missing dataset /restart/%s", s->path, name) : 0;
  hid_t dset = H5Dopen2(g, name, H5P_DEFAULT);
  hid_t type = dset < 0 ? -1 : H5Dget_type(dset);
  hid_t space = dset < 0 ? -1 : H5Dget_space(dset);
  hsize_t dims[1] = {0};
  int rc = 0;
  if (type < 0 || space < 0)
    rc = h5_fail(err, s->path, "cannot open dataset /restart/%s", name);
  else if (!is_numeric(type))
    rc = sph_error_set(err, "%s: dataset /restart/%s is not numeric", s->path, name);
  else if (H5Sget_simple_extent_ndims(space) != 1 ||
           H5Sget_simple_extent_dims(space, dims, NULL) < 0 || dims[0] != (hsize_t)s->count)
    rc = sph_error_set(err, "%s: dataset /restart/%s is not 1-D with %zu values (particle_count)",
                       s->path, name, s->count);
  if (rc == 0) {
    *out = malloc((s->count ? s->count : 1) * size);
    if (!*out)
      rc = sph_error_set(err, "%s: out of memory", s->path);
    else if (s->count > 0 && H5Dread(dset, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, *out) < 0)
      rc = h5_fail(err, s->path, "cannot read dataset /restart/%s", name);
  }
  close_id(space);
  close_id(type);
  close_id(dset);
  if (rc) {
    free(*out);
    *out = NULL;
  }
  return rc;
}

/* An optional one-number attribute of /restart: 0 when absent. */
static int get_optional_number(const sph_snapshot *s, hid_t g, const char *name, double *out,
                               sph_error *err) {
  *out = 0.0;
  const htri_t there = H5Aexists(g, name);
  if (there < 0) return h5_fail(err, s->path, "cannot look for attribute \"%s\" on /restart", name);
  return there > 0 ? get_numbers_of(s, g, "/restart", name, H5T_NATIVE_DOUBLE, out, 1, err) : 0;
}

/* An optional attribute of /restart holding doubles: malloc'd into *out
 * (*n values), or NULL and 0 where it is absent. */
static int get_optional_doubles(const sph_snapshot *s, hid_t g, const char *name, double **out,
                                size_t *n, sph_error *err) {
  *out = NULL;
  *n = 0;
  const long long len = attribute_length(s, g, name, err);
  if (len < 0) return -1;
  if (len == 0) return 0;
  if (!(*out = malloc((size_t)len * sizeof **out)))
    return sph_error_set(err, "%s: out of memory", s->path);
  *n = (size_t)len;
  return get_numbers_of(s, g, "/restart", name, H5T_NATIVE_DOUBLE, *out, *n, err);
}

static int read_restart(const sph_snapshot *s, hid_t g, sph_snapshot_restart_data *r,
                        sph_error *err) {
  int64_t format = 0;
  if (get_numbers_of(s, g, "/restart", "format", H5T_NATIVE_INT64, &format, 1, err)) return -1;
  if (format != 1)
    return sph_error_set(err, "%s: attribute \"format\" on /restart is %lld, this program reads 1",
                         s->path, (long long)format);
  if (get_numbers_of(s, g, "/restart", "output_index", H5T_NATIVE_INT64, &r->output_index, 1,
                     err) ||
      get_numbers_of(s, g, "/restart", "first_step", H5T_NATIVE_INT64, &r->first_step, 1, err) ||
      get_numbers_of(s, g, "/restart", "ledger", H5T_NATIVE_DOUBLE, r->ledger, 2 + SPH_DIM, err))
    return -1;
  if (get_optional_number(s, g, "ledger_diffusion", &r->ledger_diffusion, err) ||
      get_optional_number(s, g, "ledger_shifting", &r->ledger_shifting, err))
    return -1;
  if (r->output_index < 0 || r->output_index > 99999999)
    return sph_error_set(err,
                         "%s: attribute \"output_index\" on /restart is %lld, expected 0..99999999",
                         s->path, (long long)r->output_index);
  if (r->first_step != 0 && r->first_step != 1)
    return sph_error_set(err, "%s: attribute \"first_step\" on /restart is %lld, expected 0 or 1",
                         s->path, (long long)r->first_step);
  if (get_optional_doubles(s, g, "gauge_levels", &r->levels, &r->n_levels, err) ||
      get_optional_doubles(s, g, "probe_filters", &r->filters, &r->n_filters, err))
    return -1;
  const long long nout = attribute_length(s, g, "outflow", err);
  if (nout < 0) return -1;
  if (nout > 0 && nout != 3 + SPH_DIM)
    return sph_error_set(err, "%s: attribute \"outflow\" on /restart has %lld values, expected %d",
                         s->path, nout, 3 + SPH_DIM);
  if (nout > 0 &&
      get_numbers_of(s, g, "/restart", "outflow", H5T_NATIVE_DOUBLE, r->outflow, 3 + SPH_DIM, err))
    return -1;
  r->has_outflow = nout > 0;
  r->count = s->count;
  void *a = NULL;
  if (read_restart_array(s, g, "origin", 0, H5T_NATIVE_INT64, sizeof(int64_t), &a, err)) return -1;
  r->origin = a;
  if (read_restart_array(s, g, "order", 1, H5T_NATIVE_INT64, sizeof(int64_t), &a, err)) return -1;
  r->order = a;
  /* order must be a permutation of 0..count-1 */
  unsigned char *seen = calloc(s->count ? s->count : 1, 1);
  if (!seen) return sph_error_set(err, "%s: out of memory", s->path);
  for (size_t k = 0; k < s->count; k++) {
    const int64_t id = r->order[k];
    if (id < 0 || (uint64_t)id >= s->count || seen[id]) {
      free(seen);
      return sph_error_set(err,
                           "%s: dataset /restart/order holds %lld at row %zu: expected each of "
                           "0..%zu once",
                           s->path, (long long)id, k, s->count ? s->count - 1 : 0);
    }
    seen[id] = 1;
  }
  free(seen);
  const char *names[] = {"vxh", "vyh", "rhoh", "uh", SPH_IF3("vzh")};
  double **half[] = {&r->vxh, &r->vyh, &r->rhoh, &r->uh, SPH_IF3(&r->vzh)};
  enum { N_HALF = sizeof half / sizeof half[0] };
  int present = 0;
  for (int k = 0; k < N_HALF; k++) {
    if (read_restart_array(s, g, names[k], 0, H5T_NATIVE_DOUBLE, sizeof(double), &a, err))
      return -1;
    *half[k] = a;
    present += a != NULL;
  }
  if (present != 0 && present != N_HALF)
    return sph_error_set(err, "%s: group /restart has only some of vxh, vyh, rhoh, uh%s", s->path,
                         SPH_DIM == 3 ? ", vzh" : "");
  return 0;
}

int sph_snapshot_read_restart(const sph_snapshot *s, sph_snapshot_restart_data *r, sph_error *err) {
  memset(r, 0, sizeof *r);
  if (s->dim != SPH_DIM) return other_dimension(s, err);
  h5_quiet q;
  quiet_begin(&q);
  int rc = 0;
  hid_t g = -1;
  htri_t there = H5Lexists(s->file, "restart", H5P_DEFAULT);
  if (there < 0)
    rc = h5_fail(err, s->path, "cannot look for group /restart");
  else if (there == 0)
    rc = sph_error_set(err, "%s: no group /restart: the snapshot holds no restart record", s->path);
  else if ((g = H5Gopen2(s->file, "restart", H5P_DEFAULT)) < 0)
    rc = h5_fail(err, s->path, "cannot open group /restart");
  else
    rc = read_restart(s, g, r, err);
  close_id(g);
  quiet_end(&q);
  if (rc) sph_snapshot_restart_free(r);
  return rc;
}

void sph_snapshot_restart_free_particles(sph_snapshot_restart_data *r) {
  free(r->order);
  free(r->origin);
  r->origin = NULL;
  free(r->vxh);
  free(r->vyh);
  SPH_IF3(free(r->vzh); r->vzh = NULL;)
  free(r->rhoh);
  free(r->uh);
  r->order = NULL;
  r->vxh = r->vyh = r->rhoh = r->uh = NULL;
  r->count = 0;
}

void sph_snapshot_restart_free(sph_snapshot_restart_data *r) {
  sph_snapshot_restart_free_particles(r);
  free(r->levels);
  free(r->filters);
  memset(r, 0, sizeof *r);
}
