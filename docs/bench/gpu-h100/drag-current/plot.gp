set terminal pngcairo size 900,420 noenhanced
set datafile separator ','
set logscale y
set grid
set xlabel 'seconds after release (rendering only)'
set ylabel 'mean Delta E against the reference'
set key top right
set arrow from graph 0, first 1 to graph 1, first 1 nohead dt 2
plot 'release.csv' using (strcol(1) eq 'Ceiling panel' && strcol(2) eq 'moved only' ? $3 : 1/0):5 with linespoints title 'Ceiling panel (moved only)', 'release.csv' using (strcol(1) eq 'Ceiling panel' && strcol(2) eq 'everything' ? $3 : 1/0):5 with linespoints title 'Ceiling panel (everything)', 'release.csv' using (strcol(1) eq 'LED spot' && strcol(2) eq 'moved only' ? $3 : 1/0):5 with linespoints title 'LED spot (moved only)', 'release.csv' using (strcol(1) eq 'LED spot' && strcol(2) eq 'everything' ? $3 : 1/0):5 with linespoints title 'LED spot (everything)', 'release.csv' using (strcol(1) eq 'Linear pendant' && strcol(2) eq 'moved only' ? $3 : 1/0):5 with linespoints title 'Linear pendant (moved only)', 'release.csv' using (strcol(1) eq 'Linear pendant' && strcol(2) eq 'everything' ? $3 : 1/0):5 with linespoints title 'Linear pendant (everything)'
