# plots.gp - gnuplot script of tools/plots/plots.sh. Inputs (no header): label, path, cycles/ray,
# build, setup, traverse, intersect per ray, depth RMSE, utilisation %, machine.
set datafile separator ','
set terminal pngcairo size 900,560 noenhanced font 'sans,10'
set key outside right
set grid ytics

set output out.'/cycles-per-phase.png'
set title 'Simulated cycles per ray by phase (lrb16, 1 GHz, 16 lanes)'
set style data histograms
set style histogram rowstacked
set style fill solid 0.8 border -1
set boxwidth 0.7
set ylabel 'cycles per ray'
set xtics rotate by -30
plot lrb using 4:xtic(1) title 'build', '' using 5 title 'setup', '' using 6 title 'traverse', \
     '' using 7 title 'intersect'

set output out.'/error-vs-cycles.png'
set title 'The trade: depth RMSE against the double reference vs cycles per ray (lrb16)'
set style data points
set xtics norotate
set xlabel 'cycles per ray'
set ylabel 'depth RMSE (scene units, log)'
set xlabel 'cycles per ray (log)'
set logscale xy
plot lrb using (strcol(2) eq 'q16' ? $3 : 1/0):8:1 with labels point pt 7 offset 1,1 title 's15.16', \
     lrb using (strcol(2) eq 'f32' ? $3 : 1/0):8:1 with labels point pt 5 offset 1,-1 title 'float32'
unset logscale xy

set output out.'/lane-utilisation.png'
set title 'Lane utilisation (active lanes / 16 over masked lane ops, lrb16)'
set style data histograms
set style histogram clustered
set xlabel ''
set ylabel 'utilisation %'
set yrange [0:100]
set xtics rotate by -30
plot lrb using 9:xtic(1) title 'lrb16'
set autoscale y

set output out.'/machines.png'
set title 'Cycles per ray: Larrabee-like lrb16 vs scalar Cortex-M4-like mcu-m4 (log)'
set logscale y
set ylabel 'cycles per ray'
plot lrb using 3:xtic(1) title 'lrb16', mcu using 3 title 'mcu-m4'
