# %% [markdown]
# # The paper's set-up, from recordings to the backbone, in Python
#
# A notebook in the percent format (`# %%` cells): open it in JupyterLab
# with jupytext, in VS Code or Spyder, or run it whole with
# `python3 examples/notebook/paper_setup.py [OUTPUT_FOLDER]`
# (docs/python.md says how `import beamid` finds the module).
#
# It walks the paper's experiment: a clamped steel beam resting on a rod
# whose contact is a nonlinear torsional spring, M = k1·θ + k2·θ² + k3·θ³ +
# c·θ̇, driven near its first resonance at three force levels. The
# recordings come from beamid's independent time-domain simulator; the
# same calls read a real test's campaign folder (docs/campaign-format.md).

# %%
import os
import pathlib
import sys

import matplotlib

if "ipykernel" not in sys.modules:
    matplotlib.use("Agg")  # run as a script: draw into files, no window
import matplotlib.pyplot as plt
import numpy as np

import beamid

here = pathlib.Path(__file__).resolve().parent if "__file__" in globals() else pathlib.Path.cwd()
scenario = here.parent / "scenarios" / "paper_base.json"
arguments = [a for a in sys.argv[1:] if not a.startswith("-")] if "ipykernel" not in sys.modules else []
output = pathlib.Path(arguments[0] if arguments else "paper_setup_notebook")
output.mkdir(parents=True, exist_ok=True)
print("beamid", beamid.__version__, "- writing into", output)

# %% [markdown]
# ## 1. The recordings
# Three force levels (1, 4 and 9 N), 33 steps each, force and three
# accelerometers per step (about 10 s to simulate).

# %%
campaign = output / "campaign"
beamid.simulate(scenario, campaign, overwrite=True,
                progress=lambda task, fraction, what: print(f"\r{task} {fraction:4.0%} {what:40}", end=""))
print()
info = beamid.read_campaign(campaign)
print(info["name"], "-", len(info["steps"]), "steps, levels", info["levels"])
print("sensors:", [(s["channel"], s["position_m"]) for s in info["sensors"]])

# %% [markdown]
# ## 2. Harmonic phasors of every step
# Each step's steady state, harmonics 1..5, with their σ from the
# recording's own noise; every step turned so that the force is real.

# %%
phasors = beamid.extract(campaign)
table = beamid.to_pandas(phasors)
print(table[table.harmonic == 1][["level", "frequency_Hz", "channel", "amplitude", "phase_rad"]].head(8))

fig, ax = plt.subplots(figsize=(6, 4))
for level, data in phasors["levels"].items():
    acc3 = data["channels"]["acc3"]
    ax.errorbar(data["frequency_hz"], np.abs(acc3["phasors"][:, 0]), yerr=2 * acc3["std_amplitude"][:, 0],
                fmt="o-", ms=3, label=f"{level}")
ax.set(xlabel="frequency [Hz]", ylabel="|acc3|, 1st harmonic [m/s²]", title="Measured response at 0.57 m")
ax.legend(title="level")
fig.tight_layout()
fig.savefig(output / "response_curves.png", dpi=120)

# %% [markdown]
# ## 3. Identify the support from acc1 and acc2; acc3 held out

# %%
result_file = output / "result.json"
result = beamid.identify(campaign, fit=["acc1", "acc2"], validate=["acc3"], output=result_file)
print(beamid.to_pandas(result)[["parameter", "unit", "value", "std", "lower_95", "upper_95"]])
print("fit:", result["fit"]["verdict"])
print("acc3 held out: worst 1st-harmonic error",
      f"{result['validation']['acc3']['worst_h1_relative_error']:.2%}")

# %% [markdown]
# ## 4. Predict the held-out sensor (the paper's Fig. 4)

# %%
prediction = beamid.predict(result_file, x=0.57, campaign=campaign)
print(f"acc3 predicted at every step, worst 1st-harmonic error {prediction['worst_h1_relative_error']:.2%}")

# %% [markdown]
# ## 5. The backbone: model-free from the measurements, and the model's
# Per level the phase-resonance point (where the response lags the force
# by 90°) with its σ, against the identified model's backbone.

# %%
measured = beamid.measured_backbone(campaign, channel="acc3", result=result_file)
levels = measured["levels"]
amplitude = np.array([level["amplitude_m"] for level in levels])
frequency = np.array([level["quadrature_frequency_hz"] for level in levels])
model = measured["document"]["model_backbone"]
fig, ax = plt.subplots(figsize=(6, 4))
ax.errorbar(frequency, 1e3 * amplitude, xerr=2 * np.array([level["quadrature_frequency_std_hz"] for level in levels]),
            yerr=2e3 * np.array([level["amplitude_std_m"] for level in levels]), fmt="o", label="measured (±2σ)")
# Beyond the largest measured phase-resonance amplitude the model extrapolates: drawn dashed.
model_amplitude = np.array([p["amplitude_m"] for p in model])
model_frequency = np.array([p["frequency_Hz"] for p in model])
inside = model_amplitude <= np.nanmax(amplitude)
ax.plot(model_frequency[inside], 1e3 * model_amplitude[inside], "-", color="C1", label="identified model")
ax.plot(model_frequency[~inside], 1e3 * model_amplitude[~inside], "--", color="C1",
        label="identified model, beyond the measured amplitudes")
ax.set(xlabel="frequency [Hz]", ylabel="displacement amplitude at 0.57 m [mm]", title="Backbone")
ax.legend()
fig.tight_layout()
fig.savefig(output / "backbone.png", dpi=120)
print(beamid.to_pandas(measured)[["level", "quadrature_frequency_Hz", "amplitude_m", "zeta", "zeta_std"]])
print("damping against amplitude:", measured["damping_trend"]["verdict"])
