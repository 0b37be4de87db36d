/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * probes.h - what a run's probes read (output.probes, probes.csv).
 *
 *   pressure  the pressure a wall sensor of the given diameter reads: the
 *             Shepard-normalised SPH interpolation of the fluid's pressure,
 *             p(x) = sum_j p*_j V_j W(x - x_j) / sum_j V_j W(x - x_j) over fluid
 *             particles j (V = m/rho), p*_j = p_j + rho_j g . (x - x_j) the
 *             particle's pressure carried to x along the hydrostatic
 *             gradient (at a wall face or a floor the kernel sees one side
 *             only, and the plain average of a hydrostatic field is then off
 *             by rho g times the particles' mean distance, about 1.3 dx:
 *             3 % of rho g H at H = 20 dx; the carried value is exact for it,
 *             and changes an impact peak by less than rho g 2h), at
 *             SPH_PROBE_FACE_POINTS points
 *             spread evenly over the sensor's face (one point for diameter
 *             0), averaged. A point whose kernel sum sum_j V_j W is below
 *             SPH_PROBE_WET_SUM (a tenth of a full neighbourhood; half a
 *             neighbourhood is what a point on a wall face sees) is dry and
 *             reads 0: spray passing the sensor is not a pressure.
 *             A sensor may state another interpolation, so that a
 *             peer's sensor can be read as the peer reads it (bench/
 *             peers_trixi: TrixiParticles' dam-break sensors): `points`
 *             face points instead of 5 (2-D: evenly spaced over the face,
 *             both ends included; 3-D: 1 or 5), the kernel's h times
 *             `smoothing`, `clip_negative` (each particle's pressure below
 *             0 read as 0, as sensors that clip cavitation do),
 *             `hydrostatic: false` (p_j as it is, not carried) and
 *             `wet_sum` (the kernel sum below which a point is dry).
 *             With `low_pass` (Hz) the sensor's response too: a
 *             first-order low-pass filter of the reading at that cut-off
 *             (sph_probe_low_pass), in a column of its own beside the raw
 *             one, so that a comparison says which it used.
 *   level     the water depth at x above the bed: the highest fluid particle
 *             centre within dx of x, plus dx/2 (the top of its cell), less
 *             the floor; 0 where no fluid is. Always finite. With `wetted`
 *             the wetted length of a wire gauge along the vertical line
 *             instead: the integral along the line of the fluid's volume
 *             fraction sum_j V_j W(x - x_j), that is sum_j V_j K(rho_j) with
 *             rho_j the particle's distance from the line and K(rho) the
 *             integral of W(sqrt(rho^2 + s^2)) over s (Simpson, 64
 *             intervals). A column of still water reads its depth (a
 *             lattice: within the kernel sum's 1-2 %); spray or a jet
 *             above it adds its own thickness, not its height.
 *   velocity  vx and vy, Shepard-normalised as the pressure, at a point; 0
 *             where dry.
 * In 3-D (core/dim.h; z up) a pressure sensor is a disc on a wall face,
 * given by its centre, its normal and its diameter: its face points are the
 * centre and four points at R/sqrt(2) from it (the circle that halves the
 * disc's area) along two directions across the normal; a level gauge is the
 * vertical line at (x, y), read from the particles within dx of it
 * horizontally; a velocity probe reads vx, vy, vz.
 * Each reads the particles alone, serially in storage order (a sensor's
 * face points in one pass, each point's sums in that order): the same bits
 * for any thread count and across a restart. A run reads its probes one to
 * a thread (solver/run.c).
 */
#ifndef SPH_PROBES_H
#define SPH_PROBES_H

#include <stddef.h>

#include "core/particles.h"
#include "physics/models.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SPH_PROBE_FACE_POINTS 5
#define SPH_PROBE_MAX_POINTS 64
#define SPH_PROBE_WET_SUM 0.1

typedef enum {
  SPH_PROBE_PRESSURE = 0, /* a wall pressure sensor: p (Pa) */
  SPH_PROBE_LEVEL = 1,    /* a water-level gauge: depth above the bed (m) */
  SPH_PROBE_VELOCITY = 2  /* a point: vx, vy (m/s) */
} sph_probe_kind;

typedef struct sph_probe {
  char name[65]; /* [A-Za-z0-9_.-], 1 to 64 characters, unique in a case */
  sph_probe_kind kind;
  double x, y; /* the point (pressure, velocity); x of a level gauge ((x, y) in 3-D) */
#if SPH_DIM == 3
  double z;         /* the point's height (pressure, velocity) */
  double normal[3]; /* pressure: the unit normal of the sensor's face */
#endif
  double diameter; /* pressure: the width of the sensor's face (m); 0 = a point */
  int along_x;     /* pressure (2-D): the face spans x (a sensor in a floor); default y */
  double low_pass; /* pressure: the cut-off (Hz) of the sensor's first-order response, 0 = none */
  int wetted;      /* level: the wetted length of a wire gauge instead of the highest particle */
  /* pressure: the interpolation, where it is not the default (0 in each means the default) */
  int points;        /* face points, 1 .. SPH_PROBE_MAX_POINTS (default SPH_PROBE_FACE_POINTS;
                        1 for diameter 0) */
  double smoothing;  /* the interpolation's h over the case's (default 1) */
  int clip_negative; /* each particle's pressure below 0 read as 0 */
  int no_carry;      /* each particle's pressure as it is, not carried along g */
  double wet_sum;    /* the kernel sum below which a point is dry (default SPH_PROBE_WET_SUM) */
} sph_probe;

/* Whether q has a sensor response (a pressure probe with low_pass > 0). */
static inline int sph_probe_filtered(const sph_probe *q) {
  return q->kind == SPH_PROBE_PRESSURE && q->low_pass > 0.0;
}
/* The number of CSV columns of a probe: velocity 2 (3 in 3-D), a pressure
 * probe with low_pass 2 (raw, filtered), else 1. */
int sph_probe_columns(const sph_probe *q);
/* The header of its columns, "name (Pa)", "name (Pa),name_low_pass (Pa)"
 * or "name_vx (m/s),name_vy (m/s)", written to buf with a leading comma. */
void sph_probe_header(const sph_probe *q, char *buf, size_t len);
/* Its reading on the particles p (with the kernel, h the smoothing length,
 * dx the particle spacing, floor_y the bed's height, g the gravity) into
 * out[0] (a velocity probe: out[0 .. SPH_DIM - 1]); a low-pass column is
 * sph_probe_low_pass's, from the series of readings. */
void sph_probe_read(const sph_probe *q, const sph_particles *p, sph_kernel_kind kernel, double h,
                    double dx, double floor_y, const double g[SPH_DIM], double *out);
/* One step of a first-order low-pass filter (time constant
 * tau = 1 / (2 pi cutoff)) from its output y at the previous reading to the
 * reading x a time dt later, the reading held over the interval (exact for
 * a piecewise-constant input): y + (1 - exp(-dt / tau)) (x - y). A series
 * starts with y = its first reading. */
double sph_probe_low_pass(double y, double x, double dt, double cutoff);

#ifdef __cplusplus
}
#endif

#endif
