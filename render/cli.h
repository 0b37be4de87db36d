/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * cli.h - the command line of sph-render.
 */
#ifndef SPH_RENDER_CLI_H
#define SPH_RENDER_CLI_H

#include <stdio.h>

#include "core/error.h"
#include "options.h"

/* Fills o from argv. Returns 0 to go on, 1 if the command was --help or
 * --version (already printed), -1 with err on a bad command line. */
int rcli_parse(int argc, char **argv, roptions *o, sph_error *err);
void rcli_usage(FILE *fp);

#endif
