"""What the Python module's tests share: the program, a small simulated campaign, and comparisons of numbers.

The module and the program run the same workflows on the same input, so their numbers agree to the last digit or
so: the tests compare them to a relative 1e-12 (RELATIVE).
"""

import json
import math
import os
import subprocess

import numpy

SOURCE_DIR = os.environ.get("BEAMID_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
PROGRAM = os.environ.get("BEAMID_EXECUTABLE", os.path.join(SOURCE_DIR, "build", "release", "beamid"))
MODEL_FILE = os.path.join(SOURCE_DIR, "examples", "paper_setup", "model.json")
RELATIVE = 1e-12


def run_program(*arguments, expect=0):
    """Runs beamid with these arguments; returns its stdout and stderr, checking its exit code."""
    run = subprocess.run([PROGRAM, *arguments], capture_output=True, text=True, check=False)
    if run.returncode != expect:
        raise AssertionError("beamid %s: exit %d, expected %d\n%s%s" % (
            " ".join(arguments), run.returncode, expect, run.stdout, run.stderr))
    return run.stdout, run.stderr


def read_json(path):
    with open(path, encoding="utf-8") as file:
        return json.load(file)


def write_scenario(path, levels, seed):
    """The demo's scenario (examples/scenarios/paper_base.json) with these levels, its noise seeded so."""
    scenario = read_json(os.path.join(SOURCE_DIR, "examples", "scenarios", "paper_base.json"))
    scenario["name"] = "python test"
    scenario["levels"] = levels
    scenario["noise"]["seed"] = seed
    with open(path, "w", encoding="utf-8") as file:
        json.dump(scenario, file)


def error_message(stderr, prefix):
    """The text the program prints after 'beamid: PREFIX: ' (its last line of stderr)."""
    line = stderr.strip().splitlines()[-1]
    head = "beamid: %s: " % prefix
    if not line.startswith(head):
        raise AssertionError("not an error line of kind %r: %r" % (prefix, line))
    return line[len(head):]


def assert_close(testcase, actual, expected, what, rtol=RELATIVE):
    """Arrays or numbers equal to rtol (NaN where the other has NaN; null in JSON is NaN)."""
    actual = numpy.asarray(actual, dtype=complex if numpy.iscomplexobj(actual) else float)
    expected = numpy.asarray(
        [math.nan if v is None else v for v in numpy.ravel(numpy.asarray(expected, dtype=object))],
        dtype=actual.dtype).reshape(numpy.shape(expected))
    testcase.assertEqual(actual.shape, expected.shape, what)
    numpy.testing.assert_allclose(actual, expected, rtol=rtol, atol=0, equal_nan=True, err_msg=what)


def assert_documents_equal(testcase, actual, expected, path="", ignore=("seconds",)):
    """Two JSON documents equal, numbers to RELATIVE; keys naming a time (ignore) are left out."""
    if isinstance(expected, dict):
        testcase.assertIsInstance(actual, dict, path)
        keys = [k for k in expected if not any(word in k for word in ignore)]
        testcase.assertEqual(sorted(k for k in actual if not any(word in k for word in ignore)), sorted(keys), path)
        for key in keys:
            assert_documents_equal(testcase, actual[key], expected[key], path + "/" + key, ignore)
    elif isinstance(expected, list):
        testcase.assertIsInstance(actual, list, path)
        testcase.assertEqual(len(actual), len(expected), path)
        for i, (a, e) in enumerate(zip(actual, expected)):
            assert_documents_equal(testcase, a, e, "%s/%d" % (path, i), ignore)
    elif isinstance(expected, float) and not isinstance(actual, bool):
        testcase.assertIsInstance(actual, (int, float), path)
        testcase.assertTrue(math.isclose(actual, expected, rel_tol=RELATIVE, abs_tol=0.0) or actual == expected,
                            "%s: %r != %r" % (path, actual, expected))
    else:
        testcase.assertEqual(actual, expected, path)
