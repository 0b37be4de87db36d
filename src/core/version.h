/*
 * version.h - what build produced a file: stored in every snapshot.
 */
#ifndef SPH_VERSION_H
#define SPH_VERSION_H

#ifdef __cplusplus
extern "C" {
#endif

/* "sph 0.1.0" */
const char *sph_version(void);
/* The arguments ./configure was run with. */
const char *sph_configure_args(void);
/* Compiler name and version, and whether OpenMP was compiled in. */
const char *sph_compiler(void);

#ifdef __cplusplus
}
#endif

#endif
