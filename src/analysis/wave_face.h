/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * wave_face.h - the front face of a breaking wave: how steep it is, and
 * whether it has passed vertical (paper B §4.3: "the front of the wave
 * becomes steeper and at t = 0.38 T vertical; a jet is then thrown from
 * the crest").
 *
 * Definition (a wave running towards +x over still water of level `level`):
 *   crest   the highest fluid particle with x in [x0, x1] (ties: larger x);
 *   y_lo    level + (crest_y - level) / 4, the foot of the measured face;
 *   toe     the first column of width dx ahead of the crest whose highest
 *           fluid particle lies below y_lo (or that is empty): the face,
 *           and a jet thrown over it, lie between the crest and the toe;
 *   bands   horizontal bands of height dx from y_lo up to the crest; in
 *           each, x_f = the largest x of the fluid particles with x in
 *           [x0, toe) - the leading edge of the face at that height (under
 *           a jet, the face below it; the toe column holds no water at
 *           band heights, so no wave ahead of the toe counts);
 *   angle   90 + atan(s) in degrees, s the least-squares slope dx_f/dy over
 *           the bands: 90 is a vertical face, less leans back (a face that
 *           rises towards the crest behind its foot), more overhangs (the
 *           upper face is ahead of the lower: a jet).
 * Heights are y in 2-D and z in 3-D (z up); in 3-D the particles of the
 * whole width count, so the face is that of the water's profile seen from
 * the side (crest_y is then the crest's z).
 * The particles' order does not matter (sums run over bands in order).
 */
#ifndef SPH_WAVE_FACE_H
#define SPH_WAVE_FACE_H

#include "core/error.h"
#include "core/particles.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sph_wave_face {
  double crest_x, crest_y; /* the highest fluid particle in the window */
  double toe_x;            /* end of the face region (see above) */
  double angle;            /* degrees: < 90 leaning back, 90 vertical, > 90 overhanging */
  int bands;               /* bands holding particles, used in the fit */
} sph_wave_face;

/* Measures the face of the highest crest in [x0, x1]. Returns 0 with *f
 * filled, 1 when there is no face to measure (no fluid in the window, a
 * crest less than 4 dx above the level, or fewer than 3 bands; f->angle is
 * then NaN), or -1 with err for bad arguments. */
int sph_wave_face_measure(const sph_particles *p, double level, double dx, double x0, double x1,
                          sph_wave_face *f, sph_error *err);

#ifdef __cplusplus
}
#endif

#endif
