set terminal pngcairo size 1000,420 noenhanced
set datafile separator ','
set grid
set multiplot layout 1,2
set logscale x
set ylabel 'mean Delta E against ray-traced'
set xlabel 'shadow maps per luminaire (192^2 faces)'
plot 'shadows.csv' using (strcol(1) eq 'count' ? $3 : 1/0):7 with linespoints pointsize 1.5 title 'shadow maps', 1.40039 title 'noise: ray-traced, another seed' dt 2
set xlabel 'cube-face resolution (49 maps)'
set logscale x 2
plot 'shadows.csv' using (strcol(1) eq 'resolution' ? $4 : 1/0):7 with linespoints pointsize 1.5 title 'shadow maps', 1.40039 title 'noise: ray-traced, another seed' dt 2
unset multiplot
