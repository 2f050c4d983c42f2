"""The Python package `layers` against the C++ toolkit (run by ctest as
python_package; docs/python.md): on the regression fixture written by
layers_python_fixture, the ids, splits and every array's content hash equal
what the C++ reader printed; the error and H-collision recomputed in Python
from an evaluation's predictions.h5 equal its metrics.json; damaged or
wrong inputs raise the C++ line as layers.Error / layers.InputError."""
import json
import os
import shutil
import subprocess

import numpy as np
import pytest

import layers


def fnv1a64(array):
    """core/checksum.h's content hash of an array's bytes."""
    h = 1469598103934665603
    for b in np.ascontiguousarray(array).tobytes():
        h = ((h ^ b) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return "%016x" % h


@pytest.fixture(scope="session")
def fixture(tmp_path_factory):
    folder = tmp_path_factory.mktemp("python")
    out = subprocess.run([os.environ["LAYERS_PYTHON_FIXTURE"], str(folder)], check=True, capture_output=True, text=True)
    reference = json.loads(out.stdout)
    reference["folder"] = str(folder)
    return reference


@pytest.fixture(scope="session")
def evaluated(fixture):
    """The fixture evaluated with the `static` reference model (no training)."""
    folder = fixture["folder"]
    source = os.environ["LAYERS_SOURCE_DIR"]
    experiment = os.path.join(folder, "static.yaml")
    with open(experiment, "w") as f:
        f.write("include: [%s/configs/models/static.yaml, %s/configs/experiments/tiny.yaml]\n" % (source, source))
        f.write("data: {dataset: %s}\n" % fixture["dataset"])
        f.write("run: {output: %s/run}\n" % folder)
        f.write("eval: {horizon: 12}\n")
    for verb in ("train", "eval"):
        subprocess.run([os.environ["LAYERS_BIN"], verb, experiment], check=True, capture_output=True, text=True)
    return os.path.join(folder, "run", "eval-test")


def test_ids_and_splits_are_the_readers(fixture):
    ds = layers.open_dataset(fixture["dataset"])
    assert ds.ids() == fixture["ids"]
    assert len(ds) == len(fixture["ids"])
    assert ds.splits() == fixture["splits"]
    info = ds.info("seq0")
    assert info["n_frames"] == 20 and len(info["garments"]) == 2


def test_every_array_hashes_as_in_cpp(fixture):
    ds = layers.open_dataset(fixture["dataset"])
    for seq_id, hashes in fixture["hashes"].items():
        seq = ds.read_sequence(seq_id)
        body, wind = seq["body"], seq["wind"]
        assert body["positions"].shape == (20, body["skin_index"].shape[0], 3)
        got = {
            "body/positions": fnv1a64(body["positions"]),
            "body/faces": fnv1a64(body["faces"]),
            "body/joints": fnv1a64(body["joints"]),
            "body/skin_weight": fnv1a64(body["skin_weight"]),
            "wind/strength": fnv1a64(wind["strength"]),
        }
        for k, g in enumerate(seq["garments"]):
            for name in ("positions", "rest", "faces", "uv"):
                got["garments/%d/%s" % (k, name)] = fnv1a64(g[name])
        assert got == hashes, seq_id


def test_read_frames_is_a_slice_of_the_sequence(fixture):
    ds = layers.open_dataset(fixture["dataset"])
    whole = ds.read_sequence("seq4")
    part = ds.read_frames("seq4", 5, 3)
    assert part["first_frame"] == 5 and part["n_frames"] == 3
    np.testing.assert_array_equal(part["garments"][1]["positions"], whole["garments"][1]["positions"][5:8])
    np.testing.assert_array_equal(part["body"]["positions"], whole["body"]["positions"][5:8])


def test_error_and_h_collision_equal_metrics_json(fixture, evaluated):
    with open(os.path.join(evaluated, "metrics.json")) as f:
        metrics = json.load(f)
    truth = layers.open_dataset(fixture["dataset"])
    predicted = layers.open_dataset(os.path.join(evaluated, "predictions.h5"))
    assert metrics["per_sequence"], "the evaluation measured no sequence"
    for entry in metrics["per_sequence"]:
        p, t = predicted.read_sequence(entry["id"]), truth.read_sequence(entry["id"])
        errors, h = [], []
        for frame in range(2, p["n_frames"]):
            pred = np.concatenate([g["positions"][frame] for g in p["garments"]])
            true = np.concatenate([g["positions"][frame] for g in t["garments"]])
            errors.append(layers.error_mm(pred, true))
            h.append(layers.h_collision(pred, t["body"]["positions"][frame], t["body"]["faces"]))
        assert abs(np.mean(errors) - entry["error_mm"]) <= 1e-6 * max(1.0, entry["error_mm"]), entry["id"]
        assert abs(np.mean(h) - entry["h_collision"]) <= 1e-6, entry["id"]


def tensor_hash(t):
    return fnv1a64(t.contiguous().numpy())


def test_windows_are_the_cpp_loaders(fixture):
    ref = fixture["loader"]
    ds = layers.WindowDataset(fixture["dataset"], split=ref["split"], history=ref["history"], horizon=ref["horizon"],
                              seed=ref["seed"], epoch=ref["epoch"])
    assert len(ds) == ref["count"]
    for item, expected in ((ds[0], ref["first"]), (ds[len(ds) - 1], ref["last"])):
        assert (item["id"], item["start"]) == (expected["id"], expected["start"])
        assert tensor_hash(item["body"]) == expected["body"]
        assert [tensor_hash(g) for g in item["garments"]] == expected["garments"]
    assert ds.stats["split"] == "train" and ds.stats["garment/position"]["std"].shape == (3,)
    inner = layers.WindowDataset(fixture["dataset"], horizon=3, seed=7, inner_only=True)
    assert len(inner[0]["garments"]) == 1


def test_dataloader_workers_give_the_batches_of_one_process(fixture):
    import torch

    def batches(workers):
        ds = layers.WindowDataset(fixture["dataset"], horizon=3, seed=7)
        loader = torch.utils.data.DataLoader(ds, batch_size=2, shuffle=True, num_workers=workers,
                                             generator=torch.Generator().manual_seed(11),
                                             collate_fn=layers.collate_windows)
        return [[(s["id"], s["start"], tensor_hash(s["garments"][0])) for s in b] for b in loader]

    one = batches(0)
    assert len(one) > 1
    assert batches(2) == one


def test_the_zoo_lists_the_reference_models():
    assert {"static", "skinned"} <= set(layers.models()), layers.plugin_problems()


def test_a_rollout_from_python_equals_layers_rollout(fixture, evaluated, tmp_path):
    experiment = os.path.join(fixture["folder"], "static.yaml")
    subprocess.run([os.environ["LAYERS_BIN"], "rollout", experiment, "--sequence", "seq4", "--out",
                    str(tmp_path / "cli")], check=True, capture_output=True, text=True)
    result = layers.rollout(experiment, "seq4", str(tmp_path / "py"))
    assert result["model"] == "static" and result["frames"] > 0
    cli = layers.open_dataset(str(tmp_path / "cli" / "predictions.h5")).read_sequence("seq4")
    py = layers.open_dataset(result["predictions"]).read_sequence("seq4")
    assert len(result["garments"]) == len(cli["garments"]) == 2
    for k, g in enumerate(cli["garments"]):
        assert g["positions"].tobytes() == py["garments"][k]["positions"].tobytes()
        assert g["positions"].tobytes() == result["garments"][k].numpy().tobytes()
    assert cli["body"]["positions"].tobytes() == py["body"]["positions"].tobytes()


def test_a_wrong_checkpoint_raises_the_cpp_message(fixture, evaluated, tmp_path):
    experiment = os.path.join(fixture["folder"], "static.yaml")
    junk = tmp_path / "junk.pt"
    junk.write_bytes(b"not a checkpoint")
    with pytest.raises(layers.Error) as e:
        layers.rollout(experiment, "seq4", str(tmp_path / "out"), checkpoint=str(junk))
    assert str(junk) in str(e.value)


def test_measures_of_two_layers(fixture):
    seq = layers.open_dataset(fixture["dataset"]).read_sequence("seq1")
    inner, outer, body = seq["garments"][0], seq["garments"][1], seq["body"]
    rates = layers.l_collision(outer["positions"][3], inner["positions"][3], inner["faces"])
    assert set(rates) == {"ours", "plain"} and 0 <= rates["ours"] <= rates["plain"] <= 1
    assert layers.error_mm(inner["positions"][3], inner["positions"][3]) == 0.0
    h = layers.h_crossing([(inner["positions"][3], inner["faces"])], body["positions"][3], body["faces"])
    lx = layers.l_crossing([(outer["positions"][3], outer["faces"])], [(inner["positions"][3], inner["faces"])])
    assert 0 <= h <= 1 and 0 <= lx <= 1
    assert layers.stretch(inner["rest"], inner["rest"], inner["faces"]) < 1e-6  # float32 rounding
    longer = inner["rest"] * np.float32(1.1)  # every edge 10% longer
    assert abs(layers.stretch(longer, inner["rest"], inner["faces"]) - 0.1) < 1e-5
    with pytest.raises(layers.InputError, match="vertices as the rest shape"):
        layers.stretch(inner["rest"][:5], inner["rest"], inner["faces"])


def test_wrong_input_is_the_cpp_line(fixture, tmp_path):
    with pytest.raises(layers.InputError) as e:
        layers.open_dataset(str(tmp_path / "none"))
    assert str(tmp_path / "none") in str(e.value) and e.value.file
    with pytest.raises(layers.InputError, match=r"\[V,3\]"):
        layers.error_mm(np.zeros((4, 2), np.float32), np.zeros((4, 2), np.float32))
    # Issue 63: arrays of different vertex counts are a bad input too.
    with pytest.raises(layers.InputError, match="predicted: shape: expected 5 vertices as truth, got 4"):
        layers.error_mm(np.zeros((4, 3), np.float32), np.zeros((5, 3), np.float32))


def test_a_damaged_shard_raises_the_cpp_message(fixture, tmp_path):
    copy = tmp_path / "damaged"
    shutil.copytree(fixture["dataset"], copy)
    shard = next(p for p in copy.iterdir() if p.suffix == ".h5" and p.name != "stats.h5")
    data = bytearray(shard.read_bytes())
    seq = layers.open_dataset(fixture["dataset"]).read_sequence("seq2")
    needle = np.ascontiguousarray(seq["garments"][0]["positions"][10]).tobytes()[:64]
    at = data.find(needle)
    at = at + 8 if at > 0 else len(data) * 3 // 5  # stored compressed: somewhere in the data
    data[at] ^= 0xFF
    shard.write_bytes(bytes(data))
    with pytest.raises(layers.Error) as e:
        damaged = layers.open_dataset(str(copy))
        for seq_id in damaged.ids():
            damaged.read_sequence(seq_id)
    assert shard.name in str(e.value) or "seq" in str(e.value), str(e.value)


def test_read_stats_checks_the_recorded_hash(fixture, tmp_path):
    """Issue 62 S4: read_stats returned an edited stats.h5 as it was."""
    copy = tmp_path / "stats-edited"
    shutil.copytree(fixture["dataset"], copy)
    assert layers.read_stats(str(copy / "stats.h5"))["split"] == "train"
    manifest = (copy / "dataset.yaml").read_text()
    recorded = next(line.split(":")[1].strip() for line in manifest.splitlines() if line.startswith("stats_hash:"))
    (copy / "dataset.yaml").write_text(manifest.replace(recorded, "0123456789abcdef"))
    with pytest.raises(layers.InputError) as e:
        layers.read_stats(str(copy / "stats.h5"))
    assert "stats_hash" in str(e.value), str(e.value)


@pytest.mark.parametrize("kwargs, field", [
    ({"rank": 5, "world": 2}, "rank"),
    ({"world": 0}, "world"),
    ({"history": -1}, "history"),
    ({"horizon": -1}, "horizon"),
    ({"stride": 0}, "stride"),
])
def test_window_arguments_the_cli_would_refuse_raise(fixture, kwargs, field):
    """Issue 62 S5: these were accepted."""
    with pytest.raises(layers.InputError) as e:
        layers.WindowDataset(fixture["dataset"], **kwargs)
    assert "layers.WindowDataset: " + field + ": expected" in str(e.value), str(e.value)


def test_a_rollout_horizon_below_minus_one_raises(fixture, evaluated, tmp_path):
    """Issue 62 S5: horizon=-7 ran 27 frames."""
    with pytest.raises(layers.InputError) as e:
        layers.rollout(os.path.join(fixture["folder"], "static.yaml"), fixture["ids"][0], str(tmp_path / "r"),
                       horizon=-7)
    assert "layers.rollout: horizon: expected" in str(e.value) and "got -7" in str(e.value), str(e.value)
    assert not (tmp_path / "r").exists()


def test_measures_refuse_indices_they_would_wrap_float_faces_and_nan(fixture):
    """Issue 62 S6: an index of 2^32 + 2 was read as 2, float faces were
    truncated, and an all-NaN garment measured 0.0."""
    seq = layers.open_dataset(fixture["dataset"]).read_sequence("seq1")
    garment, body = seq["garments"][0]["positions"][3], seq["body"]
    faces = np.array(body["faces"], dtype=np.int64)
    faces[0, 2] = 2**32 + 2
    with pytest.raises(layers.InputError, match="body: faces: expected vertex indices from 0 to 2"):
        layers.h_collision(garment, body["positions"][3], faces)
    with pytest.raises(layers.InputError, match="expected integer vertex indices, got an array of dtype float64"):
        layers.h_collision(garment, body["positions"][3], body["faces"].astype(np.float64))
    with pytest.raises(layers.InputError, match="garment: positions: expected finite coordinates"):
        layers.h_collision(np.full_like(garment, np.nan), body["positions"][3], body["faces"])
    assert 0 <= layers.h_collision(garment, body["positions"][3], body["faces"].astype(np.uint32)) <= 1
