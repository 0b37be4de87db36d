/*
 * models.h - the named choices of the physical model that a case selects:
 * the smoothing kernel, the laminar viscosity model and the density
 * filter. Types only, so that the case schema (src/case/) can name them
 * without reaching into the physics' functions; the names are listed and
 * parsed by the case reader (sph_kernel_name, ...) and the filter
 * (sph_filter_name).
 */
#ifndef SPH_MODELS_H
#define SPH_MODELS_H

#include "core/error.h"

/* The smoothing kernel (src/physics/kernel.h). */
typedef enum { SPH_KERNEL_CUBIC_SPLINE = 0 } sph_kernel_kind;

/* The laminar viscosity model (src/solver/forces.h). */
typedef enum {
  SPH_VISCOSITY_NONE = 0,
  SPH_VISCOSITY_STRESS_TENSOR = 1, /* paper A eq. (11), (13), (14) */
  SPH_VISCOSITY_MORRIS = 2         /* paper B eq. (4), laminar term */
} sph_viscosity_kind;

/* Density re-initialisation, paper B §2.8 (src/physics/filter.h). */
typedef enum sph_filter_kind {
  SPH_FILTER_NONE = 0,
  SPH_FILTER_MLS = 1,
  SPH_FILTER_SHEPARD = 2
} sph_filter_kind;

/* The names of the choices in enum order, NULL-terminated:
 * {"none", "mls", "shepard", NULL}. */
extern const char *const sph_filter_kind_names[];
/* "none", "mls", "shepard"; "?" for a value outside the enum. */
const char *sph_filter_name(sph_filter_kind k);
/* The kind named `name`; an unknown name is an error listing the valid ones. */
int sph_filter_from_name(const char *name, sph_filter_kind *k, sph_error *err);

#endif
