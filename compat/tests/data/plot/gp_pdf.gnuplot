#!/usr/bin/env gnuplot
#
# created Sun Nov 22 04:26:03 2026 (20261122_04:26)
#
dataFile="< bzcat gp_pdf.data.bz2"set term cairopdf; set output 'gp_pdf.0.pdf'
set xlabel 'iteration'
set grid
set datafile missing 'nan'
set ylabel '$t$,E_k [J]'
set y2label 'F,sigma'
set y2tics
plot  dataFile using 15:19 title '← $t$(iteration)' with lines, dataFile using 15:1 title '← E_k [J](iteration)' with lines, dataFile using 15:2 title 'F(iteration) →' with lines axes x1y2, dataFile using 15:18 title 'sigma(iteration) →' with lines axes x1y2
set term cairopdf; set output 'gp_pdf.1.pdf'
set xlabel 't=O.time'
set grid
set datafile missing 'nan'
set ylabel 'sigma'
plot  dataFile using 19:18 title '← sigma($t$)' with lines
set term cairopdf; set output 'gp_pdf.2.pdf'
set xlabel 'i '
set grid
set datafile missing 'nan'
set ylabel 'w_x,w_z'
set y2label 'M_xx,M_yy'
set y2tics
plot  dataFile using 15:23 title '← w_x(iteration)' with lines, dataFile using 15:25 title '← w_z(iteration)' with lines, dataFile using 15:3 title 'M_xx(iteration) →' with lines axes x1y2, dataFile using 15:7 title 'M_yy(iteration) →' with lines axes x1y2
set term cairopdf; set output 'gp_pdf.3.pdf'
set xlabel 'F'
set grid
set datafile missing 'nan'
set ylabel 'flag'
plot  dataFile using 2:14 title '← flag(F)' with lines
