/*
 * version.c - program version and build description (see version.h).
 * Nothing here depends on the date, the time or the host.
 */
#include "config.h"

#include "core/version.h"

const char *sph_version(void) { return PACKAGE_NAME " " PACKAGE_VERSION; }

const char *sph_configure_args(void) { return SPH_CONFIGURE_ARGS; }

const char *sph_compiler(void) {
#ifdef _OPENMP
#define SPH_OMP " with OpenMP"
#else
#define SPH_OMP " without OpenMP"
#endif
#ifdef __VERSION__
  return "cc " __VERSION__ SPH_OMP;
#else
  return "cc (unknown version)" SPH_OMP;
#endif
}
