"""layers.rollout: a trained experiment rolled out on one sequence by the
C++ code of `layers rollout` (plugins found as the CLI finds them), with
the predictions read back."""
from . import _core


def rollout(experiment, sequence, out, checkpoint="best", horizon=0, sets=()):
    """Roll `experiment`'s model (its checkpoint: best, last or a file) out on
    `sequence` for `horizon` predicted frames (0: to the end of the sequence,
    as `layers rollout --frames`; -1: the experiment's eval.horizon), writing
    predictions.h5 and metrics.json into `out` exactly as
    `layers rollout <experiment> --sequence <sequence> --out <out>` does.

    Returns a dict: model, checkpoint, frames, diverged, the two file paths,
    and `garments`: the predicted positions of each garment, [T,V,3] torch
    tensors (numpy arrays where torch is not installed), ground truth at
    frames 0 and 1 as the rollout starts from it. `sets` are --set
    overrides ("key.path=value"; a single string is one override)."""
    sets = [sets] if isinstance(sets, str) else list(sets)  # one override given as a string
    result = _core.rollout(experiment, sequence, out, checkpoint, horizon, sets)
    predicted = _core.open_dataset(result["predictions"]).read_sequence(sequence)
    garments = [g["positions"] for g in predicted["garments"]]
    try:
        import torch

        garments = [torch.from_numpy(g) for g in garments]
    except ImportError:  # pragma: no cover
        pass
    result["garments"] = garments
    return result
