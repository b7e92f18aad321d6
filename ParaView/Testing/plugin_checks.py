# SPDX-License-Identifier: GPL-3.0-or-later
"""What the plugin's pvbatch tests share: checks that collect failures, the data folder, and
running a plain VTK algorithm for the expected result."""
import os
import sys

DATA = os.environ["MESOLENS_DATA_DIR"]
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)


def data(relative):
    return os.path.join(DATA, relative)


def vtk_output(algorithm, port=0):
    algorithm.Update()
    return algorithm.GetOutputDataObject(port)


def finish(passed_message):
    """Exits 1 after any failed check, else prints `passed_message`."""
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
    print(passed_message)
