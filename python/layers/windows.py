"""layers.WindowDataset: training windows as `layers train` reads them.

The windows of an epoch -- which sequences, which start frames, in which
shuffled order for a seed and epoch -- come from the C++ loader's own
function (train/window_loader.h epoch_windows), and each window is read by
the C++ reader, so item i is the i-th window the C++ loader reads in that
epoch. No HDF5 file is kept open by the object itself: each process (each
DataLoader worker) opens the dataset on its first read.
"""
import os

import torch

from . import _core


def collate_windows(samples):
    """A batch as the C++ trainer takes one: a list of windows (scenes differ in vertex counts)."""
    return list(samples)


class WindowDataset(torch.utils.data.Dataset):
    """Frames [start - history, start + horizon] of the epoch's windows.

    Each item is a dict of tensors named as the C++ loader's FrameTensors:
    body [n,Vb,3], root [n,3], root_rot [n,4], joints [n,J,3,4],
    wind_rotation [n,4], wind_strength [n], garments (a list of [n,V,3]),
    with id, start and first_frame. `stats` holds stats.h5's normalisation
    statistics (layers.read_stats) when the dataset has them; the models
    normalise with them, the windows are as stored.
    """

    def __init__(self, path, split="train", history=1, horizon=1, stride=1, seed=0, epoch=0, subsets=(),
                 windows_per_epoch=0, inner_only=False, allow_unhashed=False, rank=0, world=1):
        self.path, self.history, self.horizon = path, history, horizon
        self.inner_only, self.allow_unhashed = inner_only, allow_unhashed
        dataset = _core.open_dataset(path, allow_unhashed)
        self.windows = _core.epoch_windows(dataset, split, list(subsets), history, horizon, stride, seed, epoch,
                                           windows_per_epoch, rank, world)
        del dataset  # closes its files: workers fork without an open HDF5 file
        stats = os.path.join(path, "stats.h5")
        self.stats = _core.read_stats(stats) if os.path.isfile(stats) else None
        self._dataset, self._pid = None, None

    def __len__(self):
        return len(self.windows)

    def __getitem__(self, index):
        if self._dataset is None or self._pid != os.getpid():
            self._dataset, self._pid = _core.open_dataset(self.path, self.allow_unhashed), os.getpid()
        seq_id, start = self.windows[index]
        w = self._dataset.read_window(seq_id, start, self.history, self.horizon)
        body, wind = w["body"], w["wind"]
        garments = [g for g in w["garments"] if not self.inner_only or g["layer"] == 0]
        return {
            "id": seq_id,
            "start": start,
            "first_frame": w["first_frame"],
            "body": torch.from_numpy(body["positions"]),
            "root": torch.from_numpy(body["root"]),
            "root_rot": torch.from_numpy(body["root_rot"]),
            "joints": torch.from_numpy(body["joints"]),
            "wind_rotation": torch.from_numpy(wind["rotation"]),
            "wind_strength": torch.from_numpy(wind["strength"]),
            "garments": [torch.from_numpy(g["positions"]) for g in garments],
        }

    def __getstate__(self):
        state = dict(self.__dict__)
        state["_dataset"], state["_pid"] = None, None  # a spawned worker opens its own
        return state
