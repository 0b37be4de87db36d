/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * version.h - what build produced a file: stored in every snapshot.
 *
 * The version numbers below are the project's one source of its version:
 * configure.ac reads SPH_VERSION_STRING from here for AC_INIT, so the
 * package, the library and this header cannot disagree. A program built
 * against the installed library can test them with #if. Raise them with
 * NEWS, and libsph's -version-info in Makefile.am by libtool's rules.
 */
#ifndef SPH_VERSION_H
#define SPH_VERSION_H

#define SPH_VERSION_MAJOR 0
#define SPH_VERSION_MINOR 2
#define SPH_VERSION_PATCH 0
#define SPH_VERSION_STRING "0.2.0"

#ifdef __cplusplus
extern "C" {
#endif

/* "sph 0.1.0" */
const char *sph_version(void);
/* The arguments ./configure was run with ("" when none). */
const char *sph_configure_args(void);
/* What the build has, whatever the arguments were: OpenMP, the debug
 * checks, the sanitizers, warnings as errors, the SIMD lanes, e.g.
 * "OpenMP yes, debug checks no, sanitizers no, -Werror no, SIMD lanes yes". */
const char *sph_build_features(void);
/* Compiler name and version, and whether OpenMP was compiled in. */
const char *sph_compiler(void);

#ifdef __cplusplus
}
#endif

#endif
