/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * snapshot_fields.h - the fields of a snapshot (internal to libsphio): name,
 * type, where the array lives in sph_particles, units and description.
 * snapshot.c writes and reads them; xdmf.c describes them to ParaView. One
 * table, so the two can never disagree.
 */
#ifndef SPH_SNAPSHOT_FIELDS_H
#define SPH_SNAPSHOT_FIELDS_H

#include <stddef.h>

#include "core/particles.h"

typedef enum { FT_F64, FT_I32, FT_I64, FT_U8 } field_type;

typedef struct field_spec {
  const char *name;
  field_type type;
  size_t member; /* offset of the array pointer in sph_particles */
  const char *units;
  const char *description;
} field_spec;

/* XDMF NumberType and Precision (bytes) of each field type. */
static inline const char *field_xdmf_type(field_type t) {
  return t == FT_F64 ? "Float" : t == FT_U8 ? "UChar" : "Int";
}
static inline int field_bytes(field_type t) {
  return t == FT_F64 || t == FT_I64 ? 8 : t == FT_I32 ? 4 : 1;
}

/* In writing order; phase (two-phase runs) and free_surface (last) only
 * when asked for. */
static const field_spec FIELDS[] = {
    {"x", FT_F64, offsetof(sph_particles, x), "m", "position, x coordinate"},
#if SPH_DIM == 2
    {"y", FT_F64, offsetof(sph_particles, y), "m", "position, y coordinate (up)"},
    {"vx", FT_F64, offsetof(sph_particles, vx), "m/s", "velocity, x component"},
    {"vy", FT_F64, offsetof(sph_particles, vy), "m/s", "velocity, y component"},
#else /* z up */
    {"y", FT_F64, offsetof(sph_particles, y), "m", "position, y coordinate"},
    {"z", FT_F64, offsetof(sph_particles, z), "m", "position, z coordinate (up)"},
    {"vx", FT_F64, offsetof(sph_particles, vx), "m/s", "velocity, x component"},
    {"vy", FT_F64, offsetof(sph_particles, vy), "m/s", "velocity, y component"},
    {"vz", FT_F64, offsetof(sph_particles, vz), "m/s", "velocity, z component"},
#endif
    {"rho", FT_F64, offsetof(sph_particles, rho), "kg/m^3", "density"},
    {"p", FT_F64, offsetof(sph_particles, p), "Pa", "pressure from the equation of state"},
    {"mass", FT_F64, offsetof(sph_particles, mass), "kg", "particle mass"},
    {"h", FT_F64, offsetof(sph_particles, h), "m", "smoothing length"},
    {"u", FT_F64, offsetof(sph_particles, u), "J/kg", "thermal energy per unit mass"},
    {"kind", FT_I32, offsetof(sph_particles, kind), "1", "particle kind: 0 fluid, 1 wall"},
    {"id", FT_I64, offsetof(sph_particles, id), "1", "particle id, 0..n-1 (the row index)"},
    {"phase", FT_U8, offsetof(sph_particles, phase), "1",
     "the particle's material: 0 the liquid, 1 the air (physics.air)"},
    {"free_surface", FT_U8, offsetof(sph_particles, flags), "1",
     "1 if the particle is on the free surface (flags bit 0), else 0"},
};
#define N_FIELDS (sizeof FIELDS / sizeof FIELDS[0])
#define FREE_SURFACE_FIELD (N_FIELDS - 1)
#define PHASE_FIELD (N_FIELDS - 2)

#define ID_FIELD (SPH_DIM == 2 ? 10 : 12)

#endif
