/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * choices.h - the names of the case file's choices that the schema reads
 * (case.c) and the describer writes back (describe.c), each list
 * NULL-terminated in the order of its enum. Internal to src/case/.
 */
#ifndef SPH_CASE_CHOICES_H
#define SPH_CASE_CHOICES_H

extern const char *const sph_case_motion_names[];  /* sph_motion_kind: walls[k].motion.type */
extern const char *const sph_case_h_names[];       /* numerics.smoothing_length */
extern const char *const sph_case_leaving_names[]; /* sph_leaving_kind: geometry.leaving */

#endif
