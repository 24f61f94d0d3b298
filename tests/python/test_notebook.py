"""The notebook example (examples/notebook/paper_setup.py) runs from recordings to the backbone plot.

It is run as a user runs it, by the interpreter in a fresh process, into a temporary folder; its figures must be
PNG images of the size it draws, its files those of the workflows it calls, and its identified support the
simulation's truth within the intervals it prints.
"""

import os
import struct
import subprocess
import sys
import tempfile
import unittest

from beamid_test_support import SOURCE_DIR, read_json

NOTEBOOK = os.path.join(SOURCE_DIR, "examples", "notebook", "paper_setup.py")


def png_size(path):
    """Width and height of a PNG image, from its IHDR chunk."""
    with open(path, "rb") as file:
        header = file.read(24)
    if header[:8] != b"\x89PNG\r\n\x1a\n" or header[12:16] != b"IHDR":
        raise AssertionError(path + " is no PNG image")
    return struct.unpack(">II", header[16:24])


class Notebook(unittest.TestCase):
    def test_runs_from_the_recordings_to_the_backbone_plot(self):
        with tempfile.TemporaryDirectory(prefix="beamid_notebook_test_") as folder:
            output = os.path.join(folder, "out")
            # matplotlib's font cache in the folder, not the user's home.
            run = subprocess.run([sys.executable, NOTEBOOK, output], cwd=folder, capture_output=True, text=True,
                                 env=dict(os.environ, MPLCONFIGDIR=folder), check=False)
            self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
            # 6 × 4 inches at 120 dpi.
            for figure in ("response_curves.png", "backbone.png"):
                self.assertEqual(png_size(os.path.join(output, figure)), (720, 480), figure)
            self.assertIn("acc3 predicted at every step", run.stdout)
            truth = {p["name"]: p["value"] for p in read_json(os.path.join(output, "campaign", "truth.json"))
                     ["support_law"]["parameters"]}
            result = read_json(os.path.join(output, "result.json"))
            for name in ("k1", "k3"):
                parameter = result["parameters"][name]
                self.assertLess(abs(parameter["value"] - truth[name]) / parameter["std"], 4, name)


if __name__ == "__main__":
    unittest.main()
