/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * snapshot.h - HDF5 snapshots: one file per output time, and their XDMF index.
 *
 * Layout of a snapshot file (see doc/snapshot-format.md):
 *   attributes on "/": time, step, dt, particle_count, case_name, case_text,
 *     overrides, parameters, version, configure_args, compiler, dx, h, rho0,
 *     view (4 doubles: x0, x1, y0, y1 of the region the case was set in);
 *   /particles/<field>: one 1-D dataset per field, particles in id order,
 *     each with string attributes "units" and "description".
 *   Fields: x y vx vy rho p mass h u (float64), kind (int32), id (int64),
 *     phase (uint8) where the store has phases (physics.air), and
 *     free_surface (uint8) when the writer is asked for it;
 *   /restart: what `sph run --restart` needs beyond the fields (written when
 *     the meta has a restart record; see sph_snapshot_restart below).
 * Files are written to "<path>.tmp" and renamed, so an interrupted run never
 * leaves a torn snapshot. Nothing time- or host-dependent is stored.
 *
 * The renderer and `sph info` use only the reading half of this API.
 */
#ifndef SPH_SNAPSHOT_H
#define SPH_SNAPSHOT_H

#include <stddef.h>
#include <stdint.h>

#include "core/error.h"
#include "core/particles.h"
#include "io/snapshot_geometry.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sph_snapshot_meta {
  double time, dt;
  int64_t step;
  const char *case_name;  /* required */
  const char *case_text;  /* may be NULL: stored as "" */
  const char *overrides;  /* may be NULL */
  const char *parameters; /* resolved parameters and choices, "key: value" lines; may be NULL */
  const char *kernel;     /* the smoothing kernel's name (numerics.kernel); may be NULL */
  double dx, h, rho0;
  double view[2 * SPH_DIM];                   /* x0, x1, y0, y1 (, z0, z1) */
  int free_surface;                           /* write the free_surface field (flags bit 0) */
  const struct sph_snapshot_restart *restart; /* the /restart group, or NULL for none */
  const sph_snapshot_geometry *geometry;      /* the /geometry group, or NULL for none */
} sph_snapshot_meta;

/* What a run needs beyond the particle fields to continue exactly from a
 * snapshot (`sph run --restart`), stored in the group /restart:
 *   attributes: format (1), output_index (k of snap_k), first_step (1 until
 *     the leap-frog's first step is done), ledger (4 values: wall work, XSPH
 *     drift, impulse x, impulse y; see ledger in sim.c), ledger_diffusion
 *     (the density diffusion's energy, with the Riemann continuity term's; only in runs with
 * density diffusion or physics.riemann, 0 when absent), ledger_shifting (particle shifting's
 * potential-energy drift; only in runs with shifting, 0 when absent), gauge_levels (each gauge's
 * level at t = 0; absent without gauges), probe_filters (the probes' low-pass filters: each probe's
 * output, then the time of the last probe row and the rows seen; absent where no probe has a
 *     filter, and a resumed run's filters then start afresh);
 *     outflow (with geometry.leaving: remove: the fluid particles that left
 *     the domain, their mass, energy and momentum by axis; solver/outflow.h);
 *   datasets (in storage order, not id order): order (int64: the id of the
 *     particle at each storage index: the within-cell order the neighbour
 *     sums run in), and with the leap-frog vxh, vyh, rhoh, uh (float64: the
 *     half-step values); origin (int64, in id order, once a particle has
 *     left the domain: the id each particle had when the case made it,
 *     increasing).
 * For writing, the arrays are the store's own (n values each, storage
 * order); NULL half-step arrays are not written. */
typedef struct sph_snapshot_restart {
  int64_t output_index;
  int64_t first_step;
  double ledger[2 + SPH_DIM];
  int has_diffusion; /* write ledger_diffusion */
  double ledger_diffusion;
  int has_shifting; /* write ledger_shifting */
  double ledger_shifting;
  size_t n_levels;
  const double *levels;
  size_t n_filters;
  const double *filters;
  int has_outflow; /* write outflow */
  double outflow[3 + SPH_DIM];
  const int64_t *origin; /* NULL: not written */
  const int64_t *order;
  const double *vxh, *vyh, *rhoh, *uh;
#if SPH_DIM == 3
  const double *vzh;
#endif
} sph_snapshot_restart;

/* Writes p (any storage order) to path in id order, atomically. */
int sph_snapshot_write(const char *path, const sph_snapshot_meta *meta, const sph_particles *p,
                       sph_error *err);

/* The processes of an MPI run that write a snapshot together
 * (doc/parallel.md): every process of MPI_COMM_WORLD, this one's rank
 * and their count, and their collective agreement on a result (0 on
 * every process when rc is 0 on every one, else -1 on every one with the
 * message of the first that failed: solver/procs.h's sph_procs_agree). */
typedef struct sph_snapshot_team {
  int rank, count;
  int (*agree)(int rc, sph_error *err);
} sph_snapshot_team;

/* sph_snapshot_write by a team (NULL, or one process: alone), a
 * collective step: every process calls it with the same arguments (the
 * same meta, the same particles) and each writes its share of the
 * particles' rows (whole HDF5 chunks) through parallel HDF5, the file the
 * same bytes as a lone writer's. A build without parallel HDF5, or a text
 * of meta too long for an attribute in the root's header (64 KiB less
 * 1 KiB), has the first process write alone and the others return 0 at
 * once. The result is the team's on every process, except a lone
 * writer's (the caller agrees it). */
int sph_snapshot_write_team(const char *path, const sph_snapshot_meta *meta, const sph_particles *p,
                            const sph_snapshot_team *team, sph_error *err);

/* Writes (atomically) an XDMF 3 file that describes a series of snapshots,
 * so ParaView and VisIt open the whole run: h5_names are the snapshot file
 * names relative to the XDMF file, times their times, n_particles their
 * particle counts; optional the fields they hold beyond the fixed ones
 * (SPH_XDMF_*; 1 is the free-surface field alone). */
#define SPH_XDMF_FREE_SURFACE 1
#define SPH_XDMF_PHASE 2
int sph_xdmf_write(const char *xmf_path, size_t n_snap, const char *const *h5_names,
                   const double *times, const size_t *n_particles, int optional, sph_error *err);

/* Reading. */
typedef struct sph_snapshot sph_snapshot;

/* The dimension a snapshot file was written in (its attribute "dimension";
 * 2 when absent, as in every 2-D file) into *dim, without reading the rest:
 * what the command line reads to hand a file to the build of its dimension.
 * Non-zero with err if the file cannot be opened as HDF5. */
int sph_snapshot_file_dimension(const char *path, int *dim, sph_error *err);

/* Opens a snapshot and reads its header; errors name the file (and the
 * missing attribute or dataset). A snapshot of the other dimension than the
 * library's is refused. */
int sph_snapshot_open(const char *path, sph_snapshot **out, sph_error *err);
/* The same for a snapshot of either dimension: its attributes and fields
 * read by name (the renderer draws both); reading its particles or its
 * restart record is refused unless it has the library's dimension. */
int sph_snapshot_open_any(const char *path, sph_snapshot **out, sph_error *err);
/* The snapshot's dimension, 2 or 3. */
int sph_snapshot_dimension(const sph_snapshot *s);
void sph_snapshot_close(sph_snapshot *s);
const char *sph_snapshot_path(const sph_snapshot *s);
double sph_snapshot_time(const sph_snapshot *s);
double sph_snapshot_dt(const sph_snapshot *s);
int64_t sph_snapshot_step(const sph_snapshot *s);
size_t sph_snapshot_count(const sph_snapshot *s);
/* A string attribute of "/" (case_name, case_text, overrides, parameters,
 * version, configure_args, compiler), or NULL if absent. Owned by s. */
const char *sph_snapshot_text(const sph_snapshot *s, const char *name);
/* A floating-point attribute of "/" with exactly n values (dx, h, rho0: 1;
 * view: 4). Returns non-zero with err if absent or of another length. */
int sph_snapshot_number(const sph_snapshot *s, const char *name, double *out, size_t n,
                        sph_error *err);
/* The fields present, in file order. */
size_t sph_snapshot_field_count(const sph_snapshot *s);
const char *sph_snapshot_field_name(const sph_snapshot *s, size_t i);
int sph_snapshot_has_field(const sph_snapshot *s, const char *name);
/* The `units` attribute of a field (e.g. "m/s") into buf (size bytes);
 * returns -1 (buf "") if the field or the attribute is absent. */
int sph_snapshot_field_units(const sph_snapshot *s, const char *name, char *buf, size_t size);
/* Reads one field converted to double into out (count values). An absent
 * field or a failed read is an error naming the file and the dataset. */
int sph_snapshot_read_field(const sph_snapshot *s, const char *name, double *out, sph_error *err);
/* Reads the full particle state (exact types, id order) into p, which is
 * initialised here (free with sph_particles_free). */
int sph_snapshot_read_particles(const sph_snapshot *s, sph_particles *p, sph_error *err);

/* The restart record of a snapshot, read into malloc'd arrays (free with
 * sph_snapshot_restart_free): order is checked to be a permutation of
 * 0..count-1; the half-step arrays are NULL when absent (all four or none).
 * A snapshot without /restart, or a malformed one, is an error naming the
 * file and the attribute or dataset. */
typedef struct sph_snapshot_restart_data {
  int64_t output_index;
  int64_t first_step;
  double ledger[2 + SPH_DIM];
  double ledger_diffusion; /* 0 when the attribute is absent */
  double ledger_shifting;  /* 0 when the attribute is absent */
  size_t n_levels;
  double *levels;
  size_t n_filters;
  double *filters; /* NULL when absent */
  int has_outflow;
  double outflow[3 + SPH_DIM]; /* zeros when absent */
  size_t count;
  int64_t *order;
  int64_t *origin; /* NULL when absent */
  double *vxh, *vyh, *rhoh, *uh;
#if SPH_DIM == 3
  double *vzh;
#endif
} sph_snapshot_restart_data;
int sph_snapshot_read_restart(const sph_snapshot *s, sph_snapshot_restart_data *r, sph_error *err);
void sph_snapshot_restart_free(sph_snapshot_restart_data *r);
/* Frees only r's per-particle arrays (order, origin and the half-step values; count
 * becomes 0), keeping its gauges, filters and scalars: for a caller that
 * has copied those arrays into its store. */
void sph_snapshot_restart_free_particles(sph_snapshot_restart_data *r);

#ifdef __cplusplus
}
#endif

#endif
