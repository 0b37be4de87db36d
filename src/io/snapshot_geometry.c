/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * snapshot_geometry.c - the group /geometry of a snapshot
 * (snapshot_geometry.h): written with the rest of the file by
 * sph_snapshot_write, read by sph_snapshot_read_geometry.
 */
#include "config.h"

#include "io/geometry_group.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "io/snapshot.h"

static void close_id(hid_t id) {
  if (id >= 0) H5Idec_ref(id);
}

static int fail(sph_error *err, const char *path, const char *what) {
  return sph_error_set(err, "%s: cannot %s the group /geometry", path, what);
}

/* A fixed-length, NUL-terminated string type of size bytes. */
static hid_t string_type(size_t size) {
  hid_t t = H5Tcopy(H5T_C_S1);
  if (t >= 0 && (H5Tset_size(t, size) < 0 || H5Tset_strpad(t, H5T_STR_NULLTERM) < 0)) {
    H5Tclose(t);
    return -1;
  }
  return t;
}

/* rows x cols values of memory type mtype (file type ftype) as dataset
 * name of g, the values written by this process when it writes them;
 * nothing for no rows. */
static int put_rows(hid_t g, const char *name, hid_t ftype, hid_t mtype, const void *data,
                    size_t rows, size_t cols, hid_t dcpl, int values) {
  if (rows == 0) return 0;
  const hsize_t dims[2] = {rows, cols};
  hid_t space = H5Screate_simple(cols ? 2 : 1, dims, NULL);
  hid_t set = space < 0 ? -1 : H5Dcreate2(g, name, ftype, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  const int rc =
      set < 0 || (values && H5Dwrite(set, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) ? -1 : 0;
  close_id(set);
  close_id(space);
  return rc;
}

/* The first k of each row of 6 (or 3) doubles, packed: rows x k. */
static double *packed(const double *rows, size_t n, size_t stride, size_t k) {
  double *out = malloc((n ? n : 1) * k * sizeof *out);
  if (out)
    for (size_t i = 0; i < n; i++)
      memcpy(out + i * k, rows + i * stride, k * sizeof *out);
  return out;
}

int sph_geometry_group_write(hid_t file, const sph_snapshot_geometry *g, const char *path,
                             int values, sph_error *err) {
  const size_t dim = (size_t)g->dim, box = 2 * dim;
  hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE), dcpl = H5Pcreate(H5P_DATASET_CREATE);
  /* space taken when a dataset is made, as the parallel library does */
  if (gcpl < 0 || dcpl < 0 || H5Pset_obj_track_times(gcpl, 0) < 0 ||
      H5Pset_obj_track_times(dcpl, 0) < 0 || H5Pset_alloc_time(dcpl, H5D_ALLOC_TIME_EARLY) < 0) {
    close_id(gcpl);
    close_id(dcpl);
    return fail(err, path, "set up");
  }
  hid_t grp = H5Gcreate2(file, "geometry", H5P_DEFAULT, gcpl, H5P_DEFAULT);
  hid_t name_t = string_type(SPH_GEOMETRY_NAME), kind_t = string_type(SPH_GEOMETRY_KIND);
  int rc = grp < 0 || name_t < 0 || kind_t < 0 ? -1 : 0;
  const int64_t head[2] = {SPH_GEOMETRY_FORMAT, g->dim};
  static const char *const names[2] = {"format", "dimension"};
  for (int k = 0; rc == 0 && k < 2; k++) {
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t a =
        space < 0 ? -1 : H5Acreate2(grp, names[k], H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT);
    if (a < 0 || H5Awrite(a, H5T_NATIVE_INT64, &head[k]) < 0) rc = -1;
    close_id(a);
    close_id(space);
  }
  double *t = NULL, *o = NULL, *w = NULL, *q = NULL;
  if (rc == 0) {
    t = packed(g->tank, 1, 6, box);
    o = packed(g->obstacles ? &g->obstacles[0][0] : NULL, g->n_obstacles, 6, box);
    w = packed(g->walls ? &g->walls[0][0] : NULL, g->n_walls, 6, box);
    q = packed(g->probe_position ? &g->probe_position[0][0] : NULL, g->n_probes, 3, dim);
    if (!t || !o || !w || !q) rc = -1;
  }
  if (rc == 0 && g->has_tank)
    rc = put_rows(grp, "tank", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, t, box, 0, dcpl, values);
  if (rc == 0)
    rc = put_rows(grp, "obstacles", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, o, g->n_obstacles, box, dcpl,
                  values);
  if (rc == 0)
    rc =
        put_rows(grp, "walls", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, w, g->n_walls, box, dcpl, values);
  if (rc == 0)
    rc = put_rows(grp, "probe_position", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, q, g->n_probes, dim,
                  dcpl, values);
  if (rc == 0)
    rc = put_rows(grp, "probe_name", name_t, name_t, g->probe_name, g->n_probes, 0, dcpl, values);
  if (rc == 0)
    rc = put_rows(grp, "probe_kind", kind_t, kind_t, g->probe_kind, g->n_probes, 0, dcpl, values);
  free(t);
  free(o);
  free(w);
  free(q);
  close_id(name_t);
  close_id(kind_t);
  close_id(grp);
  close_id(gcpl);
  close_id(dcpl);
  return rc ? fail(err, path, "write") : 0;
}

/* The rows of dataset name of g (absent: 0 rows) with cols columns each,
 * into *out (malloc'ed, rows of stride doubles; unused columns 0). */
static int get_rows(hid_t g, const char *name, size_t cols, size_t stride, double **out,
                    size_t *n) {
  *out = NULL;
  *n = 0;
  if (H5Lexists(g, name, H5P_DEFAULT) <= 0) return 0;
  hid_t set = H5Dopen2(g, name, H5P_DEFAULT), space = set < 0 ? -1 : H5Dget_space(set);
  hsize_t dims[2] = {0, 0};
  const int rank = space < 0 ? -1 : H5Sget_simple_extent_ndims(space);
  int rc = rank < 1 || rank > 2 || H5Sget_simple_extent_dims(space, dims, NULL) < 0 ? -1 : 0;
  const size_t rows = rank == 1 ? 1 : (size_t)dims[0], c = rank == 1 ? (size_t)dims[0] : dims[1];
  if (rc == 0 && (c != cols || rows > ((size_t)1 << 24))) rc = -1; /* not this layout */
  double *flat = rc ? NULL : malloc((rows ? rows : 1) * cols * sizeof *flat);
  double *res = rc ? NULL : calloc(rows ? rows : 1, stride * sizeof *res);
  if (rc == 0 && (!flat || !res)) rc = -1;
  if (rc == 0 && H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, flat) < 0) rc = -1;
  if (rc == 0)
    for (size_t i = 0; i < rows; i++)
      memcpy(res + i * stride, flat + i * cols, cols * sizeof *res);
  free(flat);
  close_id(space);
  close_id(set);
  if (rc) {
    free(res);
    return -1;
  }
  *out = res;
  *n = rows;
  return 0;
}

/* n strings of size bytes each from dataset name of g into *out. */
static int get_strings(hid_t g, const char *name, size_t size, size_t n, char **out) {
  *out = calloc(n ? n : 1, size);
  if (!*out) return -1;
  if (n == 0) return 0;
  hid_t set = H5Dopen2(g, name, H5P_DEFAULT), space = set < 0 ? -1 : H5Dget_space(set);
  hsize_t dims[1] = {0};
  hid_t t = string_type(size);
  int rc = space < 0 || t < 0 || H5Sget_simple_extent_ndims(space) != 1 ||
                   H5Sget_simple_extent_dims(space, dims, NULL) < 0 || dims[0] != n
               ? -1
               : 0;
  if (rc == 0 && H5Dread(set, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, *out) < 0) rc = -1;
  for (size_t i = 0; rc == 0 && i < n; i++)
    (*out)[i * size + size - 1] = '\0';
  close_id(t);
  close_id(space);
  close_id(set);
  return rc;
}

int sph_geometry_group_read(hid_t file, sph_snapshot_geometry *g, const char *path,
                            sph_error *err) {
  memset(g, 0, sizeof *g);
  if (H5Lexists(file, "geometry", H5P_DEFAULT) <= 0) return 1;
  hid_t grp = H5Gopen2(file, "geometry", H5P_DEFAULT);
  if (grp < 0) return fail(err, path, "open");
  int64_t format = 0, dim = 0;
  hid_t a = H5Aopen(grp, "format", H5P_DEFAULT), b = H5Aopen(grp, "dimension", H5P_DEFAULT);
  int rc = a < 0 || b < 0 || H5Aread(a, H5T_NATIVE_INT64, &format) < 0 ||
                   H5Aread(b, H5T_NATIVE_INT64, &dim) < 0
               ? -1
               : 0;
  close_id(a);
  close_id(b);
  if (rc == 0 && (format != SPH_GEOMETRY_FORMAT || (dim != 2 && dim != 3))) {
    close_id(grp);
    return sph_error_set(err,
                         "%s: the group /geometry has format %lld, dimension %lld (this "
                         "build reads format %d, dimension 2 or 3)",
                         path, (long long)format, (long long)dim, SPH_GEOMETRY_FORMAT);
  }
  g->dim = (int)dim;
  const size_t box = 2 * (size_t)dim;
  double *tank = NULL, *pos = NULL, *obstacles = NULL, *walls = NULL;
  char *names = NULL, *kinds = NULL;
  size_t n_tank = 0, n_pos = 0;
  if (rc == 0) rc = get_rows(grp, "tank", box, 6, &tank, &n_tank);
  if (rc == 0 && n_tank == 1) {
    memcpy(g->tank, tank, sizeof g->tank);
    g->has_tank = 1;
  }
  free(tank);
  /* each array read through a pointer of its own type, then given its rows' type */
  if (rc == 0) rc = get_rows(grp, "obstacles", box, 6, &obstacles, &g->n_obstacles);
  g->obstacles = (double(*)[6])obstacles;
  if (rc == 0) rc = get_rows(grp, "walls", box, 6, &walls, &g->n_walls);
  g->walls = (double(*)[6])walls;
  if (rc == 0) rc = get_rows(grp, "probe_position", (size_t)dim, 3, &pos, &n_pos);
  g->probe_position = (double(*)[3])pos;
  g->n_probes = n_pos;
  if (rc == 0) rc = get_strings(grp, "probe_name", SPH_GEOMETRY_NAME, n_pos, &names);
  g->probe_name = (char(*)[SPH_GEOMETRY_NAME])names;
  if (rc == 0) rc = get_strings(grp, "probe_kind", SPH_GEOMETRY_KIND, n_pos, &kinds);
  g->probe_kind = (char(*)[SPH_GEOMETRY_KIND])kinds;
  close_id(grp);
  if (rc) {
    sph_snapshot_geometry_free(g);
    return fail(err, path, "read");
  }
  return 0;
}

int sph_snapshot_read_geometry(const struct sph_snapshot *s, sph_snapshot_geometry *g,
                               sph_error *err) {
  return sph_geometry_group_read(sph_snapshot_hdf5_file(s), g, sph_snapshot_path(s), err);
}

void sph_snapshot_geometry_free(sph_snapshot_geometry *g) {
  free(g->obstacles);
  free(g->walls);
  free(g->probe_position);
  free(g->probe_name);
  free(g->probe_kind);
  memset(g, 0, sizeof *g);
}
