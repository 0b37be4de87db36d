/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * case.h - a case: everything a run needs, read from a YAML case file.
 *
 * The case file is read with libyaml into a tree, `--set key=value`
 * overrides are applied to that tree, and the tree is then validated
 * strictly against the schema documented in doc/case-files.md:
 * an unknown key, a wrong type, a missing required key or a value out of
 * range is an error naming the file, line, key and what was expected.
 * Choices are names (kernel: cubic_spline), never numbers.
 *
 * After sph_case_load() every field below holds its final value: defaults
 * are filled in and derived values (sound_speed, h) are computed.
 */
#ifndef SPH_CASE_H
#define SPH_CASE_H

#include <stddef.h>

#include "analysis/probes.h"
#include "core/dim.h"
#include "core/error.h"
#include "physics/models.h"
#include "walls/wall_types.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  SPH_INTEGRATOR_PREDICTOR_CORRECTOR = 0, /* paper B eq. (7)-(8) */
  SPH_INTEGRATOR_LEAPFROG = 1             /* paper A eq. (17)-(19) */
} sph_integrator_kind;
typedef enum {
  SPH_DT_PAPER_B = 0, /* paper B §2.6: min 0.3 h/(c + max |h v.r/r^2|) */
  SPH_DT_CFL = 1,     /* paper A eq. (20): C min h / max(c + |v|) */
  SPH_DT_FIXED = 2    /* a constant step from the case */
} sph_dt_rule;
typedef enum { SPH_STOP_NONE = 0, SPH_STOP_FRONT_AT_WALL = 1 } sph_stop_kind;
/* geometry.leaving: a fluid particle outside the domain stops the run as
 * a blow-up, or is taken out of it (solver/outflow.h) */
typedef enum { SPH_LEAVING_STOP = 0, SPH_LEAVING_REMOVE = 1 } sph_leaving_kind;
/* numerics.scheme: a named set of defaults for the pressure term, the
 * dissipation, the diffusion, the kernel, the step rule and the tank's
 * wall model (src/case/presets.c, doc/method.md, Schemes); the keys a case
 * gives win. In the order of the presets' table. */
typedef enum {
  SPH_SCHEME_RIEMANN = 0,  /* the default: Zhang et al. 2017's pressure, Wendland h = 2 dx,
                              Adami walls */
  SPH_SCHEME_PAPER_A = 1,  /* the dam-break paper's base: cubic spline h = 1.3 dx, dynamic walls */
  SPH_SCHEME_PAPER_B = 2,  /* the breaking-wave paper's base: the same keys */
  SPH_SCHEME_DELTA_SPH = 3 /* Marrone et al. 2011: alpha 0.02, antuono 0.1, Morris, mdbc */
} sph_scheme_kind;
const char *sph_scheme_name(sph_scheme_kind s);

/* Names of the choices, for messages and snapshots ("cubic_spline", ...). */
const char *sph_kernel_name(sph_kernel_kind k);
const char *sph_integrator_name(sph_integrator_kind k);
const char *sph_dt_rule_name(sph_dt_rule r);
const char *sph_boundary_name(sph_boundary_kind b);
const char *sph_stop_name(sph_stop_kind s);
const char *sph_viscosity_name(sph_viscosity_kind v);

/* The shape of a fluid block (doc/case-files.md, Shapes): the box itself,
 * or a shape whose inside keeps the box's lattice points (the box then
 * its bounding box). A polygon's vertices are (x, y) in 2-D and (x, z) in
 * 3-D, where it is a prism across the box's y range. */
typedef enum {
  SPH_SHAPE_BOX = 0,      /* the box lo..hi */
  SPH_SHAPE_POLYGON = 1,  /* a simple polygon, vertices in order either way round */
  SPH_SHAPE_BALL = 2,     /* a circle in 2-D, a sphere in 3-D: centre, radius */
  SPH_SHAPE_CYLINDER = 3, /* 3-D: the axis from `centre` to `end`, radius */
  SPH_SHAPE_MESH = 4      /* 3-D: a closed triangle surface read from a mesh file */
} sph_shape_kind;
typedef struct sph_mesh sph_mesh; /* a closed triangle surface (src/case/mesh.c) */
typedef struct sph_shape {
  sph_shape_kind kind;
  size_t n;         /* polygon: vertices */
  double *vertex;   /* polygon: 2n numbers (x, up), up y in 2-D, z in 3-D; owned by the case */
  double centre[3]; /* ball: its centre; cylinder: one end of its axis */
  double end[3];    /* cylinder: the other end of its axis */
  double radius;    /* ball, cylinder */
  sph_mesh *mesh;   /* mesh: the surface, owned by the case */
  char *file;       /* mesh: the file as the case names it, owned by the case */
  double scale;     /* mesh: each coordinate v of the file becomes scale v + offset */
  double offset[3];
} sph_shape;

/* A block of fluid filled on the lattice of spacing dx: particle centres
 * at (x0 + (i + 1/2) dx, y0 + (j + 1/2) dx) inside [x0,x1] x [y0,y1], and
 * inside its shape. */
typedef struct sph_fluid_block {
  SPH_COMPONENTS(double, lo, x0, y0, z0); /* lower corner (m; z up in 3-D, doc/dimensions.md) */
  SPH_COMPONENTS(double, hi, x1, y1, z1); /* upper corner (m) */
  SPH_COMPONENTS(double, v, vx, vy, vz);  /* initial velocity, default 0 */
  int hydrostatic; /* initial density from rho0 g (surface - height), default 1 */
  double surface;  /* free-surface height for the hydrostatic start, default the block's top
                      (y1; z1 in 3-D) */
  double jitter;   /* perturbed start: each particle moved by up to jitter*dx in x and in y
                      (uniform, seeded), in [0, 0.5); default 0 = on the lattice */
  int seed;        /* seed of the jitter, default 1 */
  sph_shape shape; /* the box (default) or the shape that clips it */
  size_t line;     /* the block's line in the case file (0: from --set) */
} sph_fluid_block;

const char *sph_probe_kind_name(sph_probe_kind k);

typedef struct sph_case {
  char *name;        /* required, [A-Za-z0-9_.-]+ */
  char *description; /* optional, "" by default */
  char *path;        /* the file it was read from */
  char *text;        /* the file's full text (stored in snapshots) */
  char *overrides;   /* the --set overrides, "k=v" joined by "\n" ("" if none) */
  int dimension;     /* 2 or 3: SPH_DIM, the build's (a case of the other is refused) */

  /* physics */
  double rho0;             /* reference density, default 1000 */
  double gravity[SPH_DIM]; /* default (0, -9.81); (0, 0, -9.81) in 3-D */
  double sound_speed; /* c0 (m/s), resolved: value, or factor*sqrt(2|g|height), or factor*speed */
  double alpha, beta; /* artificial viscosity, paper A eq. (15)-(16); defaults 0, 0 */
  double eta;         /* eta = eta * h_ij, default 0.1 (eta^2 = 0.01 h^2) */
  double xsph;        /* XSPH epsilon, paper B eq. (6); default 0 = off */
  int negative_pressure;  /* 1 (default): the fluid's pressure may fall below 0; 0: its density
                             is held at rho0 or above, so it holds no tension (physics/eos.h) */
  int riemann;            /* Riemann-solver pressure (Zhang et al. 2017), default off */
  double riemann_limiter; /* its dissipation limiter eta, default 3 */
  int sps;                /* SPS turbulence (paper B eq. 4), default off */
  double sps_cs, sps_ci;  /* Smagorinsky C_s = 0.12 and C_I = 0.00066; Delta = dx */
  sph_viscosity_kind viscosity; /* laminar viscosity model, default none */
  double mu;                    /* dynamic viscosity (Pa s), required unless viscosity is none */
  int gradient_correction;   /* stress tensor: kernel-gradient correction (src/solver/forces.h) */
  double repulsion;          /* D of the Lennard-Jones wall force (m^2/s^2), paper A eq. (22);
                                default 5 |g| H, H the deepest fluid block */
  int air;                   /* physics.air: the tank's free volume filled with air, a second
                                phase (doc/method.md, Two phases); default 0 */
  sph_material air_material; /* its material (physics/models.h), the keys of physics.air:
                                rho0 1.2 kg/m^3, exponent 1, mu 1.8e-5 Pa s by default
                                (src/case/air.c) */

  /* numerics */
  sph_scheme_kind scheme; /* numerics.scheme, default riemann */
  char *scheme_kept;      /* the keys of the scheme's set the case gives itself (they keep the
                             case's values), joined by ", "; "" if none or no scheme */
  double dx;              /* initial particle spacing (required) */
  double h_factor;        /* h = h_factor * dx, default 1.3 */
  double h;               /* derived: h_factor * dx (h0 when variable) */
  int variable_h;         /* h = h0 (rho0/rho)^(1/2), paper B §2.1; default constant */
  sph_kernel_kind kernel;
  sph_integrator_kind integrator;
  sph_dt_rule dt_rule;            /* default paper_b */
  double dt_factor;               /* CFL coefficient, default 0.3 */
  double dt_fixed;                /* required when dt_rule == SPH_DT_FIXED */
  double density_limit;           /* blow-up when |rho/rho0 - 1| exceeds it; default 0.3 */
  sph_filter_kind density_filter; /* paper B §2.8, default none */
  int filter_every;               /* steps between filter applications, default 30 */
  sph_diffusion_kind diffusion;   /* numerics.density_diffusion.model, default none */
  double diffusion_delta;         /* numerics.density_diffusion.delta, default 0.1 */
  int shifting;                /* numerics.shifting given (src/physics/shifting.h), default off */
  double shifting_coefficient; /* numerics.shifting.coefficient A, default 2 */
  int corrected_gradient;      /* numerics.gradient_correction: the pressure and continuity
                                  terms with the kernel-gradient correction (src/solver/forces.h),
                                  default off */

  /* time */
  double t_end;           /* required */
  double output_interval; /* required unless output_times is given */
  size_t n_output_times;  /* time.output_times: extra output times, increasing */
  double *output_times;
  sph_stop_kind stop; /* default none */

  /* geometry */
  sph_tank tank;
  size_t n_fluid;
  sph_fluid_block *fluid; /* at least one block */
  size_t n_walls;
  sph_wall_segment *walls;
  int periodic;               /* 1 if geometry.periodic_x (3-D: or _y, _z) was given */
  double periodic_range[2];   /* its range: particles leaving one side re-enter at the other */
  int domain_set;             /* 1 if geometry.domain was given */
  double domain[2 * SPH_DIM]; /* x0, x1, y0, y1 (, z0, z1) */
  sph_leaving_kind leaving;   /* what a fluid particle leaving the domain does (geometry.leaving) */

  /* free surface (paper A §7) */
  double fs_radius_factor; /* circle radius = factor * h, default 1 */
  double fs_h_factor;      /* h* = k h on surface particles; 0 = off (default) */

  /* output */
  int snapshots;           /* write HDF5 snapshots, default 1 */
  int output_free_surface; /* write the free_surface field, default 0 */
  int energy;              /* energy ledger (output.energy), default 0 */
  size_t n_gauges;         /* output.gauges: wave gauges (gauges.csv) */
  double *gauges;          /* n_gauges x (SPH_DIM - 1): each gauge's x (2-D), or x, y (3-D: the
                              vertical line at (x, y)) */
  size_t n_probes;         /* output.probes (probes.csv) */
  sph_probe *probes;
  double probe_interval; /* output.probe_interval: time between probe rows, 0 = every step */

  /* resources (not case keys) */
  double est_fluid, est_wall; /* particles the geometry makes at dx, estimated from above */
  size_t dx_line;             /* the line of numerics.dx in the file; 0: from a --set */
  double max_particles;       /* the bound sph_sim_create enforces; 0: sph_case_default_max */

  int periodic_axis;  /* geometry.periodic_*: the axis that wraps, 0 (x), 1 (y), 2 (z) */
  size_t n_obstacles; /* geometry.obstacles (boxes or shapes of wall particles), then
                         geometry.vessels (shapes holding the fluid) */
  sph_obstacle *obstacles;
  sph_shape *obstacle_shape; /* each obstacle's shape (SPH_SHAPE_BOX for a box) */
  size_t n_vessels;          /* the last n_vessels of obstacles are geometry.vessels */
} sph_case;

/* Bytes per particle a run needs, as the bound reckons it: measured peak
 * RSS per extra particle is about 560 bytes for the plain dam break
 * (bench/results/features.md) and about 890 with the stress tensor, the
 * energy ledger and free-surface flags at h* = 2h together (doc/memory.md). */
#define SPH_BYTES_PER_PARTICLE 1200.0
/* The largest particle count the storage can index (neighbour rows hold
 * 32-bit indices). */
#define SPH_MAX_PARTICLES_HARD 2147483647.0
/* The default bound: half this machine's physical memory at
 * SPH_BYTES_PER_PARTICLE (at most SPH_MAX_PARTICLES_HARD). */
double sph_case_default_max(void);
/* Whether the estimated particle count (est_fluid + est_wall, mirror
 * particles counted as fluid where the case has mirror walls) is within
 * max (0: the default) and the hard bound: 0, or -1 with an error naming
 * numerics.dx (file:line), the count, the memory and the bound. Checked by
 * sph_sim_create before any particle is made (issue 21, D3, D4). */
int sph_case_check_size(const sph_case *c, double max, sph_error *err);

/* The lattice points lo + (i + 1/2) dx, i = 0, 1, ..., a fluid block's
 * range [lo, hi] holds: floor((hi - lo) / dx) with a tolerance for the
 * rounding of hi - lo, relative to the coordinates (a block far from the
 * origin, x + 1e6 m, holds what it holds at the origin; issue 61, E8). */
long sph_case_lattice_points(double lo, double hi, double dx);

/* The fluid particles a block makes at spacing dx (its box's lattice
 * points, those inside its shape), and its area (2-D) or volume (3-D):
 * the box's or its shape's (doc/case-files.md, Shapes). */
long sph_case_block_points(const sph_fluid_block *f, double dx);
double sph_case_block_measure(const sph_fluid_block *f);

/* The name of gauge g's column in gauges.csv ("eta_X", in 3-D "eta_X_Y"):
 * unique among the case's gauges (the reader refuses two with one name). */
void sph_case_gauge_column(const sph_case *c, size_t g, char *buf, size_t len);

/* The case file's `dimension` (2 when absent) into *dim, after the
 * overrides (a --set dimension=3 counts): what `sph` reads to choose the
 * build that runs the case. Non-zero with err (file, line, key) if the file
 * cannot be read or the value is not 2 or 3. */
int sph_case_file_dimension(const char *path, const char *const *set, size_t n_set, int *dim,
                            sph_error *err);
/* The same from text in memory (sph_case_read_text's); `origin` names it. */
int sph_case_text_dimension(const char *text, size_t len, const char *origin,
                            const char *const *set, size_t n_set, int *dim, sph_error *err);
/* A case file's text, read once (a FIFO, /dev/stdin or <(...) can be read
 * only once), at most 1 MiB, into a malloc'd *text of *len bytes. */
int sph_case_read_text(const char *path, char **text, size_t *len, sph_error *err);

/* Reads and validates a case file, applying n_set overrides of the form
 * "dotted.key=yaml-value" (e.g. "numerics.dx=0.001"). On failure returns
 * non-zero with err naming file, line, key and expectation, and leaves *c
 * empty (safe to sph_case_free). */
int sph_case_load(const char *path, const char *const *set, size_t n_set, sph_case *c,
                  sph_error *err);
/* The same from text in memory; `origin` names it in messages. */
int sph_case_parse(const char *text, size_t len, const char *origin, const char *const *set,
                   size_t n_set, sph_case *c, sph_error *err);
void sph_case_free(sph_case *c);
/* The resolved parameters and choices of a loaded case as "dotted.key: value"
 * lines, one per schema key in schema order (every default filled in), for
 * the start-of-run listing and the snapshots' "parameters" attribute.
 * Numbers printed with %.17g so they read back exactly. malloc'ed; free it. */
char *sph_case_describe(const sph_case *c);
/* The commented physics.air block of `sph new`'s template: a line for the
 * key and one for each key of the air's material, with its example value
 * and what it is (src/case/air.c), into buf (snprintf's return). */
int sph_case_air_template(char *buf, size_t n);
/* Whether the case needs free-surface detection (the field is asked for
 * in the output, or h* is set). */
int sph_case_needs_free_surface(const sph_case *c);
/* Whether the tank or a wall segment has the boundary model b. */
int sph_case_has_boundary(const sph_case *c, sph_boundary_kind b);

/* The directory of installed example cases: $SPH_CASES_DIR, else
 * <datadir>/sph/cases of the library's installation. */
const char *sph_case_cases_dir(void);
/* The case file a user names with arg: arg itself when it names a file,
 * else for a bare name (no '/') cases/NAME.yaml here, then NAME.yaml among
 * the installed cases (".yaml" may be given). Returns arg or buf (n bytes),
 * or NULL with why (nw bytes) saying where it looked and which cases are
 * installed. */
const char *sph_case_find(const char *arg, char *buf, size_t n, char *why, size_t nw);

#ifdef __cplusplus
}
#endif

#endif
