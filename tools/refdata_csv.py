"""The reference data for the plotting tools, looked for as the program looks (src/base/refdata.c) and
from any current directory: $SPHFSI_REFDATA when set (then only there), else the first of
TOOLS/../refdata (installed: PREFIX/share/sphfsi/tools beside PREFIX/share/sphfsi/refdata),
TOOLS/../../shared/refdata (a checkout with shared/ beside it) and ../shared/refdata from the current
directory that holds the file.  A file found nowhere is said in one line on stderr, not dropped
silently.  load_ref reads a CSV whose comment lines start with '#' as a dict of numpy columns."""
import os
import sys

import numpy as np

_tools = os.path.dirname(os.path.abspath(__file__))
_env = os.environ.get("SPHFSI_REFDATA")
ref_dirs = [_env] if _env else [os.path.normpath(os.path.join(_tools, "..", "refdata")),
                                os.path.normpath(os.path.join(_tools, "..", "..", "shared", "refdata")),
                                os.path.join("..", "shared", "refdata")]
_told = set()  # one line per file, however often a tool asks for it


def ref_path(name, without="the experiment is left out", level="warning"):
    """path of the reference file NAME, or None after one line saying what the tool does without it"""
    for d in ref_dirs:
        path = os.path.join(d, name)
        if os.path.exists(path):
            return path
    if name not in _told:
        _told.add(name)
        print(f"{os.path.basename(sys.argv[0])}: {level}: reference data {name} not found in {', '.join(ref_dirs)}: "
              f"{without} (SPHFSI_REFDATA=DIR names the folder)", file=sys.stderr)
    return None


def load_ref(name):
    """columns of a refdata CSV as a dict of arrays; the tool stops when the file is not found (it
    draws the comparison with the experiment)"""
    path = ref_path(name, "cannot compare with the experiment", "error")
    if path is None:
        sys.exit(1)
    lines = [l for l in open(path) if not l.startswith("#")]
    cols = lines[0].strip().split(",")
    data = np.array([[float(v) for v in l.strip().split(",")] for l in lines[1:] if l.strip()])
    return {c: data[:, k] for k, c in enumerate(cols)}
