# Drawn by `layers report`; redraw with: gnuplot speed_accuracy.gp
set terminal pngcairo size 900,600 font 'Sans,10' noenhanced
if (!exists('out')) out = 'speed_accuracy.png'
set output out
set title 'Accuracy against speed'
set xlabel 'ms per predicted frame (log scale)'
set ylabel 'mean Euclidean error (mm)'
set logscale x
set yrange [0:*]
set grid
set key outside right top
set datafile missing 'NaN'
set offsets graph 0.15, graph 0.35, graph 0.15, graph 0.15
plot 'speed_accuracy_front.dat' using 1:2 with steps dt 2 lw 1.5 lc rgb '#999999' title 'Pareto front', \
     'speed_accuracy_front.dat' using 1:2 with points pt 6 ps 3.2 lw 2 lc rgb '#d62728' title 'on the front', \
     'speed_accuracy_runs.dat' index 0 using 1:2 with points pt 7 ps 1.8 lc rgb '#1f77b4' title 'deepsd-inner_T', \
     'speed_accuracy_runs.dat' index 1 using 1:2 with points pt 7 ps 1.8 lc rgb '#ff7f0e' title 'mgnet-inner_T', \
     'speed_accuracy_runs.dat' index 2 using 1:2 with points pt 7 ps 1.8 lc rgb '#2ca02c' title 'layersnet-inner_T', \
     'speed_accuracy_runs.dat' index 3 using 1:2 with points pt 7 ps 1.8 lc rgb '#d62728' title 'skinned-inner_T', \
     'speed_accuracy_runs.dat' index 4 using 1:2 with points pt 7 ps 1.8 lc rgb '#9467bd' title 'deepsd_T', \
     'speed_accuracy_runs.dat' index 5 using 1:2 with points pt 7 ps 1.8 lc rgb '#8c564b' title 'layersnet_T', \
     'speed_accuracy_runs.dat' index 6 using 1:2 with points pt 7 ps 1.8 lc rgb '#e377c2' title 'skinned_T', \
     'speed_accuracy_runs.dat' index 7 using 1:2 with points pt 7 ps 1.8 lc rgb '#7f7f7f' title 'deepsd-inner_T+W', \
     'speed_accuracy_runs.dat' index 8 using 1:2 with points pt 7 ps 1.8 lc rgb '#bcbd22' title 'mgnet-inner_T+W', \
     'speed_accuracy_runs.dat' index 9 using 1:2 with points pt 7 ps 1.8 lc rgb '#17becf' title 'layersnet-inner_T+W', \
     'speed_accuracy_runs.dat' index 10 using 1:2 with points pt 7 ps 1.8 lc rgb '#1f77b4' title 'skinned-inner_T+W', \
     'speed_accuracy_runs.dat' index 11 using 1:2 with points pt 7 ps 1.8 lc rgb '#ff7f0e' title 'deepsd_T+W', \
     'speed_accuracy_runs.dat' index 12 using 1:2 with points pt 7 ps 1.8 lc rgb '#2ca02c' title 'layersnet_T+W', \
     'speed_accuracy_runs.dat' index 13 using 1:2 with points pt 7 ps 1.8 lc rgb '#d62728' title 'skinned_T+W', \
     'speed_accuracy_runs.dat' index 14 using 1:2 with points pt 7 ps 1.8 lc rgb '#9467bd' title 'deepsd-inner_L', \
     'speed_accuracy_runs.dat' index 15 using 1:2 with points pt 7 ps 1.8 lc rgb '#8c564b' title 'mgnet-inner_L', \
     'speed_accuracy_runs.dat' index 16 using 1:2 with points pt 7 ps 1.8 lc rgb '#e377c2' title 'layersnet-inner_L', \
     'speed_accuracy_runs.dat' index 17 using 1:2 with points pt 7 ps 1.8 lc rgb '#7f7f7f' title 'skinned-inner_L', \
     'speed_accuracy_runs.dat' index 18 using 1:2 with points pt 7 ps 1.8 lc rgb '#bcbd22' title 'deepsd_L', \
     'speed_accuracy_runs.dat' index 19 using 1:2 with points pt 7 ps 1.8 lc rgb '#17becf' title 'layersnet_L', \
     'speed_accuracy_runs.dat' index 20 using 1:2 with points pt 7 ps 1.8 lc rgb '#1f77b4' title 'skinned_L', \
     'speed_accuracy_runs.dat' index 21 using 1:2 with points pt 7 ps 1.8 lc rgb '#ff7f0e' title 'deepsd-inner_L+W', \
     'speed_accuracy_runs.dat' index 22 using 1:2 with points pt 7 ps 1.8 lc rgb '#2ca02c' title 'mgnet-inner_L+W', \
     'speed_accuracy_runs.dat' index 23 using 1:2 with points pt 7 ps 1.8 lc rgb '#d62728' title 'layersnet-inner_L+W', \
     'speed_accuracy_runs.dat' index 24 using 1:2 with points pt 7 ps 1.8 lc rgb '#9467bd' title 'skinned-inner_L+W', \
     'speed_accuracy_runs.dat' index 25 using 1:2 with points pt 7 ps 1.8 lc rgb '#8c564b' title 'deepsd_L+W', \
     'speed_accuracy_runs.dat' index 26 using 1:2 with points pt 7 ps 1.8 lc rgb '#e377c2' title 'layersnet_L+W', \
     'speed_accuracy_runs.dat' index 27 using 1:2 with points pt 7 ps 1.8 lc rgb '#7f7f7f' title 'skinned_L+W', \
     'speed_accuracy_runs.dat' using 1:2:3 with labels offset char 1.5,0.9 left notitle
