# Plots beamid frc output (PREFIX.csv) and, if given, the backbone (BB.csv):
#   gnuplot -c scripts/plot_frc.gp out/frc.csv acc3 out/frc.png [out/backbone.csv]
# Solid: stable branches; dashed: unstable (between turning points).
# Files and channel are arguments (ARG1..ARG4): gnuplot takes them as
# strings, so a quote in a path stays part of it (pasting a path into
# -e "frc='...'" would run whatever follows a quote in it as gnuplot).
if (ARGC >= 1) frc = ARG1
if (ARGC >= 2) channel = ARG2
if (ARGC >= 3) out = ARG3
if (ARGC >= 4) bb = ARG4
if (!exists("channel")) channel = 'acc3'
if (!exists("out")) out = 'frc.png'
set terminal pngcairo size 900,560 enhanced font ",11"
set output out
set datafile separator ','
set datafile columnheaders
set xlabel 'frequency [Hz]'
set ylabel sprintf('%s: 1st-harmonic acceleration amplitude [m/s^2]', channel) noenhanced
set grid
set key top left
amp = sprintf('%s_h1_acc_amp_m_s2', channel)
stats frc using 1 nooutput
# Level labels: the distinct force amplitudes, in file order.
levels = ''
last = -1
do for [i=0:STATS_records-1] {
  stats frc every ::i::i using 1 nooutput
  if (STATS_min != last) { levels = levels.sprintf(' %g', STATS_min); last = STATS_min }
}
plot for [f in levels] frc using 2:((column(1) == real(f) && column(3) == 1) ? column(amp) : NaN) \
       with lines lw 2 title sprintf('%s N', f), \
     for [f in levels] frc using 2:((column(1) == real(f) && column(3) == 0) ? column(amp) : NaN) \
       with lines dt 2 lw 2 lc rgb 'gray40' notitle, \
     (exists("bb") ? bb : frc) using (exists("bb") ? column(2) : NaN):(exists("bb") ? column(amp) : NaN) \
       with lines lw 1.5 lc rgb 'black' title 'backbone (harmonic balance)'
