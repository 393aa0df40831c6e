# Figures of scripts/pavement_study.sh: the contact maps of the four
# pavement scenes (the nodes of the last cycle, in contact or lifted) and
# the largest principal stress of the bottom and the top fibre along
# x = 0, across the slab through the tyre at (0, 1.65).
# usage: gnuplot -e "last='04'" scripts/pavement_figures.gp
set datafile separator ','
scenes = 'pavement-day pavement-night pavement-day-half-space pavement-night-half-space'
titles = "'day, dense liquid' 'night, dense liquid' 'day, half-space' 'night, half-space'"

set terminal pngcairo size 1000,820 font ',11'
set output 'output/pavement/contact-maps.png'
set multiplot layout 2,2 title 'Pavement slab 4.5 m x 3.6 m, tyre at (0, 1.65): nodes in contact (green) and lifted (red)'
set size ratio -1
unset key
set xrange [-2.3:2.3]
set yrange [-1.85:1.85]
do for [i=1:4] {
  set title word(titles, i)
  plot 'output/'.word(scenes, i).'/nodes-'.last.'.csv' skip 1 \
       using 1:2:($6 > 0 ? 0x2ca02c : 0xd62728) with points pt 7 ps 0.25 lc rgb variable
}
unset multiplot

set terminal pngcairo size 1000,460 font ',11'
set output 'output/pavement/stress-profiles.png'
set size noratio
set autoscale
set grid
set key below
set multiplot layout 1,2 title 'Largest principal stress along x = 0 (tension > 0); the tyre at y = 1.65'
set xlabel 'y [m]'
set ylabel 'bottom fibre [kPa]'
set title 'bottom fibre'
plot for [i=1:4] 'output/'.word(scenes, i).'/profile-'.last.'.csv' skip 1 \
     using 2:10 with lines lw 2 title word(titles, i)
set ylabel 'top fibre [kPa]'
set title 'top fibre'
plot for [i=1:4] 'output/'.word(scenes, i).'/profile-'.last.'.csv' skip 1 \
     using 2:14 with lines lw 2 title word(titles, i)
unset multiplot
