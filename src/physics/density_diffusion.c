/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * density_diffusion.c - the names of the density-diffusion models (see
 * density_diffusion.h).
 */
#include "config.h"

#include "physics/density_diffusion.h"

#include <stddef.h>

const char *const sph_diffusion_kind_names[] = {"none", "molteni_colagrossi", "antuono",
                                                "fourtakas", NULL};

const char *sph_diffusion_name(sph_diffusion_kind k) {
  if ((int)k < 0 || (int)k > (int)SPH_DIFFUSION_FOURTAKAS) return "?";
  return sph_diffusion_kind_names[k];
}
