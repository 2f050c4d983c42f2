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
     'speed_accuracy_runs.dat' index 0 using 1:2 with points pt 7 ps 1.8 lc rgb '#1f77b4' title 'layersnet', \
     'speed_accuracy_runs.dat' index 1 using 1:2 with points pt 7 ps 1.8 lc rgb '#ff7f0e' title 'static', \
     'speed_accuracy_runs.dat' index 2 using 1:2 with points pt 7 ps 1.8 lc rgb '#2ca02c' title 'skinned', \
     'speed_accuracy_runs.dat' using 1:2:3 with labels offset char 1.5,0.9 left notitle
