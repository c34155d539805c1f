# Cost per body against size: capsule-ragdolls
# Run gnuplot on this file in its folder: it writes scale.png and scale.svg. The data is inline, below.
$s0 << EOD
11 2.3912727272727277 "n=1"
44 1.8165568181818181 "n=4"
176 1.4083409090909089 "n=16"
704 1.3517492897727272 "n=64"
2816 1.3882858664772728 "n=256"
11264 1.710524813565341 "n=1024"
EOD
$s1 << EOD
11 2.8669545454545458 "n=1"
44 2.1750454545454545 "n=4"
176 1.7477926136363637 "n=16"
704 1.3320610795454546 "n=64"
2816 1.0091885653409092 "n=256"
11264 1.0508007368607954 "n=1024"
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
