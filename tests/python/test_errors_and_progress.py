"""beamid's errors as Python exceptions with the program's messages; progress, Ctrl-C and other threads during
the work; to_pandas without pandas. On the paper's model file: no campaign needed."""

import os
import signal
import sys
import tempfile
import threading
import time
import unittest

import beamid
from beamid_test_support import MODEL_FILE, error_message, run_program

# A backbone long enough (seconds) to be interrupted: many amplitudes and harmonics.
LONG_BACKBONE = {"points": 10000, "harmonics": 15}
# A backbone of a few tenths of a second.
MEDIUM_BACKBONE_POINTS = 1000


class Exceptions(unittest.TestCase):
    def test_a_missing_campaign_is_an_input_error_with_the_programs_message(self):
        with tempfile.TemporaryDirectory(prefix="beamid_python_test_") as root:
            empty, output = os.path.join(root, "empty"), os.path.join(root, "p.json")
            os.mkdir(empty)
            _, stderr = run_program("-q", "extract", empty, "-o", output, expect=2)
            with self.assertRaises(beamid.InputError) as raised:
                beamid.extract(empty, output=output)
        self.assertIsInstance(raised.exception, ValueError)
        self.assertEqual(str(raised.exception), error_message(stderr, "error"))
        self.assertIn("campaign.json", str(raised.exception))

    def test_a_backbone_that_stops_early_is_a_numerical_error_with_the_programs_message(self):
        with tempfile.TemporaryDirectory(prefix="beamid_python_test_") as out:
            _, stderr = run_program("-q", "backbone", MODEL_FILE, "--max-theta-rad", "1", "--points", "30", "-o",
                                    os.path.join(out, "b"), expect=3)
        with self.assertRaises(beamid.NumericalError) as raised:
            beamid.model_backbone(MODEL_FILE, max_theta_rad=1.0, points=30)
        self.assertIsInstance(raised.exception, ArithmeticError)
        self.assertEqual(str(raised.exception), error_message(stderr, "failed"))
        self.assertIn("the backbone stopped early", str(raised.exception))

    def test_classes_are_distinct_and_named_as_the_module(self):
        classes = (beamid.InputError, beamid.NumericalError, beamid.EnvironmentError)
        self.assertEqual([c.__module__ + "." + c.__name__ for c in classes],
                         ["beamid.InputError", "beamid.NumericalError", "beamid.EnvironmentError"])
        self.assertTrue(issubclass(beamid.EnvironmentError, OSError))
        self.assertFalse(issubclass(beamid.InputError, ArithmeticError))
        self.assertFalse(issubclass(beamid.NumericalError, ValueError))

    def test_a_bad_argument_is_an_input_error(self):
        with self.assertRaisesRegex(beamid.InputError, "phasor_uncertainty: unknown weighting 'exact'"):
            beamid.identify("no_campaign", phasor_uncertainty="exact")
        with self.assertRaisesRegex(TypeError, "progress must be None or a callable"):
            beamid.model_backbone(MODEL_FILE, points=2, progress=3)


class Progress(unittest.TestCase):
    def test_the_callback_sees_the_backbone_advance_to_its_end(self):
        calls = []
        beamid.model_backbone(MODEL_FILE, points=20,
                              progress=lambda task, fraction, what: calls.append((task, fraction)))
        self.assertEqual({task for task, _ in calls}, {"backbone"})
        fractions = [fraction for _, fraction in calls]
        self.assertGreaterEqual(len(fractions), 10)
        self.assertEqual(fractions, sorted(fractions))
        self.assertEqual((fractions[0], fractions[-1]), (0.0, 1.0))

    def test_an_exception_of_the_callback_stops_the_work_and_reaches_the_caller(self):
        calls = []

        def stop_at_the_third(task, fraction, what):
            calls.append(fraction)
            if len(calls) == 3:
                raise LookupError("stopped by the callback")

        with self.assertRaisesRegex(LookupError, "stopped by the callback"):
            beamid.model_backbone(MODEL_FILE, progress=stop_at_the_third, **LONG_BACKBONE)
        self.assertEqual(len(calls), 3)  # not called again once it raised
        # The module is usable again.
        self.assertTrue(beamid.model_backbone(MODEL_FILE, points=5)["complete"])


    def test_a_call_of_beamid_from_the_callback_is_refused(self):
        def call_again(task, fraction, what):
            beamid.model_backbone(MODEL_FILE, points=2)

        with self.assertRaisesRegex(RuntimeError, "cannot be called from a progress callback"):
            beamid.model_backbone(MODEL_FILE, points=5, progress=call_again)


class Threads(unittest.TestCase):
    def test_calls_from_several_threads_give_each_its_own_result(self):
        alone = beamid.model_backbone(MODEL_FILE, points=50)["frequency_hz"]
        results = {}

        def trace(name, points):
            results[name] = beamid.model_backbone(MODEL_FILE, points=points)["frequency_hz"]

        threads = [threading.Thread(target=trace, args=(i, 50 if i % 2 == 0 else 30)) for i in range(4)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        for i in range(4):
            self.assertEqual(len(results[i]), 50 if i % 2 == 0 else 30)
        self.assertEqual(list(results[0]), list(alone))
        self.assertEqual(list(results[2]), list(alone))


class Interrupt(unittest.TestCase):
    def test_ctrl_c_abandons_the_work_with_keyboard_interrupt(self):
        # SIGINT from another thread, as a terminal's Ctrl-C, while the work runs without a callback.
        timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
        start = time.monotonic()
        timer.start()
        try:
            with self.assertRaises(KeyboardInterrupt):
                beamid.model_backbone(MODEL_FILE, **LONG_BACKBONE)
        finally:
            timer.cancel()
        # Abandoned at the next progress report, long before the backbone's end.
        self.assertLess(time.monotonic() - start, 2.0)
        self.assertTrue(beamid.model_backbone(MODEL_FILE, points=5)["complete"])

    def test_other_threads_run_while_the_work_does(self):
        counted = [0]
        done = threading.Event()

        def count():
            while not done.is_set():
                counted[0] += 1

        thread = threading.Thread(target=count)
        thread.start()
        try:
            # The counter's pace beside this thread when it sleeps (which releases the GIL).
            before = counted[0]
            time.sleep(0.1)
            pace = (counted[0] - before) / 0.1
            before, start = counted[0], time.monotonic()
            beamid.model_backbone(MODEL_FILE, points=MEDIUM_BACKBONE_POINTS)
            seconds = time.monotonic() - start
            during = counted[0] - before
        finally:
            done.set()
            thread.join()
        self.assertGreater(seconds, 0.1)  # long beside the GIL's switch interval (5 ms)
        # Holding the GIL, the work would let the counter run only at the edges of the call, a few switch
        # intervals; released, the counter keeps much of its pace on the other core.
        self.assertGreater(during, 0.2 * pace * seconds)


class ToPandas(unittest.TestCase):
    def test_without_pandas_says_what_to_install(self):
        backbone = beamid.model_backbone(MODEL_FILE, points=5)
        saved = sys.modules.get("pandas")
        sys.modules["pandas"] = None  # import pandas now fails
        try:
            with self.assertRaisesRegex(ImportError, "install the Debian package python3-pandas"):
                beamid.to_pandas(backbone)
        finally:
            if saved is None:
                del sys.modules["pandas"]
            else:
                sys.modules["pandas"] = saved

    def test_refuses_what_is_no_result_of_beamid(self):
        with self.assertRaisesRegex(TypeError, "to_pandas takes the dict of extract"):
            beamid.to_pandas({"levels": []})


if __name__ == "__main__":
    unittest.main()
