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
plot 'learning_curves.dat' index 0 using 1:2 with linespoints lw 2 pt 7 ps 0.8 lc rgb '#1f77b4' title 'layersnet', \
     40.4947024 with lines dt 2 lw 2 lc rgb '#000000' title 'static (reference)', \
     17.0048975 with lines dt 2 lw 2 lc rgb '#555555' title 'skinned (reference)'
