"""The module's functions on a small simulated campaign give what the program writes for the same options."""

import math
import os
import pathlib
import shutil
import tempfile
import unittest

import numpy

import beamid
from beamid_test_support import (MODEL_FILE, SOURCE_DIR, assert_close, assert_documents_equal, error_message, read_json,
                                 run_program, write_scenario)

# Two levels of five steps about the resonance (54 Hz): enough for a fit with a held-out channel, a diagnosis
# and a measured backbone, in seconds.
LEVELS = [{"label": "low", "force_amplitude_N": 1.0, "frequencies_Hz": {"start": 53.0, "stop": 55.0, "step": 0.5}},
          {"label": "high", "force_amplitude_N": 4.0, "frequencies_Hz": {"start": 53.0, "stop": 55.0, "step": 0.5}}]

folder = None  # the module's temporary folder: the campaign and the program's files
paths = {}


def setUpModule():
    global folder
    folder = tempfile.TemporaryDirectory(prefix="beamid_python_test_")
    for name in ("scenario.json", "campaign", "phasors.json", "phasors.csv", "result.json", "parameters.csv",
                 "prediction.json", "diagnosis.json", "measured", "model_backbone", "frc"):
        paths[name] = os.path.join(folder.name, name)
    write_scenario(paths["scenario.json"], LEVELS, seed=11)
    campaign = paths["campaign"]
    run_program("-q", "simulate", paths["scenario.json"], "-o", campaign)
    run_program("-q", "extract", campaign, "-o", paths["phasors.json"], "--csv", paths["phasors.csv"])
    run_program("-q", "identify", campaign, "--fit", "acc1,acc2", "--validate", "acc3", "--phasors",
                paths["phasors.json"], "-o", paths["result.json"], "--csv", paths["parameters.csv"])
    run_program("-q", "predict", paths["result.json"], "--x", "0.57", "--campaign", campaign, "-o",
                paths["prediction.json"])
    run_program("-q", "diagnose", campaign, "--fit", "acc1,acc2", "--validate", "acc3", "--phasors",
                paths["phasors.json"], "--candidates", "support_friction", "--no-recording-check", "-o",
                paths["diagnosis.json"])
    run_program("-q", "backbone", "--measured", campaign, "--channel", "acc2", "-o", paths["measured"])
    run_program("-q", "backbone", MODEL_FILE, "--points", "20", "-o", paths["model_backbone"])
    run_program("-q", "frc", MODEL_FILE, "--force-N", "0.5,2", "--from-hz", "52", "--to-hz", "56", "-H", "3",
                "-o", paths["frc"])


def tearDownModule():
    folder.cleanup()


def find_level_step(phasors, file):
    """The level and the row of a step (by its recording's file) in extract's dict."""
    for level, data in phasors["levels"].items():
        if file in data["files"]:
            return level, data["files"].index(file)
    raise AssertionError("no step " + file)


class Simulate(unittest.TestCase):
    def test_the_campaign_is_the_programs_byte_for_byte(self):
        steps = []
        output = os.path.join(folder.name, "simulated_by_python")
        simulation = beamid.simulate(paths["scenario.json"], output, progress=lambda *report: steps.append(report))
        written = read_json(os.path.join(paths["campaign"], "campaign.json"))
        self.assertEqual(simulation["num_steps"], len(written["steps"]))
        self.assertEqual(simulation["document"], written)
        self.assertGreater(len(steps), 0)
        compared = 0
        for folder_path, _, files in os.walk(paths["campaign"]):
            for name in files:
                relative = os.path.relpath(os.path.join(folder_path, name), paths["campaign"])
                with open(os.path.join(paths["campaign"], relative), "rb") as a, \
                        open(os.path.join(output, relative), "rb") as b:
                    self.assertEqual(a.read(), b.read(), relative)
                compared += 1
        self.assertEqual(compared, simulation["num_steps"] + 2)  # the recordings, campaign.json and truth.json

    def test_a_campaign_already_there_is_an_input_error_with_the_programs_message(self):
        _, stderr = run_program("-q", "simulate", paths["scenario.json"], "-o", paths["campaign"], expect=2)
        with self.assertRaises(beamid.InputError) as raised:
            beamid.simulate(paths["scenario.json"], paths["campaign"])
        self.assertEqual(str(raised.exception), error_message(stderr, "error"))


class ReadCampaign(unittest.TestCase):
    def test_holds_the_campaign_files_channels_and_steps(self):
        campaign = beamid.read_campaign(paths["campaign"])
        written = read_json(os.path.join(paths["campaign"], "campaign.json"))
        self.assertEqual(campaign["name"], written["name"])
        self.assertEqual([s["channel"] for s in campaign["sensors"]], ["acc1", "acc2", "acc3"])
        self.assertEqual([s["position_m"] for s in campaign["sensors"]], [0.1, 0.3, 0.57])
        self.assertEqual(campaign["excitation"]["channel"], "force")
        self.assertEqual([s["file"] for s in campaign["steps"]], [s["file"] for s in written["steps"]])
        self.assertEqual([s["frequency_hz"] for s in campaign["steps"]], [s["frequency_Hz"] for s in written["steps"]])
        self.assertEqual(campaign["levels"], ["low", "high"])
        self.assertEqual(beamid.read_campaign(pathlib.Path(paths["campaign"]))["steps"], campaign["steps"])
        self.assertEqual(campaign["beam"]["length_m"], 0.6)
        # The content hash the program's phasors carry.
        self.assertEqual(campaign["sha256"], read_json(paths["phasors.json"])["campaign_sha256"])


class Extract(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.phasors = beamid.extract(paths["campaign"])

    def test_phasors_are_the_programs_by_level_and_channel(self):
        written = read_json(paths["phasors.json"])
        self.assertEqual(self.phasors["num_harmonics"], 5)
        self.assertEqual(list(self.phasors["levels"]), ["low", "high"])
        self.assertEqual(sum(len(d["files"]) for d in self.phasors["levels"].values()), len(written["steps"]))
        for step in written["steps"]:
            level, row = find_level_step(self.phasors, step["file"])
            self.assertEqual(level, step["level"])
            data = self.phasors["levels"][level]
            assert_close(self, data["frequency_hz"][row], step["frequency_Hz"], step["file"])
            assert_close(self, data["frequency_std_hz"][row], step["frequency_std_Hz"], step["file"])
            self.assertEqual([c["channel"] for c in step["channels"]], list(data["channels"]))
            for channel in step["channels"]:
                c = data["channels"][channel["channel"]]
                what = "%s %s" % (step["file"], channel["channel"])
                self.assertEqual(c["quantity"], channel["quantity"], what)
                expected = [h["re"] + 1j * h["im"] for h in channel["harmonics"]]
                assert_close(self, c["phasors"][row], expected, what)
                assert_close(self, c["std_real"][row], [h["std_re"] for h in channel["harmonics"]], what)
                assert_close(self, c["std_imag"][row], [h["std_im"] for h in channel["harmonics"]], what)
                assert_close(self, c["correlation"][row], [h["correlation"] for h in channel["harmonics"]], what)
                assert_close(self, c["std_amplitude"][row], [h["std_amplitude"] for h in channel["harmonics"]], what)
                assert_close(self, c["mean"][row], channel["mean"], what)
                assert_close(self, c["snr_db"][row], channel["snr_dB"], what)
        # Referenced to the force: its fundamental is real and positive at every step.
        for data in self.phasors["levels"].values():
            force = data["channels"]["force"]["phasors"][:, 0]
            self.assertTrue(numpy.all(force.imag == 0.0) and numpy.all(force.real > 0.0))

    def test_to_pandas_is_the_programs_csv(self):
        import pandas
        table = beamid.to_pandas(self.phasors)
        written = pandas.read_csv(paths["phasors.csv"])
        self.assertEqual(list(table.columns), list(written.columns))
        self.assertEqual(len(table), len(written))
        for column in ("file", "level", "channel", "quantity", "unit", "harmonic"):
            self.assertEqual(list(table[column]), list(written[column]), column)
        # The CSV's precision: 12 digits, 6 for the uncertainties and positions, 4 for the SNR.
        for column in written.columns:
            if written[column].dtype.kind != "f":
                continue
            digits = 12 if column in ("nominal_frequency_Hz", "frequency_Hz", "re", "im", "amplitude",
                                      "phase_rad") else 4 if column == "snr_dB" else 6
            assert_close(self, table[column].to_numpy(), written[column].to_numpy(), column,
                         rtol=0.6 * 10.0 ** (1 - digits))

    def test_channels_and_harmonics_are_the_arguments(self):
        output = os.path.join(folder.name, "phasors_h2.json")
        run_program("-q", "extract", paths["campaign"], "-H", "2", "--channel", "acc2", "--threads", "1", "-o", output)
        phasors = beamid.extract(paths["campaign"], harmonics=2, channels=["acc2"], threads=1)
        self.assertEqual(phasors["num_harmonics"], 2)
        data = phasors["levels"]["high"]
        self.assertEqual(data["channels"]["acc2"]["phasors"].shape, (5, 2))
        for step in read_json(output)["steps"]:
            level, row = find_level_step(phasors, step["file"])
            acc2 = [c for c in step["channels"] if c["channel"] == "acc2"][0]
            assert_close(self, phasors["levels"][level]["channels"]["acc2"]["phasors"][row],
                         [h["re"] + 1j * h["im"] for h in acc2["harmonics"]], step["file"])

    def test_output_keeps_the_programs_files(self):
        output = os.path.join(folder.name, "kept", "phasors.json")
        phasors = beamid.extract(paths["campaign"], output=output)
        self.assertEqual(phasors["output"], output)
        assert_documents_equal(self, read_json(output), read_json(paths["phasors.json"]))
        self.assertIsNone(self.phasors["output"])


class Identify(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.result = beamid.identify(paths["campaign"], fit=["acc1", "acc2"], validate=["acc3"],
                                     phasors=paths["phasors.json"])

    def test_parameters_and_intervals_are_the_programs(self):
        written = read_json(paths["result.json"])
        self.assertEqual(self.result["parameter_names"], list(written["parameters"]))
        self.assertEqual(self.result["parameter_names"], ["k1", "k2", "k3", "c", "loss_factor"])
        for name, p in self.result["parameters"].items():
            w = written["parameters"][name]
            assert_close(self, [p["value"], p["std"], p["lower_95"], p["upper_95"], p["std_model_error"]],
                         [w["value"], w["std"], w["ci95"][0], w["ci95"][1], w["std_model_error"]], name)
            self.assertEqual(p["unit"], w["unit"], name)
        totals = {i["name"]: i for i in written["damping_laws"]["model_form_intervals"]}
        for name in ("k1", "k2", "k3", "c"):
            p = self.result["parameters"][name]
            assert_close(self, [p["total_lower_95"], p["total_upper_95"]], totals[name]["ci95"], name)
        self.assertTrue(math.isnan(self.result["parameters"]["loss_factor"]["total_lower_95"]))
        assert_close(self, self.result["covariance"], written["covariance"], "covariance")
        assert_close(self, self.result["fit"]["reduced_chi_square"], written["fit"]["reduced_chi_square"], "chi2")
        self.assertEqual(self.result["fit"]["channels"], ["acc1", "acc2"])
        # The simulated support is found: k3 = 3e5 within its interval.
        k3 = self.result["parameters"]["k3"]
        self.assertLess(k3["lower_95"], 3e5)
        self.assertGreater(k3["upper_95"], 3e5)

    def test_held_out_channel_is_the_programs(self):
        written = read_json(paths["result.json"])["validation"]["acc3"]
        acc3 = self.result["validation"]["acc3"]
        assert_close(self, acc3["worst_h1_relative_error"], written["worst_h1_relative_error"], "worst h1")
        self.assertEqual(acc3["predicted"].shape[0], len(written["steps"]))
        self.assertEqual(acc3["files"], [s["file"] for s in written["steps"]])
        self.assertLess(acc3["worst_h1_relative_error"], 0.05)

    def test_whole_result_file_is_the_programs(self):
        assert_documents_equal(self, self.result["document"], read_json(paths["result.json"]))
        self.assertTrue(self.result["fit"]["within_noise"])
        self.assertEqual(self.result["fit"]["verdict"], self.result["document"]["fit"]["verdict"])

    def test_to_pandas_is_the_programs_csv(self):
        import pandas
        table = beamid.to_pandas(self.result)
        written = pandas.read_csv(paths["parameters.csv"], keep_default_na=False)
        self.assertEqual(list(table.columns), list(written.columns))
        self.assertEqual(list(table["parameter"]), list(written["parameter"]))
        self.assertEqual(list(table["total_holds"]), list(written["total_holds"]))
        # The CSV's precision: 9 digits, 3 for the σ's.
        for column in ("value", "std", "lower_95", "upper_95", "std_model_error", "total_lower_95", "total_upper_95"):
            assert_close(self, table[column].to_numpy(), pandas.to_numeric(written[column]).to_numpy(), column,
                         rtol=6e-3 if column.startswith("std") else 6e-9)


class Predict(unittest.TestCase):
    def test_prediction_is_the_programs(self):
        prediction = beamid.predict(paths["result.json"], x=0.57, campaign=paths["campaign"])
        written = read_json(paths["prediction.json"])
        assert_documents_equal(self, prediction["document"], written)
        self.assertEqual(prediction["compared_channel"], "acc3")
        self.assertEqual(prediction["files"], [s["file"] for s in written["steps"]])
        for row, step in enumerate(written["steps"]):
            assert_close(self, prediction["displacement_m"][row],
                         [h["displacement_m"][0] + 1j * h["displacement_m"][1] for h in step["harmonics"]],
                         step["file"])
            assert_close(self, prediction["relative_error"][row, 0], step["harmonics"][0]["relative_error"],
                         step["file"])
            assert_close(self, prediction["acceleration_history_m_s2"][row], step["acceleration_m_s2"], step["file"])
        self.assertTrue(numpy.all(prediction["converged"]))
        self.assertEqual(len(beamid.to_pandas(prediction)), prediction["displacement_m"].size)


class Diagnose(unittest.TestCase):
    def test_diagnosis_is_the_programs(self):
        diagnosis = beamid.diagnose(paths["campaign"], fit=["acc1", "acc2"], validate=["acc3"],
                                    phasors=paths["phasors.json"], candidates=["support_friction"],
                                    recording_check=False)
        written = read_json(paths["diagnosis.json"])
        assert_documents_equal(self, diagnosis["document"], written)
        self.assertEqual(diagnosis["verdict"], written["verdict"])
        self.assertEqual(diagnosis["verdict"], "no significant discrepancy")
        self.assertEqual([c["name"] for c in diagnosis["candidates"]], ["support_friction"])
        assert_close(self, diagnosis["base"]["chi_square"], written["base"]["chi_square"], "base chi-square")
        self.assertEqual(list(beamid.to_pandas(diagnosis)["candidate"]), ["support_friction"])


class MeasuredBackbone(unittest.TestCase):
    def test_levels_are_the_programs(self):
        import pandas
        backbone = beamid.measured_backbone(paths["campaign"], channel="acc2")
        assert_documents_equal(self, backbone["document"], read_json(paths["measured"] + ".json"))
        self.assertEqual([level["level"] for level in backbone["levels"]], ["low", "high"])
        table = beamid.to_pandas(backbone)
        written = pandas.read_csv(paths["measured"] + ".csv", keep_default_na=False, na_values=[""])
        self.assertEqual(list(table.columns), list(written.columns))
        self.assertEqual(list(table["level"]), list(written["level"]))
        self.assertEqual(list(table["flags"].fillna("")), list(written["flags"].fillna("")))
        # The CSV's precision: 9 digits for values, 3 for their σ.
        for column in written.columns:
            if written[column].dtype.kind == "f":
                rtol = 6e-3 if "_std" in column else 6e-9 if column != "regeneration_relative_rms" else 6e-4
                assert_close(self, table[column].to_numpy(), written[column].to_numpy(), column, rtol=rtol)
        # The phase resonance rises with the level (a hardening support).
        frequencies = [level["quadrature_frequency_hz"] for level in backbone["levels"]]
        self.assertLess(frequencies[0], frequencies[1])


    def test_tables_given_as_paths_are_the_programs(self):
        tables = [pathlib.Path(SOURCE_DIR, "examples", "phasor_tables", level + ".csv")
                  for level in ("low", "mid", "high")]
        prefix = os.path.join(folder.name, "tables")
        run_program("-q", "backbone", "--measured", *map(str, tables), "-o", prefix)
        backbone = beamid.measured_backbone(tables, output=pathlib.Path(prefix))
        self.assertEqual(backbone["output"], prefix)
        assert_documents_equal(self, backbone["document"], read_json(prefix + ".json"))
        self.assertEqual([level["level"] for level in backbone["levels"]], ["low", "mid", "high"])


class ModelBackbone(unittest.TestCase):
    def test_backbone_is_the_programs(self):
        import pandas
        backbone = beamid.model_backbone(MODEL_FILE, points=20)
        written = read_json(paths["model_backbone"] + ".json")
        assert_documents_equal(self, backbone["document"], written)
        self.assertTrue(backbone["complete"])
        assert_close(self, backbone["frequency_hz"], [p["frequency_Hz"] for p in written["points"]], "frequency")
        assert_close(self, backbone["theta_rad"], [[t[0] + 1j * t[1] for t in p["theta_rad"]]
                                                  for p in written["points"]], "theta")
        assert_close(self, backbone["sensors"]["acc3"]["displacement_m"],
                     [[d[0] + 1j * d[1] for d in p["sensors"]["acc3"]["displacement_m"]] for p in written["points"]],
                     "acc3")
        table = beamid.to_pandas(backbone)
        csv = pandas.read_csv(paths["model_backbone"] + ".csv")
        self.assertEqual(list(table.columns), list(csv.columns))
        for column in csv.columns:
            assert_close(self, table[column].to_numpy(), csv[column].to_numpy(), column, rtol=1e-8)


class Frc(unittest.TestCase):
    def test_curves_are_the_programs(self):
        import pandas
        frc = beamid.frc(MODEL_FILE, force_N=[0.5, 2], from_hz=52, to_hz=56, harmonics=3)
        written = read_json(paths["frc"] + ".json")
        assert_documents_equal(self, frc["document"], written)
        self.assertEqual([c["force_N"] for c in frc["curves"]], [0.5, 2])
        self.assertEqual(len(frc["curves"]), len(written["curves"]))
        for curve, expected in zip(frc["curves"], written["curves"]):
            self.assertTrue(curve["complete"])
            self.assertEqual(curve["turning_points"], expected["turning_points"])
            points = expected["points"]
            assert_close(self, curve["frequency_hz"], [p["frequency_Hz"] for p in points], "frequency")
            self.assertEqual(list(curve["stable"]), [p["stable"] for p in points])
            assert_close(self, curve["theta_rad"], [[t[0] + 1j * t[1] for t in p["theta_rad"]] for p in points],
                         "theta")
            assert_close(self, curve["sensors"]["acc3"]["acceleration_m_s2"],
                         [[a[0] + 1j * a[1] for a in p["sensors"]["acc3"]["acceleration_m_s2"]] for p in points],
                         "acc3")
        # The strong level folds: its curve has turning points and an unstable branch between them.
        self.assertEqual(frc["curves"][1]["turning_points"], 2)
        self.assertFalse(all(frc["curves"][1]["stable"]))
        table = beamid.to_pandas(frc)
        csv = pandas.read_csv(paths["frc"] + ".csv")
        self.assertEqual(list(table.columns), list(csv.columns))
        for column in csv.columns:
            assert_close(self, table[column].to_numpy(), csv[column].to_numpy(), column, rtol=1e-8)

    def test_a_band_far_from_the_resonance_is_an_input_error_with_the_programs_message(self):
        _, stderr = run_program("-q", "frc", MODEL_FILE, "--from-hz", "5000", "--to-hz", "6000", "-o",
                                os.path.join(folder.name, "far"), expect=2)
        with self.assertRaises(beamid.InputError) as raised:
            beamid.frc(MODEL_FILE, from_hz=5000, to_hz=6000)
        self.assertEqual(str(raised.exception), error_message(stderr, "error"))


class Errors(unittest.TestCase):
    def test_a_full_disk_is_an_environment_error_with_the_programs_message(self):
        if not os.path.exists("/dev/full"):
            self.skipTest("no /dev/full")
        _, stderr = run_program("-q", "extract", paths["campaign"], "-o", "/dev/full", expect=4)
        with self.assertRaises(beamid.EnvironmentError) as raised:
            beamid.extract(paths["campaign"], output="/dev/full")
        self.assertIsInstance(raised.exception, OSError)
        self.assertEqual(str(raised.exception), error_message(stderr, "environment"))
        self.assertIn("free some space", str(raised.exception))

    def test_an_output_over_the_campaign_is_an_input_error_with_the_programs_message(self):
        target = os.path.join(paths["campaign"], "campaign.json")
        _, stderr = run_program("-q", "identify", paths["campaign"], "-o", target, expect=2)
        with self.assertRaises(beamid.InputError) as raised:
            beamid.identify(paths["campaign"], output=target)
        self.assertIsInstance(raised.exception, ValueError)
        self.assertEqual(str(raised.exception), error_message(stderr, "error"))


class Warnings(unittest.TestCase):
    def test_a_campaigns_warning_is_a_beamid_warning_with_the_programs_text(self):
        # A recording that is a byte copy of another step's: the campaign reads, with a warning.
        copy = os.path.join(folder.name, "copied_recording")
        shutil.copytree(paths["campaign"], copy)
        steps = read_json(os.path.join(copy, "campaign.json"))["steps"]
        shutil.copyfile(os.path.join(copy, steps[0]["file"]), os.path.join(copy, steps[1]["file"]))
        _, stderr = run_program("extract", copy, "-o", os.path.join(folder.name, "copied.json"))
        printed = [line for line in stderr.splitlines() if line.startswith("beamid extract: warning: ")]
        self.assertEqual(len(printed), 1, stderr)
        with self.assertWarns(beamid.BeamidWarning) as warned:
            phasors = beamid.extract(copy)
        self.assertEqual(str(warned.warning), printed[0].replace("warning: ", "", 1))
        self.assertEqual(warned.filename, __file__)  # the caller's line, not the module's
        self.assertEqual(phasors["run_warnings"], [printed[0][len("beamid "):].replace("warning: ", "", 1)])
        with self.assertWarns(beamid.BeamidWarning):
            campaign = beamid.read_campaign(copy)
        self.assertIn("holds the same bytes as", campaign["warnings"][0])


class Progress(unittest.TestCase):
    def test_a_fit_abandoned_by_the_callback_leaves_no_worker_process(self):
        def stop_after_the_first_start(task, fraction, what):
            if what.startswith("start "):
                raise LookupError("abandoned")

        with self.assertRaisesRegex(LookupError, "abandoned"):
            beamid.identify(paths["campaign"], fit=["acc1", "acc2"], phasors=paths["phasors.json"], starts=4,
                            workers=2, damping_laws=False, robust=False, progress=stop_after_the_first_start)
        # The worker processes of the starts are gone and reaped: none left running or a zombie.
        with self.assertRaises(ChildProcessError):
            os.waitpid(-1, os.WNOHANG)

    def test_the_callback_sees_each_task_advance_to_its_end(self):
        calls = []
        beamid.identify(paths["campaign"], fit=["acc1", "acc2"], damping_laws=False, robust=False,
                        progress=lambda task, fraction, what: calls.append((task, fraction, what)))
        tasks = [task for task, _, _ in calls]
        self.assertEqual(sorted(set(tasks), key=tasks.index), ["extract", "identify"])
        for task in ("extract", "identify"):
            fractions = [fraction for t, fraction, _ in calls if t == task]
            self.assertEqual(fractions[0], 0.0, task)
            self.assertEqual(fractions, sorted(fractions), task)
        self.assertEqual([f for t, f, _ in calls if t == "extract"][-1], 1.0)
        self.assertIn("direct estimate", [what for _, _, what in calls])


if __name__ == "__main__":
    unittest.main()
