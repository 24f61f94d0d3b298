"""beamid: identify the nonlinear support of a vibrating beam from stepped-sine tests.

The functions run the use cases of the beamid program (read_campaign, extract,
identify, predict, diagnose, measured_backbone, model_backbone, frc, simulate) and return
plain dicts of numbers, strings and numpy arrays in SI units; to_pandas turns
one into the table the program writes as CSV. docs/python.md describes them.
"""

from ._beamid import (  # noqa: F401 (re-exported)
    BeamidWarning,
    EnvironmentError,
    InputError,
    NumericalError,
    __version__,
    diagnose,
    extract,
    frc,
    identify,
    measured_backbone,
    model_backbone,
    predict,
    read_campaign,
    simulate,
)

for _class in (BeamidWarning, EnvironmentError, InputError, NumericalError):
    _class.__module__ = "beamid"  # as users name them, not the extension's own name

__all__ = [
    "BeamidWarning", "EnvironmentError", "InputError", "NumericalError", "diagnose", "extract", "frc", "identify",
    "measured_backbone", "model_backbone", "predict", "read_campaign", "simulate", "to_pandas",
]


def _pandas():
    # pandas is optional: only to_pandas needs it.
    try:
        import pandas
    except ImportError as error:
        raise ImportError(
            "beamid.to_pandas needs pandas: install the Debian package python3-pandas "
            "(the other functions of beamid do not need it)") from error
    return pandas


def _phasor_rows(phasors):
    # One row per step, channel and harmonic, in the order of `beamid extract --csv`.
    import numpy
    rows = []
    for level, data in phasors["levels"].items():
        for i, step_index in enumerate(data["step_index"]):
            for channel, c in data["channels"].items():
                for k in range(c["phasors"].shape[1]):
                    value = c["phasors"][i, k]
                    if numpy.isnan(value.real):
                        continue
                    rows.append((int(step_index), {
                        "file": data["files"][i], "level": level,
                        "nominal_frequency_Hz": data["nominal_frequency_hz"][i],
                        "frequency_Hz": data["frequency_hz"][i], "frequency_std_Hz": data["frequency_std_hz"][i],
                        "channel": channel, "quantity": c["quantity"], "unit": c["unit"],
                        "position_m": c["position_m"], "harmonic": k + 1, "re": value.real, "im": value.imag,
                        "amplitude": abs(value), "phase_rad": numpy.angle(value),
                        "std_re": c["std_real"][i, k], "std_im": c["std_imag"][i, k],
                        "correlation": c["correlation"][i, k], "std_amplitude": c["std_amplitude"][i, k],
                        "std_phase_rad": c["std_phase_rad"][i, k], "thd": c["thd"][i], "snr_dB": c["snr_db"][i]}))
    rows.sort(key=lambda row: row[0])  # stable: channels and harmonics keep their order
    return [row for _, row in rows]


def _parameter_rows(result):
    # As `beamid identify --csv`: the total interval and what it holds where the damping laws were refitted.
    rows = []
    for name in result["parameter_names"]:
        p = result["parameters"][name]
        has_total = p["total_lower_95"] == p["total_lower_95"]  # not NaN
        rows.append({
            "parameter": name, "unit": p["unit"], "value": p["value"], "std": p["std"],
            "lower_95": p["lower_95"], "upper_95": p["upper_95"], "std_model_error": p["std_model_error"],
            "total_lower_95": p["total_lower_95"], "total_upper_95": p["total_upper_95"],
            "total_holds": result["total_interval_parts"] if has_total else ""})
    return rows


def _measured_level_rows(backbone):
    # As PREFIX.csv of `beamid backbone --measured`: one row per level.
    excitation = backbone["excitation_column"]
    unit_at = excitation.rfind("_")
    excitation_std = excitation[:unit_at] + "_std" + excitation[unit_at:]
    rows = []
    for level in backbone["levels"]:
        flags = []
        for flag in level["flags"]:
            if flag["kind"] not in flags:
                flags.append(flag["kind"])
        rows.append({
            "level": level["level"], "control": level["control"],
            "quadrature_frequency_Hz": level["quadrature_frequency_hz"],
            "quadrature_frequency_std_Hz": level["quadrature_frequency_std_hz"],
            "amplitude_m": level["amplitude_m"], "amplitude_std_m": level["amplitude_std_m"],
            "response_amplitude": level["response_amplitude"],
            "response_amplitude_std": level["response_amplitude_std"],
            excitation: level["excitation_amplitude"], excitation_std: level["excitation_amplitude_std"],
            "zeta_quadrature": level["zeta_quadrature"], "zeta_quadrature_std": level["zeta_quadrature_std"],
            "zeta_local": level["zeta_local"], "zeta_local_std": level["zeta_local_std"],
            "zeta_half_power": level["zeta_half_power"], "zeta_half_power_std": level["zeta_half_power_std"],
            "peak_frequency_Hz": level["peak_frequency_hz"], "peak_frequency_std_Hz": level["peak_frequency_std_hz"],
            "local_natural_frequency_Hz": level["local_natural_frequency_hz"],
            "local_natural_frequency_std_Hz": level["local_natural_frequency_std_hz"],
            "regeneration_relative_rms": level["regeneration_relative_rms"],
            "in_global_fit": int(level["in_global_fit"]), "flags": ";".join(flags),
            "zeta": level["zeta"], "zeta_std": level["zeta_std"]})
    return rows


def _model_backbone_rows(backbone):
    # As PREFIX.csv of `beamid backbone MODEL`: the first harmonic's amplitude at each sensor.
    import numpy
    rows = []
    for i, frequency in enumerate(backbone["frequency_hz"]):
        row = {"theta_amp_rad": backbone["theta_amplitude_rad"][i], "frequency_Hz": frequency,
               "force_N": backbone["force_N"][i], "ms_frequency_Hz": backbone["multiple_scales_frequency_hz"][i]}
        for channel, sensor in backbone["sensors"].items():
            amplitude = abs(sensor["displacement_m"][i, 1])
            row[channel + "_h1_disp_amp_m"] = amplitude
            row[channel + "_h1_acc_amp_m_s2"] = amplitude * (2 * numpy.pi * frequency) ** 2
        rows.append(row)
    return rows


def _frc_rows(frc):
    # As PREFIX.csv of `beamid frc`: one row per point of every curve, harmonics 1..H in amplitude and phase.
    import numpy
    rows = []
    for curve in frc["curves"]:
        for i, frequency in enumerate(curve["frequency_hz"]):
            row = {"force_N": curve["force_N"], "frequency_Hz": frequency, "stable": int(curve["stable"][i])}
            for k in range(1, frc["harmonics"] + 1):
                theta = curve["theta_rad"][i, k]
                row["theta_h%d_amp_rad" % k] = abs(theta)
                row["theta_h%d_phase_rad" % k] = numpy.angle(theta)
            for channel, sensor in curve["sensors"].items():
                for k in range(1, frc["harmonics"] + 1):
                    displacement, acceleration = sensor["displacement_m"][i, k], sensor["acceleration_m_s2"][i, k]
                    row["%s_h%d_disp_amp_m" % (channel, k)] = abs(displacement)
                    row["%s_h%d_disp_phase_rad" % (channel, k)] = numpy.angle(displacement)
                    row["%s_h%d_acc_amp_m_s2" % (channel, k)] = abs(acceleration)
                    row["%s_h%d_acc_phase_rad" % (channel, k)] = numpy.angle(acceleration)
            rows.append(row)
    return rows


def _prediction_rows(prediction):
    # One row per step and harmonic.
    rows = []
    for i, frequency in enumerate(prediction["frequency_hz"]):
        for k in range(prediction["displacement_m"].shape[1]):
            rows.append({
                "level": prediction["levels"][i], "file": prediction["files"][i], "frequency_Hz": frequency,
                "harmonic": k + 1, "displacement_m": prediction["displacement_m"][i, k],
                "displacement_std_real_m": prediction["displacement_std_real_m"][i, k],
                "displacement_std_imag_m": prediction["displacement_std_imag_m"][i, k],
                "acceleration_m_s2": prediction["acceleration_m_s2"][i, k],
                "measured": prediction["measured"][i, k], "predicted": prediction["predicted"][i, k],
                "relative_error": prediction["relative_error"][i, k]})
    return rows


def _candidate_rows(diagnosis):
    # One row per candidate, ranked as the diagnosis ranks them.
    return [{"candidate": c["name"], "status": c["status"], "signature_score": c["signature_score"],
             "chi_square": c["fit"]["chi_square"], "residual_drop": c["residual_drop"], "bic": c["fit"]["bic"],
             "p_value": c["p_value"], "significant": c["significant"],
             "held_out_h1_relative_error": c["fit"]["held_out_h1_relative_error"]}
            for c in diagnosis["candidates"]]


_TABLES = {
    "phasors": _phasor_rows,
    "identify": _parameter_rows,
    "measured_backbone": _measured_level_rows,
    "model_backbone": _model_backbone_rows,
    "frc": _frc_rows,
    "prediction": _prediction_rows,
    "diagnosis": _candidate_rows,
}


def to_pandas(result):
    """The table of a result of beamid as a pandas DataFrame.

    extract: one row per step, channel and harmonic (the columns of `beamid extract --csv`);
    identify: one row per parameter (`beamid identify --csv`);
    measured_backbone: one row per level (PREFIX.csv of `beamid backbone --measured`);
    model_backbone: one row per amplitude (PREFIX.csv of `beamid backbone MODEL`);
    frc: one row per point of every curve (PREFIX.csv of `beamid frc`);
    predict: one row per step and harmonic; diagnose: one row per candidate.
    Raises ImportError with what to install when pandas is missing.
    """
    kind = result.get("kind") if isinstance(result, dict) else None
    if kind not in _TABLES:
        raise TypeError("to_pandas takes the dict of extract, identify, predict, diagnose, measured_backbone, "
                        "model_backbone or frc (got %s)" % ("a dict of kind %r" % kind if kind else type(result).__name__))
    pandas = _pandas()
    return pandas.DataFrame(_TABLES[kind](result))
