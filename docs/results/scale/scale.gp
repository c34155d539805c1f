# Cost per body against size: capsule-ragdolls
# Run gnuplot on this file in its folder: it writes scale.png and scale.svg. The data is inline, below.
$s0 << EOD
11 2.9319545454545453 "n=1"
44 2.3114318181818181 "n=4"
176 1.8251647727272726 "n=16"
704 1.6275404829545457 "n=64"
2816 1.5857141335227269 "n=256"
11264 1.924341042258523 "n=1024"
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
plot $s0 using 1:2 with lines lw 2 lc 'black' title 'capsule-ragdolls', \
     $s0 using 1:2:3 with labels left offset 0.7,0.6 font ',8' notitle
set terminal svg size 1000,640 font ',10' noenhanced background 'white'
set output outdir.'/'.'scale.svg'
replot
unset output
