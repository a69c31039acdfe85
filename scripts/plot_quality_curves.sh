#!/usr/bin/env bash
# Draws quality-over-time curves (the CSVs `m4d train --curve` writes) into one PNG:
#   scripts/plot_quality_curves.sh OUT.png "TITLE" LABEL=CURVE.csv [LABEL=CURVE.csv ...]
set -euo pipefail
if [ $# -lt 3 ]; then
  echo "usage: $0 OUT.png TITLE LABEL=CURVE.csv..." >&2
  exit 2
fi
out=$1 title=$2
shift 2
plots=()
for pair in "$@"; do
  label=${pair%%=*} csv=${pair#*=}
  [ -r "$csv" ] || { echo "$0: cannot read $csv" >&2; exit 1; }
  plots+=("'$csv' using 1:4 with linespoints title '$label'")
done
tmp="$out.tmp.png"
gnuplot <<GNUPLOT
set terminal pngcairo size 900,600 noenhanced
set output '$tmp'
set datafile separator ','
set key autotitle columnhead bottom right
set title '$title'
set xlabel 'wall time of m4d train (minutes, evaluation excluded)'
set ylabel 'held-out PSNR (dB)'
set grid
plot $(IFS=,; echo "${plots[*]}")
GNUPLOT
mv "$tmp" "$out"
