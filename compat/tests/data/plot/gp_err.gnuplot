#!/usr/bin/env gnuplot
#
# created Sun Nov 22 04:26:03 2026 (20261122_04:26)
#
set term wxt 0 persist
set xlabel 'iteration'
set grid
set datafile missing 'nan'
set ylabel '$t$,ghost'
