# SPDX-License-Identifier: BSD-3-Clause
# bench/front_error.awk - the surge front of a dam-break run against Martin
# & Moyce (1952): the relative error of Z = x/a at each measured T with
# Z < 3.9, the run's front interpolated linearly in time (after its last
# row: its last value). Used by bench/run, bench/pareto and bench/peers.
#
#   awk -F, -v a=A [-v col=K] [-v x0=X] [-v fmt=F] -f bench/front_error.awk \
#       RUN.csv tests/data/martin_moyce_1952_front_n2_2.csv
#
# RUN.csv: a header line, then rows with the time (s) in column 1 and the
# front x (m) in column K (default 2; diagnostics.csv: 5); X (default 0) is
# subtracted from x first (the left wall face's x). Prints the RMS and the
# largest error in percent through printf format F (default "%.2f,%.2f";
# "nan,nan" when no experimental point is used).
BEGIN { if (col == "") col = 2; if (fmt == "") fmt = "%.2f,%.2f" }
FNR == 1 { next }
FILENAME == ARGV[1] { n++; t[n] = $1; x[n] = $col - x0; next }
/^#/ { next }
{
  if ($2 >= 3.9) next
  tt = $1 / sqrt(2 * 9.81 / a); z = x[n] / a
  for (i = 2; i <= n; i++) if (tt <= t[i]) { z = (x[i-1] + (x[i] - x[i-1]) * (tt - t[i-1]) / (t[i] - t[i-1])) / a; break }
  e = (z - $2) / $2; s += e * e; m++; if (e < 0) e = -e; if (e > mx) mx = e
}
END { if (m == 0) printf "nan,nan"; else printf fmt, 100 * sqrt(s / m), 100 * mx }
