/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * csv_units.c - the units of the columns sph writes (see csv.h), from the
 * tables of doc/snapshot-format.md (diagnostics.csv, gauges.csv) and
 * doc/cli.md (audit.csv). Quantities of a 2-D run are per metre of depth:
 * mass kg/m, energies J/m, momenta kg/s in 2-D (per unit depth; kg, J and
 * kg m/s in 3-D). A test reads the headers the
 * solver writes and checks that every column is here.
 */
#include "config.h"

#include "io/csv.h"

#include "core/dim.h"

/* A 2-D run's sums are per unit depth (kg/m, J/m, kg/s); a 3-D run's are
 * whole (kg, J, kg m/s). */
#if SPH_DIM == 2
#define MASS_UNITS "kg/m"
#define ENERGY_UNITS "J/m"
#define MOMENTUM_UNITS "kg/s"
#else
#define MASS_UNITS "kg"
#define ENERGY_UNITS "J"
#define MOMENTUM_UNITS "kg m/s"
#endif

#include <stdio.h>
#include <string.h>

typedef struct column_units {
  const char *name, *units;
} column_units;

static const column_units table[] = {
    /* diagnostics.csv */
    {"time", "s"},
    {"step", ""},
    {"dt", "s"},
    {"n_fluid", ""},
    {"front_x", "m"},
    {"mass", MASS_UNITS},
    {"momentum_x", MOMENTUM_UNITS},
    {"momentum_y", MOMENTUM_UNITS},
    {"momentum_z", MOMENTUM_UNITS},
    {"kinetic", ENERGY_UNITS},
    {"potential", ENERGY_UNITS},
    {"n_free_surface", ""},
    {"internal", ENERGY_UNITS},
    {"boundary_work", ENERGY_UNITS},
    {"xsph_drift", ENERGY_UNITS},
    {"shifting_drift", ENERGY_UNITS},
    {"total_energy", ENERGY_UNITS},
    {"energy_deviation", ""},
    {"fluid_energy_deviation", ""},
    {"momentum_residual_x", MOMENTUM_UNITS},
    {"momentum_residual_y", MOMENTUM_UNITS},
    {"momentum_residual_z", MOMENTUM_UNITS},
    {"diffusion_energy", ENERGY_UNITS},
    {"wall_potential", ENERGY_UNITS},
    {"n_removed", ""},
    {"mass_removed", MASS_UNITS},
    {"energy_removed", ENERGY_UNITS},
    /* audit.csv (deviations, work and heat in units of E0) */
    {"particles", ""},
    {"dx", "m"},
    {"wall_work", ""},
    {"wall_heat", ""},
    {"mass_drift", ""},
    {"momentum_drift", ""},
};

const char *sph_csv_units(const char *column) {
  for (size_t i = 0; i < sizeof table / sizeof table[0]; i++)
    if (strcmp(table[i].name, column) == 0) return table[i].units;
  if (strncmp(column, "eta_", 4) == 0) return "m"; /* gauges.csv: eta_<x> */
  return NULL;
}

int sph_csv_put_columns(FILE *f, const char *const *names, int first) {
  for (; *names; names++, first = 0)
    if (sph_csv_put_column(f, *names, first)) return -1;
  return 0;
}

int sph_csv_put_column(FILE *f, const char *name, int first) {
  const char *u = sph_csv_units(name);
  const char *sep = first ? "" : ",";
  return (u && u[0] ? fprintf(f, "%s%s (%s)", sep, name, u) : fprintf(f, "%s%s", sep, name)) < 0
             ? -1
             : 0;
}
