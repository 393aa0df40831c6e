# Figures of one example from the CSV files of scripts/paper_examples.sh:
# w, Mx (at the Gauss points nearest the centre line) and q along y = 0 for
# the three variants, and the contact map of the exact solution.
# usage: gnuplot -e "example='example2'" scripts/paper_figures.gp
dir = 'output/'.example
set datafile separator ','
set terminal pngcairo size 800,620 font ',11'
set key below
set grid
set xlabel 'x [m]'
variants = 'paper exact bonded'
titles = "'collocation + element exclusion (paper)' 'Galerkin + active set (exact)' 'Galerkin, bonded'"

set output dir.'/w-centre-line.png'
set title example.': deflection along y = 0'
set ylabel 'w [m] (downward)'
set yrange [*:*] reverse
plot for [i=1:3] dir.'/'.word(variants,i).'/profile-00.csv' skip 1 \
     using 1:3 with lines lw 2 title word(titles,i)
set yrange [*:*] noreverse

set output dir.'/Mx-centre-line.png'
set title example.': Mx at the Gauss points nearest y = 0 (y > 0 row)'
set ylabel 'Mx [kNm/m] (sagging > 0)'
plot for [i=1:3] '< awk -F, "NR > 1 && \$2 > 0" '.dir.'/'.word(variants,i).'/gauss-profile-00.csv' \
     using 1:3 with linespoints lw 2 pt 7 ps 0.6 title word(titles,i)

set output dir.'/q-centre-line.png'
set title example.': contact pressure along y = 0'
set ylabel 'q [kPa] (compression > 0)'
plot for [i=1:3] dir.'/'.word(variants,i).'/profile-00.csv' skip 1 \
     using 1:4 with lines lw 2 title word(titles,i)

set output dir.'/contact-map.png'
set title example.': nodes in contact (exact solution: green in, red lifted)'
set size ratio -1
set xlabel 'x [m]'
set ylabel 'y [m]'
unset key
plot dir.'/exact/nodes-00.csv' skip 1 \
     using 1:2:($6 > 0.5 ? 0x2ca02c : 0xd62728) with points pt 7 ps 1.2 lc rgb variable
