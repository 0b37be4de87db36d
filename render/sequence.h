/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * sequence.h - the snapshot modes of sph-render: one frame per snapshot,
 * a figure of panels, or runs compared side by side at matching times.
 */
#ifndef SPH_RENDER_SEQUENCE_H
#define SPH_RENDER_SEQUENCE_H

#include "core/error.h"
#include "options.h"

/* Renders what o asks for. Returns 0 on success; -1 with err if nothing
 * could start (bad inputs, no range, bad layout: no file is written); 1 if
 * some images failed (each already reported on stderr, the rest written). */
int rsequence_run(const roptions *o, const char *prog, sph_error *err);

#endif
