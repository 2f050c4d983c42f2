# Drawn by `layers report`; redraw with: gnuplot per_type.gp
set terminal pngcairo size 1600,500 font 'Sans,10' noenhanced
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
plot 'per_type.dat' using 2:3:xtic(1) lc rgb '#1f77b4' title 'static', \
     'per_type.dat' using 4:5 lc rgb '#ff7f0e' title 'skinned', \
     'per_type.dat' using 6:7 lc rgb '#2ca02c' title 'deepsd/seed-0', \
     'per_type.dat' using 8:9 lc rgb '#d62728' title 'deepsd/seed-1', \
     'per_type.dat' using 10:11 lc rgb '#9467bd' title 'deepsd/seed-2', \
     'per_type.dat' using 12:13 lc rgb '#8c564b' title 'deepsd+/seed-0', \
     'per_type.dat' using 14:15 lc rgb '#e377c2' title 'deepsd+/seed-1', \
     'per_type.dat' using 16:17 lc rgb '#7f7f7f' title 'deepsd+/seed-2', \
     'per_type.dat' using 18:19 lc rgb '#bcbd22' title 'layersnet/seed-0', \
     'per_type.dat' using 20:21 lc rgb '#17becf' title 'layersnet/seed-1', \
     'per_type.dat' using 22:23 lc rgb '#1f77b4' title 'layersnet/seed-2', \
     'per_type.dat' using 24:25 lc rgb '#ff7f0e' title 'layersnet+/seed-0', \
     'per_type.dat' using 26:27 lc rgb '#2ca02c' title 'layersnet+/seed-1', \
     'per_type.dat' using 28:29 lc rgb '#d62728' title 'layersnet+/seed-2', \
     'per_type.dat' using 30:31 lc rgb '#9467bd' title 'mgnet-follow/seed-0', \
     'per_type.dat' using 32:33 lc rgb '#8c564b' title 'mgnet-follow/seed-1', \
     'per_type.dat' using 34:35 lc rgb '#e377c2' title 'mgnet-follow/seed-2', \
     'per_type.dat' using 36:37 lc rgb '#7f7f7f' title 'layersnet-body-gate/seed-0', \
     'per_type.dat' using 38:39 lc rgb '#bcbd22' title 'layersnet-body-gate/seed-1', \
     'per_type.dat' using 40:41 lc rgb '#17becf' title 'layersnet-body-gate/seed-2'
