# Error against substep size: circular-orbit
# Run gnuplot on this file in its folder: it writes converge-circular-orbit.png and converge-circular-orbit.svg. The data is inline, below.
$s0 << EOD
0.016666666666666701 0.0004512288142164863 ""
0.0083333333333333506 0.00011279949082708102 ""
0.0041666666666666753 2.8199391517594368e-05 ""
0.0020833333333333376 7.0498181938097636e-06 ""
0.0010416666666666688 1.7624550249242694e-06 ""
0.00052083333333333441 4.4060894079127737e-07 ""
0.00026041666666666721 1.1005992383778339e-07 ""
EOD
$s1 << EOD
0.016666666666666701 0.0004512288142164863 ""
0.0083333333333333506 0.00011279949082708102 ""
0.0041666666666666753 2.8199391517594368e-05 ""
0.0020833333333333376 7.0498181938097636e-06 ""
0.0010416666666666688 1.7624550249242694e-06 ""
0.00052083333333333441 4.4060894079127737e-07 ""
0.00026041666666666721 1.1005992383778339e-07 ""
EOD
$s2 << EOD
0.016666666666666701 0.0004512288142164863 ""
0.0083333333333333506 0.00011279949082708102 ""
0.0041666666666666753 2.8199391517594368e-05 ""
0.0020833333333333376 7.0498181938097636e-06 ""
0.0010416666666666688 1.7624550249242694e-06 ""
0.00052083333333333441 4.4060894079127737e-07 ""
0.00026041666666666721 1.1005992383778339e-07 ""
EOD
$s3 << EOD
0.016666666666666701 0.0004512288142164863 ""
0.0083333333333333506 0.00011279949082708102 ""
0.0041666666666666753 2.8199391517594368e-05 ""
0.0020833333333333376 7.0498181938097636e-06 ""
0.0010416666666666688 1.7624550249242694e-06 ""
0.00052083333333333441 4.4060894079127737e-07 ""
0.00026041666666666721 1.1005992383778339e-07 ""
EOD
set termoption noenhanced
set title 'Error against substep size: circular-orbit'
set xlabel 'substep h (s)'
set ylabel 'error (m)'
set logscale x
set format x '%g'
set logscale y
set format y '%.0e'
set grid xtics ytics mxtics mytics lc 'gray80'
set key outside right top box
set offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05
if (!exists('outdir')) outdir = '.'
set terminal pngcairo size 1000,640 font ',10' noenhanced
set output outdir.'/'.'converge-circular-orbit.png'
plot $s0 using 1:2 with linespoints lw 1.5 pt 7 ps 1.2 lc 1 title 'gauss-seidel particle: order 2', \
     $s1 using 1:2 with linespoints lw 1.5 pt 5 ps 1.2 lc 2 title 'jacobi particle: order 2', \
     $s2 using 1:2 with linespoints lw 1.5 pt 13 ps 1.2 lc 3 title 'xpbd particle: order 2', \
     $s3 using 1:2 with linespoints lw 1.5 pt 9 ps 1.2 lc 4 title 'shake particle: order 2', \
     1e-08 with lines dt 2 lw 1.5 lc 'gray40' title 'floor: left out of the fit'
set terminal svg size 1000,640 font ',10' noenhanced background 'white'
set output outdir.'/'.'converge-circular-orbit.svg'
replot
unset output
