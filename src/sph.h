/*
 * sph.h - the public API of libsph in one include.
 */
#ifndef SPH_H
#define SPH_H

#include "error.h"
#include "particles.h"
#include "kernel.h"
#include "eos.h"
#include "grid.h"
#include "forces.h"
#include "boundary.h"
#include "integrate.h"
#include "diag.h"
#include "case.h"
#include "snapshot.h"
#include "sim.h"
#include "run.h"
#include "version.h"
#include "filter.h"
#include "wavemaker.h"
#include "parallel.h"
#include "freesurface.h"
#include "turbulence.h"
#include "analytic.h"
#include "wave_face.h"
#include "wall_velocity.h"

#endif
