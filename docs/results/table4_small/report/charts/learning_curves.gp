# Drawn by `layers report`; redraw with: gnuplot learning_curves.gp
set terminal pngcairo size 1000,560 font 'Sans,10' noenhanced
if (!exists('out')) out = 'learning_curves.png'
set output out
set title 'Learning curves'
set xlabel 'training windows seen'
set ylabel 'validation error (mm)'
set grid
set key outside right top
set datafile missing 'NaN'
plot 'learning_curves.dat' index 0 using 1:2 with linespoints lw 2 pt 7 ps 0.8 lc rgb '#2ca02c' title 'deepsd/seed-0', \
     'learning_curves.dat' index 1 using 1:2 with linespoints lw 2 pt 7 ps 0.8 lc rgb '#d62728' title 'deepsd/seed-1', \
     'learning_curves.dat' index 2 using 1:2 with linespoints lw 2 pt 7 ps 0.8 lc rgb '#9467bd' title 'deepsd/seed-2', \
     'learning_curves.dat' index 3 using 1:2 with linespoints lw 2 pt 7 ps 0.8 lc rgb '#8c564b' title 'deepsd+/seed-0', \
     'learning_curves.dat' index 4 using 1:2 with linespoints lw 2 pt 7 ps 0.8 lc rgb '#e377c2' title 'deepsd+/seed-1', \
     'learning_curves.dat' index 5 using 1:2 with linespoints lw 2 pt 7 ps 0.8 lc rgb '#7f7f7f' title 'deepsd+/seed-2', \
     'learning_curves.dat' index 6 using 1:2 with linespoints lw 2 pt 7 ps 0.8 lc rgb '#17becf' title 'layersnet/seed-1', \
     'learning_curves.dat' index 7 using 1:2 with linespoints lw 2 pt 7 ps 0.8 lc rgb '#1f77b4' title 'layersnet/seed-2', \
     'learning_curves.dat' index 8 using 1:2 with linespoints lw 2 pt 7 ps 0.8 lc rgb '#2ca02c' title 'layersnet+/seed-1', \
     'learning_curves.dat' index 9 using 1:2 with linespoints lw 2 pt 7 ps 0.8 lc rgb '#d62728' title 'layersnet+/seed-2', \
     'learning_curves.dat' index 10 using 1:2 with linespoints lw 2 pt 7 ps 0.8 lc rgb '#9467bd' title 'mgnet-follow/seed-0', \
     'learning_curves.dat' index 11 using 1:2 with linespoints lw 2 pt 7 ps 0.8 lc rgb '#8c564b' title 'mgnet-follow/seed-1', \
     'learning_curves.dat' index 12 using 1:2 with linespoints lw 2 pt 7 ps 0.8 lc rgb '#e377c2' title 'mgnet-follow/seed-2', \
     'learning_curves.dat' index 13 using 1:2 with linespoints lw 2 pt 7 ps 0.8 lc rgb '#7f7f7f' title 'layersnet-body-gate/seed-0', \
     'learning_curves.dat' index 14 using 1:2 with linespoints lw 2 pt 7 ps 0.8 lc rgb '#bcbd22' title 'layersnet-body-gate/seed-1', \
     'learning_curves.dat' index 15 using 1:2 with linespoints lw 2 pt 7 ps 0.8 lc rgb '#17becf' title 'layersnet-body-gate/seed-2'
