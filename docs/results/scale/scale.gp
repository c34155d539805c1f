# Cost per body against size: capsule-ragdolls
# Run gnuplot on this file in its folder: it writes scale.png and scale.svg. The data is inline, below.
$s0 << EOD
11 3.2798181818181815 "n=1"
44 2.4697954545454546 "n=4"
176 2.0028011363636362 "n=16"
704 1.9753515625 "n=64"
2816 2.0902040127840911 "n=256"
11264 2.4778755770596592 "n=1024"
EOD
$s1 << EOD
11 3.7924545454545462 "n=1"
44 2.8841590909090908 "n=4"
176 2.306400568181818 "n=16"
704 1.9009438920454544 "n=64"
2816 1.2377626065340908 "n=256"
11264 1.7371427556818182 "n=1024"
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
