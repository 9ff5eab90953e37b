"""Reference curves of ../shared/refdata (or $SPHFSI_REFDATA) for the plotting tools: a CSV whose
comment lines start with '#', read as a dict of numpy columns."""
import os

import numpy as np

ref_dir = os.environ.get("SPHFSI_REFDATA", "../shared/refdata")


def load_ref(name):
    """columns of a refdata CSV as a dict of arrays"""
    lines = [l for l in open(os.path.join(ref_dir, name)) if not l.startswith("#")]
    cols = lines[0].strip().split(",")
    data = np.array([[float(v) for v in l.strip().split(",")] for l in lines[1:] if l.strip()])
    return {c: data[:, k] for k, c in enumerate(cols)}
