/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * progress.h - a one-line progress bar on a terminal: simulated time against
 * the end time, steps, steps per second and the estimated time left. A case
 * with a stop condition (time.stop: front_at_wall) also shows how far the
 * condition has come (the front between where it started and where the run
 * stops): the bar shows the further of the two, and the time left is the
 * sooner of their estimates, each from the progress made since this
 * process started (so a restarted run estimates from its own pace). It
 * draws only when its stream is a terminal, at most a few times a second,
 * and erases itself when done. When the stream is not a terminal (a log
 * file, a batch system's output) it writes instead one line every
 * log_every seconds of wall time (the first after log_every: a shorter run
 * writes none): the simulated time, the step, the steps per second, the
 * elapsed time and the time left. Output files never see either.
 */
#ifndef SPH_PROGRESS_H
#define SPH_PROGRESS_H

#include <stdio.h>

typedef struct sph_progress {
  FILE *out;
  int enabled;      /* the bar: out is a terminal */
  double log_every; /* a line every log_every s when out is not a terminal (0: none) */
  double next_log;  /* the elapsed seconds of the next line */
  double t_end;
  double wall0, last_draw; /* monotonic seconds */
  int drawn;
  int started;         /* t0, m0 taken */
  double t0;           /* simulated time at the first update */
  long step0;          /* step at the first update */
  double m0;           /* the stop condition's measure at the first update */
  const char *measure; /* what the stop condition measures ("front"), or NULL */
} sph_progress;

/* The bar when out is a terminal, else a line every log_every seconds (0:
 * none); nothing when quiet. measure names what the stop condition
 * watches (NULL: the case has none). */
void sph_progress_init(sph_progress *pg, FILE *out, double t_end, const char *measure, int quiet,
                       double log_every);
/* now, stop: the stop condition's measure and the value that ends the run
 * (ignored without a measure). */
void sph_progress_update(sph_progress *pg, double t, long step, double now, double stop);
/* The fractions of the run done by time and by the stop condition (-1:
 * none), and the estimated seconds left (-1: unknown), as the bar shows
 * them after `elapsed` seconds. */
void sph_progress_state(const sph_progress *pg, double t, long step, double now, double stop,
                        double elapsed, double *by_time, double *by_stop, double *left);
/* Erases the bar. */
void sph_progress_done(sph_progress *pg);
/* Monotonic wall-clock seconds (for timing summaries). */
double sph_wall_seconds(void);

#endif
