# Cost per body against size: capsule-ragdolls
# Run gnuplot on this file in its folder: it writes scale.png and scale.svg. The data is inline, below.
$s0 << EOD
11 4.2590909090909088 "n=1"
44 3.5624659090909092 "n=4"
176 2.8322017045454548 "n=16"
704 2.7327088068181817 "n=64"
2816 2.6343618607954542 "n=256"
11264 4.2273634144176135 "n=1024"
EOD
$s1 << EOD
11 4.9150454545454547 "n=1"
44 4.2413181818181815 "n=4"
176 2.4909005681818184 "n=16"
704 1.8206740056818183 "n=64"
2816 1.3680007102272727 "n=256"
11264 1.4784830433238634 "n=1024"
EOD
set termoption noenhanced
set title 'Cost per body against size: capsule-ragdolls'
set xlabel 'bodies'
set ylabel 'microseconds per body-step'
set logscale x
set format x '%g'
set grid xtics ytics mxtics mytics lc 'gray80'
set key outside right top box
set offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05
if (!exists('outdir')) outdir = '.'
set terminal pngcairo size 1000,640 font ',10' noenhanced
set output outdir.'/'.'scale.png'
plot $s0 using 1:2 with linespoints lw 1.5 pt 7 ps 1.2 lc 1 title 'capsule-ragdolls, 1 thread', \
     $s0 using 1:2:3 with labels left offset 0.7,0.6 font ',8' notitle, \
     $s1 using 1:2 with linespoints lw 1.5 pt 5 ps 1.2 lc 2 title 'capsule-ragdolls, 2 threads'
set terminal svg size 1000,640 font ',10' noenhanced background 'white'
set output outdir.'/'.'scale.svg'
replot
unset output
