# Drawn by `layers report`; redraw with: gnuplot by_step_h_collision.gp
set terminal pngcairo size 900,500 font 'Sans,10' noenhanced
if (!exists('out')) out = 'by_step_h_collision.png'
set output out
set title 'H-collision against rollout step'
set xlabel 'rollout step (predicted frames after the ground-truth start)'
set ylabel 'garment vertices behind the body (%)'
set grid
set key outside right top
set datafile missing 'NaN'
set xrange [1:35]
set yrange [0:*]
plot 0.105864525 with lines dt 3 lw 1.5 lc rgb '#555555' title 'ground truth', \
     'by_step.dat' index 0 using 1:3 with lines lw 2 lc rgb '#1f77b4' title 'deepsd-inner_T', \
     'by_step.dat' index 1 using 1:3 with lines lw 2 lc rgb '#ff7f0e' title 'mgnet-inner_T', \
     'by_step.dat' index 2 using 1:3 with lines lw 2 lc rgb '#2ca02c' title 'layersnet-inner_T', \
     'by_step.dat' index 3 using 1:3 with lines lw 2 lc rgb '#d62728' title 'skinned-inner_T', \
     'by_step.dat' index 4 using 1:3 with lines lw 2 lc rgb '#9467bd' title 'deepsd_T', \
     'by_step.dat' index 5 using 1:3 with lines lw 2 lc rgb '#8c564b' title 'layersnet_T', \
     'by_step.dat' index 6 using 1:3 with lines lw 2 lc rgb '#e377c2' title 'skinned_T', \
     'by_step.dat' index 7 using 1:3 with lines lw 2 lc rgb '#7f7f7f' title 'deepsd-inner_T+W', \
     'by_step.dat' index 8 using 1:3 with lines lw 2 lc rgb '#bcbd22' title 'mgnet-inner_T+W', \
     'by_step.dat' index 9 using 1:3 with lines lw 2 lc rgb '#17becf' title 'layersnet-inner_T+W', \
     'by_step.dat' index 10 using 1:3 with lines lw 2 lc rgb '#1f77b4' title 'skinned-inner_T+W', \
     'by_step.dat' index 11 using 1:3 with lines lw 2 lc rgb '#ff7f0e' title 'deepsd_T+W', \
     'by_step.dat' index 12 using 1:3 with lines lw 2 lc rgb '#2ca02c' title 'layersnet_T+W', \
     'by_step.dat' index 13 using 1:3 with lines lw 2 lc rgb '#d62728' title 'skinned_T+W', \
     'by_step.dat' index 14 using 1:3 with lines lw 2 lc rgb '#9467bd' title 'deepsd-inner_L', \
     'by_step.dat' index 15 using 1:3 with lines lw 2 lc rgb '#8c564b' title 'mgnet-inner_L', \
     'by_step.dat' index 16 using 1:3 with lines lw 2 lc rgb '#e377c2' title 'layersnet-inner_L', \
     'by_step.dat' index 17 using 1:3 with lines lw 2 lc rgb '#7f7f7f' title 'skinned-inner_L', \
     'by_step.dat' index 18 using 1:3 with lines lw 2 lc rgb '#bcbd22' title 'deepsd_L', \
     'by_step.dat' index 19 using 1:3 with lines lw 2 lc rgb '#17becf' title 'layersnet_L', \
     'by_step.dat' index 20 using 1:3 with lines lw 2 lc rgb '#1f77b4' title 'skinned_L', \
     'by_step.dat' index 21 using 1:3 with lines lw 2 lc rgb '#ff7f0e' title 'deepsd-inner_L+W', \
     'by_step.dat' index 22 using 1:3 with lines lw 2 lc rgb '#2ca02c' title 'mgnet-inner_L+W', \
     'by_step.dat' index 23 using 1:3 with lines lw 2 lc rgb '#d62728' title 'layersnet-inner_L+W', \
     'by_step.dat' index 24 using 1:3 with lines lw 2 lc rgb '#9467bd' title 'skinned-inner_L+W', \
     'by_step.dat' index 25 using 1:3 with lines lw 2 lc rgb '#8c564b' title 'deepsd_L+W', \
     'by_step.dat' index 26 using 1:3 with lines lw 2 lc rgb '#e377c2' title 'layersnet_L+W', \
     'by_step.dat' index 27 using 1:3 with lines lw 2 lc rgb '#7f7f7f' title 'skinned_L+W'
