#!/usr/bin/env gnuplot
#
# created Sun Nov 22 04:26:03 2026 (20261122_04:26)
#
# first line
# second line#
set term png; set output 'gp_png.0.png'
set xlabel 'iteration'
set grid
set datafile missing 'nan'
set title 'My title'
set ylabel '$t$,E_k [J]'
set y2label 'F,sigma'
set y2tics
plot  "< bzcat gp_png.data.bz2" using 15:19 title '← $t$(iteration)' with lines, "< bzcat gp_png.data.bz2" using 15:1 title '← E_k [J](iteration)' with lines, "< bzcat gp_png.data.bz2" using 15:2 title 'F(iteration) →' with lines axes x1y2, "< bzcat gp_png.data.bz2" using 15:18 title 'sigma(iteration) →' with lines axes x1y2
set term png; set output 'gp_png.1.png'
set xlabel 't=O.time'
set grid
set datafile missing 'nan'
set title 'My title'
set ylabel 'sigma'
plot  "< bzcat gp_png.data.bz2" using 19:18 title '← sigma($t$)' with lines
set term png; set output 'gp_png.2.png'
set xlabel 'i '
set grid
set datafile missing 'nan'
set title 'My title'
set ylabel 'w_x,w_z'
set y2label 'M_xx,M_yy'
set y2tics
plot  "< bzcat gp_png.data.bz2" using 15:23 title '← w_x(iteration)' with lines, "< bzcat gp_png.data.bz2" using 15:25 title '← w_z(iteration)' with lines, "< bzcat gp_png.data.bz2" using 15:3 title 'M_xx(iteration) →' with lines axes x1y2, "< bzcat gp_png.data.bz2" using 15:7 title 'M_yy(iteration) →' with lines axes x1y2
set term png; set output 'gp_png.3.png'
set xlabel 'F'
set grid
set datafile missing 'nan'
set title 'My title'
set ylabel 'flag'
plot  "< bzcat gp_png.data.bz2" using 2:14 title '← flag(F)' with lines
