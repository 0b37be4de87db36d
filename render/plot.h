/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * plot.h - the CSV plot mode: lines and points from CSV columns on linear
 * axes with ticks, labels, grid and a legend (e.g. the dam-break front
 * against Martin & Moyce's measurements, energy deviation against time).
 */
#ifndef SPH_RENDER_PLOT_H
#define SPH_RENDER_PLOT_H

#include "core/error.h"
#include "options.h"

/* Draws the series of o into o->output (a PNG). */
int rplot_run(const roptions *o, sph_error *err);

#endif
