/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * geometry_group.h - writing and reading the group /geometry
 * (snapshot_geometry.h) on an open HDF5 file; snapshot.c's, not the
 * public API.
 */
#ifndef SPH_GEOMETRY_GROUP_H
#define SPH_GEOMETRY_GROUP_H

#include <hdf5.h>

#include "io/snapshot_geometry.h"

/* Writes g as /geometry of file (every object without times, as the rest
 * of the snapshot); the datasets' values only when `values` (a team's
 * processes all make the objects, its first writes the values); 0, or -1
 * with err naming path. */
int sph_geometry_group_write(hid_t file, const sph_snapshot_geometry *g, const char *path,
                             int values, sph_error *err);
/* Reads /geometry of file: 0, 1 when absent, -1 with err naming path. */
int sph_geometry_group_read(hid_t file, sph_snapshot_geometry *g, const char *path, sph_error *err);
/* The HDF5 file of an open snapshot (snapshot.c). */
hid_t sph_snapshot_hdf5_file(const struct sph_snapshot *s);

#endif
