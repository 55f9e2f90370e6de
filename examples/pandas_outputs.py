"""Reads an impactlab run's outputs into pandas, with the units parsed out of the headers.

    impactlab run reference-data/decks/rod.bdf --out out/rod
    python3 examples/pandas_outputs.py out/rod

Every CSV header is `name [unit]`: the frames get the bare names as columns and the
units in `frame.attrs["units"]` ({name: unit}); `summary.json` carries its own `units`.
"""

import json
import re
import sys
from pathlib import Path

import pandas as pd

HEADER = re.compile(r"^(?P<name>[^\[\]]+) \[(?P<unit>[^\[\]]*)\]$")


def read_csv(path):
    """One of the run's CSVs: columns named without units, units in attrs["units"]."""
    frame = pd.read_csv(path)
    units = {}
    for header in frame.columns:
        m = HEADER.match(header)
        if m is None:
            raise ValueError(f"{path}: column {header!r} is not 'name [unit]'")
        units[m["name"]] = m["unit"]
    frame.columns = list(units)
    frame.attrs["units"] = units
    return frame


def read_run(out_dir):
    """history.csv, energy.csv and summary.json of a run's output directory."""
    out = Path(out_dir)
    history = read_csv(out / "history.csv")
    energy = read_csv(out / "energy.csv")
    summary = json.loads((out / "summary.json").read_text())
    return history, energy, summary


def main(out_dir):
    history, energy, summary = read_run(out_dir)
    hu, eu = history.attrs["units"], energy.attrs["units"]
    peak = history["contact_force"].idxmax()
    # repr() prints the shortest text that reads back to the same float.
    print(f"peak_force = {float(history['contact_force'][peak])!r} {hu['contact_force']}")
    print(f"peak_force_time = {float(history['time'][peak])!r} {hu['time']}")
    print(f"final_total = {float(energy['total'].iloc[-1])!r} {eu['total']}")
    print(f"max_abs_error = {float(energy['error'].abs().max())!r} {eu['error']}")
    print(f"energy_unit = {summary['units']['energy']}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(f"usage: {sys.argv[0]} OUT_DIR")
    main(sys.argv[1])
