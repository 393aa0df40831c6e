# Figures of scripts/jointed_pavement_study.sh: the contact maps of the
# jointed pavement on both foundations (the nodes of the last cycle, in
# contact or lifted; the joints as lines, the tandem's tyres as circles)
# and the largest principal stress of the bottom and the top fibre along
# the wheel path y = 1.8 across the three slabs.
# usage: gnuplot -e "last='01'" scripts/jointed_pavement_figures.gp
set datafile separator ','
scenes = 'jointed-pavement jointed-pavement-half-space'
titles = "'dense liquid, k = 50 MN/m^3' 'half-space, E_0 = 100 MPa'"

set terminal pngcairo size 1100,900 font ',11'
set output 'output/jointed-pavement-study/contact-maps.png'
set multiplot layout 2,1 title "3 x 2 slabs at night (top 10 K cooler), tandem axle before the joint x = 2.25:\nnodes in contact (green) and lifted (red); dowelled transverse joints, tied longitudinal joint"
set size ratio -1
unset key
set xrange [-6.9:6.9]
set yrange [-3.75:3.75]
set arrow 1 from -2.25,-3.6 to -2.25,3.6 nohead lw 2 lc rgb 'black' front
set arrow 2 from 2.25,-3.6 to 2.25,3.6 nohead lw 2 lc rgb 'black' front
set arrow 3 from -6.75,0 to 6.75,0 nohead lw 2 dt 2 lc rgb 'black' front
do for [i=1:2] {
  set title word(titles, i)
  plot 'output/'.word(scenes, i).'/nodes-'.last.'.csv' skip 1 \
       using 1:2:($6 > 0 ? 0x2ca02c : 0xd62728) with points pt 7 ps 0.3 lc rgb variable
}
unset multiplot
unset arrow

set terminal pngcairo size 1100,460 font ',11'
set output 'output/jointed-pavement-study/stress-profiles.png'
set size noratio
set autoscale
set grid
set key below
set multiplot layout 1,2 title 'Largest principal stress along the wheel path y = 1.8 (tension > 0); joints at x = -2.25 and 2.25'
set xlabel 'x [m]'
set ylabel 'bottom fibre [kPa]'
set title 'bottom fibre'
plot for [i=1:2] 'output/'.word(scenes, i).'/profile-'.last.'.csv' skip 1 \
     using 1:10 with lines lw 2 title word(titles, i)
set ylabel 'top fibre [kPa]'
set title 'top fibre'
plot for [i=1:2] 'output/'.word(scenes, i).'/profile-'.last.'.csv' skip 1 \
     using 1:14 with lines lw 2 title word(titles, i)
unset multiplot
