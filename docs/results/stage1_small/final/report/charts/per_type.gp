# Drawn by `layers report`; redraw with: gnuplot per_type.gp
set terminal pngcairo size 1280,500 font 'Sans,10' noenhanced
if (!exists('out')) out = 'per_type.png'
set output out
set title 'Error per garment type'
set ylabel 'mean Euclidean error (mm), +- std over sequences'
set grid ytics
set key outside right top
set datafile missing 'NaN'
set style data histograms
set style histogram errorbars gap 2 lw 1
set style fill solid 0.85 border rgb '#333333'
set boxwidth 0.9
set yrange [0:*]
set xtics nomirror
plot 'per_type.dat' using 2:3:xtic(1) lc rgb '#1f77b4' title 'layersnet', \
     'per_type.dat' using 4:5 lc rgb '#ff7f0e' title 'static', \
     'per_type.dat' using 6:7 lc rgb '#2ca02c' title 'skinned'
