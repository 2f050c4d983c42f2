"""layers: the LAYERS-H5 datasets, training windows, the evaluation's measures
and the model zoo's rollouts from Python.

The C++ toolkit's own code, bound with pybind11 (docs/python.md):

    import layers
    ds = layers.open_dataset("runs/quickstart/data")
    seq = ds.read_sequence(ds.ids()[0])          # numpy arrays, the format's shapes
    body = seq["body"]; g = seq["garments"][0]
    layers.h_collision(g["positions"][5], body["positions"][5], body["faces"])

Every C++ error arrives as layers.Error (a bad input as its subclass
layers.InputError) whose message is the C++ line: file, field, expected, got.
"""
from ._core import (  # noqa: F401
    Dataset,
    Error,
    InputError,
    error_mm,
    h_collision,
    h_crossing,
    l_collision,
    l_crossing,
    epoch_windows,
    models,
    open_dataset,
    plugin_problems,
    read_stats,
    stretch,
)
from .zoo import rollout  # noqa: F401

try:  # the windows need torch (Debian's python3-torch)
    from .windows import WindowDataset, collate_windows  # noqa: F401
except ImportError:  # pragma: no cover
    pass

__all__ = [
    "Dataset",
    "Error",
    "InputError",
    "error_mm",
    "h_collision",
    "h_crossing",
    "l_collision",
    "l_crossing",
    "epoch_windows",
    "models",
    "open_dataset",
    "plugin_problems",
    "read_stats",
    "rollout",
    "stretch",
    "WindowDataset",
    "collate_windows",
]
