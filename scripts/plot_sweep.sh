#!/usr/bin/env bash
# The envelope of a Loads/Sweep run: the largest bottom and top principal
# stress, the smallest LTE and the contact area against the axles' offset
# along the path, from DIR/sweep.csv, into DIR/sweep.png (gnuplot).
# usage: bash scripts/plot_sweep.sh DIR [title]
set -euo pipefail
dir=${1:?usage: plot_sweep.sh DIR [title]}
title=${2:-Loads/Sweep}
[ -f "$dir/sweep.csv" ] || { echo "no $dir/sweep.csv" >&2; exit 1; }
gnuplot <<GP
set datafile separator ','
set terminal pngcairo size 1100,440 font ',11'
set output '$dir/sweep.png'
set grid
set key below
set multiplot layout 1,2 title '$title'
set xlabel 'offset of the axles along the path [m]'
set ylabel 'largest principal stress [kPa]'
plot '$dir/sweep.csv' skip 1 using (sqrt((\$2-$(awk -F, 'NR==2{print $2}' "$dir/sweep.csv"))**2+(\$3-$(awk -F, 'NR==2{print $3}' "$dir/sweep.csv"))**2)):7 with linespoints lw 2 pt 7 title 'bottom fibre', \
     '' skip 1 using (sqrt((\$2-$(awk -F, 'NR==2{print $2}' "$dir/sweep.csv"))**2+(\$3-$(awk -F, 'NR==2{print $3}' "$dir/sweep.csv"))**2)):10 with linespoints lw 2 pt 5 title 'top fibre'
set ylabel 'LTE, contact area fraction'
set yrange [0:1.05]
plot '$dir/sweep.csv' skip 1 using (sqrt((\$2-$(awk -F, 'NR==2{print $2}' "$dir/sweep.csv"))**2+(\$3-$(awk -F, 'NR==2{print $3}' "$dir/sweep.csv"))**2)):14 with linespoints lw 2 pt 7 title 'smallest LTE of the joints', \
     '' skip 1 using (sqrt((\$2-$(awk -F, 'NR==2{print $2}' "$dir/sweep.csv"))**2+(\$3-$(awk -F, 'NR==2{print $3}' "$dir/sweep.csv"))**2)):13 with linespoints lw 2 pt 5 title 'contact area fraction'
unset multiplot
GP
echo "$dir/sweep.png"
