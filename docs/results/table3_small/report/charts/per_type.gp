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
plot 'per_type.dat' using 2:3:xtic(1) lc rgb '#1f77b4' title 'deepsd-inner_T', \
     'per_type.dat' using 4:5 lc rgb '#ff7f0e' title 'mgnet-inner_T', \
     'per_type.dat' using 6:7 lc rgb '#2ca02c' title 'layersnet-inner_T', \
     'per_type.dat' using 8:9 lc rgb '#d62728' title 'skinned-inner_T', \
     'per_type.dat' using 10:11 lc rgb '#9467bd' title 'deepsd_T', \
     'per_type.dat' using 12:13 lc rgb '#8c564b' title 'layersnet_T', \
     'per_type.dat' using 14:15 lc rgb '#e377c2' title 'skinned_T', \
     'per_type.dat' using 16:17 lc rgb '#7f7f7f' title 'deepsd-inner_T+W', \
     'per_type.dat' using 18:19 lc rgb '#bcbd22' title 'mgnet-inner_T+W', \
     'per_type.dat' using 20:21 lc rgb '#17becf' title 'layersnet-inner_T+W', \
     'per_type.dat' using 22:23 lc rgb '#1f77b4' title 'skinned-inner_T+W', \
     'per_type.dat' using 24:25 lc rgb '#ff7f0e' title 'deepsd_T+W', \
     'per_type.dat' using 26:27 lc rgb '#2ca02c' title 'layersnet_T+W', \
     'per_type.dat' using 28:29 lc rgb '#d62728' title 'skinned_T+W', \
     'per_type.dat' using 30:31 lc rgb '#9467bd' title 'deepsd-inner_L', \
     'per_type.dat' using 32:33 lc rgb '#8c564b' title 'mgnet-inner_L', \
     'per_type.dat' using 34:35 lc rgb '#e377c2' title 'layersnet-inner_L', \
     'per_type.dat' using 36:37 lc rgb '#7f7f7f' title 'skinned-inner_L', \
     'per_type.dat' using 38:39 lc rgb '#bcbd22' title 'deepsd_L', \
     'per_type.dat' using 40:41 lc rgb '#17becf' title 'layersnet_L', \
     'per_type.dat' using 42:43 lc rgb '#1f77b4' title 'skinned_L', \
     'per_type.dat' using 44:45 lc rgb '#ff7f0e' title 'deepsd-inner_L+W', \
     'per_type.dat' using 46:47 lc rgb '#2ca02c' title 'mgnet-inner_L+W', \
     'per_type.dat' using 48:49 lc rgb '#d62728' title 'layersnet-inner_L+W', \
     'per_type.dat' using 50:51 lc rgb '#9467bd' title 'skinned-inner_L+W', \
     'per_type.dat' using 52:53 lc rgb '#8c564b' title 'deepsd_L+W', \
     'per_type.dat' using 54:55 lc rgb '#e377c2' title 'layersnet_L+W', \
     'per_type.dat' using 56:57 lc rgb '#7f7f7f' title 'skinned_L+W'
