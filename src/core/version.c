/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * version.c - program version and build description (see version.h).
 * Nothing here depends on the date, the time or the host.
 */
#include "config.h"

#include "core/version.h"

const char *sph_version(void) { return PACKAGE_NAME " " PACKAGE_VERSION; }

const char *sph_configure_args(void) { return SPH_CONFIGURE_ARGS; }

#ifdef _OPENMP
#define SPH_F_OMP "yes"
#else
#define SPH_F_OMP "no"
#endif
#ifdef SPH_DEBUG_CHECKS
#define SPH_F_DEBUG "yes"
#else
#define SPH_F_DEBUG "no"
#endif
#ifdef SPH_SANITIZERS
#define SPH_F_SAN "yes"
#else
#define SPH_F_SAN "no"
#endif
#ifdef SPH_WERROR
#define SPH_F_WERROR "yes"
#else
#define SPH_F_WERROR "no"
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#define SPH_F_AVX "yes (AVX-512 or AVX2, the widest the processor has)"
#else
#define SPH_F_AVX "no"
#endif

const char *sph_build_features(void) {
  return "OpenMP " SPH_F_OMP ", debug checks " SPH_F_DEBUG ", sanitizers " SPH_F_SAN
         ", -Werror " SPH_F_WERROR ", SIMD lanes " SPH_F_AVX;
}

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
