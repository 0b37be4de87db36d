// SPDX-License-Identifier: BSD-3-Clause
// bench/dsph_io.cpp - particle files for the DualSPHysics side of bench/peers.
//
// DualSPHysics' case generator (GenCase) is a closed binary; the solver
// itself reads a case as an XML file and a particle file (CASE.bi4). This
// program writes the particle file, and reads the solver's Part_*.bi4
// output back, through DualSPHysics' own open data classes (JPartDataBi4
// in the DualSPHysics source tree the user names). It is compiled by
// bench/peers against that tree; nothing of DualSPHysics is committed here.
//
//   dsph_io case PARTICLES.csv DIR CASE DP H B RHO0 GAMMA MASSB MASSF
//       PARTICLES.csv: header line, then "x,y,kind,rho" rows (kind 0 fluid,
//       anything else a fixed boundary particle), boundary rows first.
//       Writes DIR/CASE.bi4 in the solver's x-z plane (y = 0).
//   dsph_io front DIR NBOUND FLOOR BAND
//       For every DIR/Part_NNNN.bi4: "time,step,front_x", front_x the
//       largest x of a fluid particle (id >= NBOUND) below FLOOR + BAND,
//       as sph's diagnostics define the surge front.
//   dsph_io case3 PARTICLES.csv DIR CASE DP H B RHO0 GAMMA MASSB MASSF
//       The same in 3-D: rows "x,y,z,kind,rho", boundary rows first.
//   dsph_io pressure DIR NBOUND H B RHO0 GAMMA MASS GZ NAME=X,Y,Z ...
//       For every DIR/Part_NNNN.bi4 (3-D): "time,NAME,..." with each
//       point's pressure as sph's pressure sensors read it
//       (src/analysis/probes.c): the Shepard average over fluid particles
//       (id >= NBOUND) within 2H of p_j + rho_j GZ (z - z_j), p_j from
//       Tait's equation with B, RHO0, GAMMA, V_j = MASS / rho_j, the cubic
//       spline of smoothing length H; 0 where sum V_j W < 0.1 (dry).
#include "JPartDataBi4.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

// case (dim 2: rows "x,y,kind,rho", written in the solver's x-z plane) and
// case3 (dim 3: rows "x,y,z,kind,rho"): the particle file of a case.
static int make_case(int argc, char **argv, int dim) {
  if (argc != 12) {
    std::fprintf(stderr,
                 "usage: dsph_io %s PARTICLES.csv DIR CASE DP H B RHO0 GAMMA MASSB MASSF\n",
                 dim == 2 ? "case" : "case3");
    return 2;
  }
  FILE *f = std::fopen(argv[2], "r");
  if (!f) {
    std::perror(argv[2]);
    return 1;
  }
  char line[512];
  if (!std::fgets(line, sizeof line, f)) {
    std::fprintf(stderr, "%s: empty\n", argv[2]);
    return 1;
  }
  std::vector<tfloat3> pos, vel;
  std::vector<float> rho;
  std::vector<unsigned> idp;
  unsigned nbound = 0;
  bool fluid_seen = false;
  tdouble3 lo = TDouble3(1e30), hi = TDouble3(-1e30);
  while (std::fgets(line, sizeof line, f)) {
    double x, y = 0.0, z, r;
    int kind;
    const int read = dim == 2 ? std::sscanf(line, "%lf,%lf,%d,%lf", &x, &z, &kind, &r)
                              : std::sscanf(line, "%lf,%lf,%lf,%d,%lf", &x, &y, &z, &kind, &r);
    if (read != dim + 2) {
      std::fprintf(stderr, "%s: bad row: %s", argv[2], line);
      return 1;
    }
    if (kind != 0) {
      if (fluid_seen) {
        std::fprintf(stderr, "%s: boundary rows must come first\n", argv[2]);
        return 1;
      }
      nbound++;
    } else {
      fluid_seen = true;
    }
    idp.push_back((unsigned)idp.size());
    pos.push_back(TFloat3((float)x, (float)y, (float)z));
    vel.push_back(TFloat3(0.f));
    rho.push_back((float)r);
    lo = TDouble3(std::fmin(lo.x, x), std::fmin(lo.y, y), std::fmin(lo.z, z));
    hi = TDouble3(std::fmax(hi.x, x), std::fmax(hi.y, y), std::fmax(hi.z, z));
  }
  std::fclose(f);
  const unsigned np = (unsigned)pos.size();
  JPartDataBi4 pd;
  pd.ConfigBasic(0, 1, "peers", dim == 2 ? "sph bench/peers" : "sph bench/peers_spheric2", argv[4],
                 dim == 2, 0.0, argv[3]);
  pd.ConfigParticles(np, nbound, 0, 0, np - nbound, lo, hi);
  pd.ConfigCtes(std::atof(argv[5]), std::atof(argv[6]), std::atof(argv[7]), std::atof(argv[8]),
                std::atof(argv[9]), std::atof(argv[10]), std::atof(argv[11]));
  pd.AddPartInfo(0, 0, np, 0, 0, 0, lo, hi);
  pd.AddPartData(np, idp.data(), pos.data(), vel.data(), rho.data());
  pd.SaveFileCase(argv[4]);
  std::printf("%u particles (%u boundary, %u fluid)\n", np, nbound, np - nbound);
  return 0;
}

// Loads DIR/Part_NNNN.bi4 (k = NNNN) into pd; false when there is no such file.
static bool load_part(const std::string &dir, unsigned k, JPartDataBi4 &pd) {
  char name[64];
  std::snprintf(name, sizeof name, "/Part_%04u.bi4", k);
  FILE *probe = std::fopen((dir + name).c_str(), "rb");
  if (!probe) return false;
  std::fclose(probe);
  pd.LoadFilePart(dir, k);
  return true;
}

// The n positions of a loaded part, in single or double precision as written.
static std::vector<tdouble3> positions(const JPartDataBi4 &pd, unsigned n) {
  std::vector<tdouble3> p(n);
  if (pd.Get_PosSimple()) {
    std::vector<tfloat3> pf(n);
    pd.Get_Pos(n, pf.data());
    for (unsigned i = 0; i < n; i++) p[i] = TDouble3(pf[i].x, pf[i].y, pf[i].z);
  } else {
    pd.Get_Posd(n, p.data());
  }
  return p;
}

// The cubic spline in 3-D, W(r, h) = 1/(pi h^3) {1 - 3/2 q^2 + 3/4 q^3; 1/4 (2 - q)^3}.
static double cubic3(double r, double h) {
  const double q = r / h, c = 1.0 / (M_PI * h * h * h);
  if (q < 1.0) return c * (1.0 - 1.5 * q * q + 0.75 * q * q * q);
  if (q < 2.0) return c * 0.25 * (2.0 - q) * (2.0 - q) * (2.0 - q);
  return 0.0;
}

// pressure: sph's sensor reading at points, from every part file.
static int pressures(int argc, char **argv) {
  if (argc < 11) {
    std::fprintf(stderr, "usage: dsph_io pressure DIR NBOUND H B RHO0 GAMMA MASS GZ NAME=X,Y,Z ...\n");
    return 2;
  }
  const std::string dir = argv[2];
  const unsigned nbound = (unsigned)std::strtoul(argv[3], nullptr, 10);
  const double h = std::atof(argv[4]), B = std::atof(argv[5]), rho0 = std::atof(argv[6]);
  const double gamma = std::atof(argv[7]), mass = std::atof(argv[8]), gz = std::atof(argv[9]);
  std::vector<std::string> names;
  std::vector<tdouble3> at;
  for (int k = 10; k < argc; k++) {
    const char *eq = std::strchr(argv[k], '=');
    double x, y, z;
    if (!eq || std::sscanf(eq + 1, "%lf,%lf,%lf", &x, &y, &z) != 3) {
      std::fprintf(stderr, "dsph_io pressure: expected NAME=X,Y,Z, got %s\n", argv[k]);
      return 2;
    }
    names.push_back(std::string(argv[k], (size_t)(eq - argv[k])));
    at.push_back(TDouble3(x, y, z));
  }
  std::printf("time");
  for (const std::string &n : names) std::printf(",%s", n.c_str());
  std::printf("\n");
  for (unsigned k = 0;; k++) {
    JPartDataBi4 pd;
    if (!load_part(dir, k, pd)) break;
    const unsigned n = pd.Get_Npok();
    std::vector<unsigned> id(n);
    std::vector<float> rho(n);
    pd.Get_Idp(n, id.data());
    const std::vector<tdouble3> p = positions(pd, n);
    pd.Get_Rhop(n, rho.data());
    std::printf("%.9g", pd.Get_TimeStep());
    for (const tdouble3 &a : at) {
      double num = 0.0, den = 0.0;
      for (unsigned i = 0; i < n; i++) {
        if (id[i] < nbound) continue;
        const double dx = a.x - p[i].x, dy = a.y - p[i].y, dz = a.z - p[i].z;
        const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
        if (r >= 2.0 * h) continue;
        const double w = mass / rho[i] * cubic3(r, h);
        const double pj = B * (std::pow(rho[i] / rho0, gamma) - 1.0) + rho[i] * gz * dz;
        num += w * pj;
        den += w;
      }
      std::printf(",%.9g", den < 0.1 ? 0.0 : num / den);
    }
    std::printf("\n");
  }
  return 0;
}

static int fronts(int argc, char **argv) {
  if (argc != 6) {
    std::fprintf(stderr, "usage: dsph_io front DIR NBOUND FLOOR BAND\n");
    return 2;
  }
  const std::string dir = argv[2];
  const unsigned nbound = (unsigned)std::strtoul(argv[3], nullptr, 10);
  const double top = std::atof(argv[4]) + std::atof(argv[5]);
  std::printf("time,step,front_x\n");
  for (unsigned k = 0;; k++) {
    JPartDataBi4 pd;
    if (!load_part(dir, k, pd)) break;
    const unsigned n = pd.Get_Npok();
    std::vector<unsigned> id(n);
    pd.Get_Idp(n, id.data());
    const std::vector<tdouble3> p = positions(pd, n);
    double front = -1e30;
    for (unsigned i = 0; i < n; i++)
      if (id[i] >= nbound && p[i].z < top && p[i].x > front) front = p[i].x;
    std::printf("%.9g,%u,%.9g\n", pd.Get_TimeStep(), pd.Get_Step(), front);
  }
  return 0;
}

int main(int argc, char **argv) {
  const std::string cmd = argc > 1 ? argv[1] : "";
  try {
    if (cmd == "case") return make_case(argc, argv, 2);
    if (cmd == "front") return fronts(argc, argv);
    if (cmd == "case3") return make_case(argc, argv, 3);
    if (cmd == "pressure") return pressures(argc, argv);
  } catch (const std::exception &e) {
    std::fprintf(stderr, "dsph_io: %s\n", e.what());
    return 1;
  }
  std::fprintf(stderr, "usage: dsph_io case|case3|front|pressure ...\n");
  return 2;
}
