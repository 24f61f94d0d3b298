# Plots the measured backbone of `beamid backbone --measured ... -o PREFIX`:
#   gnuplot -c scripts/plot_backbone.gp out/measured out/measured.png
# The prefix and the picture are arguments (ARG1, ARG2): gnuplot takes them
# as strings, so a quote in a path stays part of it (pasting a path into
# -e "bb='...'" would run whatever follows a quote in it as gnuplot).
# Top: phase-resonance frequency against the sensor's displacement amplitude,
# per level with its error bars, the single-mode fit ω_n(a) (±1 σ band) and,
# if the run had --result, the identified model's backbone at the sensor.
# Bottom: damping ratio against amplitude by the three per-level methods and
# the fit's ζ(a).
if (ARGC >= 1) bb = ARG1
if (ARGC >= 2) out = ARG2
if (!exists("bb")) bb = 'backbone'
if (!exists("out")) out = bb.'.png'
levels = bb.'.csv'
curves = bb.'_curves.csv'
set terminal pngcairo size 900,900 enhanced font ",11"
set output out
set datafile separator ','
set datafile columnheaders
set multiplot layout 2,1
set grid
set key top left
set xlabel 'first-harmonic displacement amplitude at the sensor [mm]'
set ylabel 'phase-resonance frequency [Hz]'
plot curves using ($1*1e3):($2-$3):($2+$3) with filledcurves lc rgb '#c8d8f0' title 'single-mode fit ±1σ', \
     curves using ($1*1e3):2 with lines lw 2 lc rgb '#2050a0' title 'single-mode fit ω_n(a)', \
     curves using ($1*1e3):(column('model_frequency_Hz')) with lines lw 2 dt 2 lc rgb 'black' title 'identified model', \
     levels using ($5*1e3):3:($6*1e3):4 with xyerrorbars pt 7 ps 1.2 lc rgb '#c03020' title 'measured (per level)'
set ylabel 'damping ratio ζ [-]'
set key below horizontal
plot curves using ($1*1e3):($4-$5):($4+$5) with filledcurves lc rgb '#c8d8f0' title 'single-mode fit ±1σ', \
     curves using ($1*1e3):4 with lines lw 2 lc rgb '#2050a0' title 'single-mode fit ζ(a)', \
     levels using ($5*1e3):11:12 with yerrorbars pt 7 ps 1.2 lc rgb '#c03020' title 'quadrature point', \
     levels using ($5*1e3):13:14 with yerrorbars pt 5 ps 1.0 lc rgb '#208040' title 'local single-mode fit', \
     levels using ($5*1e3):15:16 with yerrorbars pt 9 ps 1.2 lc rgb '#806020' title 'half-power'
unset multiplot
