/*
 * progress.h - a one-line progress bar on a terminal: simulated time against
 * the end time, steps, steps per second and the estimated time left. It
 * draws only when its stream is a terminal, at most a few times a second,
 * and erases itself when done. Output files never see it.
 */
#ifndef SPH_PROGRESS_H
#define SPH_PROGRESS_H

#include <stdio.h>

typedef struct sph_progress {
  FILE *out;
  int enabled;
  double t_end;
  double wall0, last_draw; /* monotonic seconds */
  int drawn;
} sph_progress;

/* Enabled only when out is a terminal and quiet is 0. */
void sph_progress_init(sph_progress *pg, FILE *out, double t_end, int quiet);
void sph_progress_update(sph_progress *pg, double t, long step);
/* Erases the bar. */
void sph_progress_done(sph_progress *pg);
/* Monotonic wall-clock seconds (for timing summaries). */
double sph_wall_seconds(void);

#endif
