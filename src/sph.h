/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * sph.h - the public API of libsph in one include: what a program needs to
 * load a case, run it, read and write snapshots, read the diagnostics and
 * measure a state against analytic solutions. Everything else under src/
 * is internal to the library and not installed.
 *
 *   core/error.h        sph_error: every call reports failure through it
 *   core/version.h      sph_version(), the program's version string
 *   core/particles.h    the particle store (structure of arrays)
 *   io/snapshot.h       HDF5 snapshots and their XDMF index
 *   io/csv.h            numeric CSV tables (diagnostics, probes, reference data)
 *   case/case.h         case files: load, validate, describe
 *   solver/sim.h        a simulation: create, step, restart
 *   solver/run.h        the run loop with outputs, signals and progress
 *   solver/procs.h      the processes of a run under mpirun (--with-mpi)
 *   solver/bindings.h   what a binding from another language needs (python/sph)
 *   solver/diag.h       the diagnostics row of a state (energy, momentum, front)
 *   analysis/analytic.h, analysis/wave_face.h
 *                       analytic profiles and the wave-face measure
 *   physics/models.h, walls/wall_types.h, walls/wavemaker.h
 *                       the named choices and wall types a case holds
 */
#ifndef SPH_H
#define SPH_H

#include "analysis/analytic.h"
#include "analysis/wave_face.h"
#include "case/case.h"
#include "core/error.h"
#include "core/particles.h"
#include "core/version.h"
#include "io/csv.h"
#include "io/snapshot.h"
#include "solver/bindings.h"
#include "solver/diag.h"
#include "solver/procs.h"
#include "solver/run.h"
#include "solver/sim.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef __cplusplus
}
#endif

#endif
