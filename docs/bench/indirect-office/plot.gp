set terminal pngcairo size 800,420 noenhanced
set datafile separator ','
set grid
set logscale y
set xlabel 'wall time since the change, s'
set ylabel 'worst work-plane point, fraction of Em'
set key top right
plot 'bench.csv' using (strcol(1) eq 'cold' ? $3 : 1/0):5 with linespoints pointsize 1.5 title 'from scratch', 'bench.csv' using (strcol(1) eq 'move' ? $3 : 1/0):5 with linespoints pointsize 1.5 title 'after a move', 0.01 title '1 %' dt 2
