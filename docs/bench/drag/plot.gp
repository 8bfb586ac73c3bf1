set terminal pngcairo size 900,420 noenhanced
set datafile separator ','
set logscale y
set grid
set xlabel 'seconds after release (rendering only)'
set ylabel 'mean Delta E against the reference'
set key top right
set arrow from graph 0, first 1 to graph 1, first 1 nohead dt 2
plot 'release.csv' using (strcol(1) eq 'Ceiling panel' ? $2 : 1/0):4 with linespoints title 'Ceiling panel', 'release.csv' using (strcol(1) eq 'LED spot' ? $2 : 1/0):4 with linespoints title 'LED spot', 'release.csv' using (strcol(1) eq 'Linear pendant' ? $2 : 1/0):4 with linespoints title 'Linear pendant'
