#!/usr/bin/env python3
"""Runs the code blocks of a doc as a reader would, from an installed
prefix (ctest `docs_python_blocks`, `docs_own_data_blocks`):

    run_doc_blocks.py <source> <build> <cmake> python.md|own-data.md

The prefix is installed from the build into a scratch folder; a block
that fails is named by its line in the doc; exit 1.

docs/python.md: a folder laid out as the README's quickstart leaves it is
made with the installed binary: runs/quickstart/data (configs/data/tiny.yaml,
cut to three short, coarse scenes) and runs/quickstart/layersnet
(layersnet_tiny with its checkpoints, trained for no epoch: the examples
need a model, not a good one). In that folder, every ```bash block runs
with bash -e (build/python is the installed package, as in a clone) and
the ```python blocks run in order in one interpreter, as a reader pastes
them.

docs/own-data.md: in an empty folder (not a clone: the shipped configs are
the installed ones), the blocks in order, with the installed `layers`
first on PATH through a wrapper that makes scenes short (`frames=16`) and
datasets small (6 sequences) and trains one epoch, so that the doc's
commands run in minutes; the wrapper changes sizes only, never a rule of
the simulator. What a reader does by hand is done in between: Blender's
part (section 2) is played by copying the T-pose garments to
mine/my_dress.obj and mine/my_jacket.obj and writing the jacket as a GLB
(mine/my_jacket.glb), and the rigged body of section 6 is the body.glb
that `layers tpose` wrote, its animation named Walk (mine/character.glb),
with `garment_pose: first_frame` as the doc says for that file.
Each ```yaml block goes where its section says (the side file
mine/my_dress.yaml, or the sections of my_scene.yaml it replaces); a yaml
block the runner does not know is a failure, as is a missing file that a
block's comments promise.
"""
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import traceback


def blocks(path):
    """(language, first line number, text) of each fenced block."""
    out, lang, start, lines = [], None, 0, []
    with open(path) as f:
        for number, line in enumerate(f, 1):
            fence = re.match(r"^```(\w*)\s*$", line)
            if fence and lang is None:
                lang, start, lines = fence.group(1) or "text", number + 1, []
            elif line.startswith("```") and lang is not None:
                out.append((lang, start, "".join(lines)))
                lang = None
            elif lang is not None:
                lines.append(line)
    return out


def run(command, cwd, env):
    r = subprocess.run(command, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        sys.exit("setup failed: %s\n%s" % (" ".join(command), r.stdout[-3000:]))


def install(build, cmake, scratch, env):
    prefix = os.path.join(scratch, "prefix")
    run([cmake, "--install", build, "--prefix", prefix], scratch, env)
    return prefix


def python_md(source, prefix, scratch, env):
    doc = os.path.join(source, "docs", "python.md")
    layers = os.path.join(prefix, "bin", "layers")
    package = os.path.join(prefix, "lib", "python3", "dist-packages")
    work = os.path.join(scratch, "work")
    os.makedirs(os.path.join(work, "build"))
    os.symlink(package, os.path.join(work, "build", "python"))
    configs = os.path.join(prefix, "share", "layers", "configs")
    run([layers, "generate", "--config", os.path.join(configs, "data", "tiny.yaml"), "--quiet",
         "--set", "sequences=3", "--set", "frames=16", "--set", "drape_frames=2",
         "--set", "body.transition_frames=2", "--set", "garments.fit.edge_length=0.1",
         "--set", "splits={val: 0.34, test: 0.0}",
         "--set", "sim.validation.max_l_penetration=1", "--set", "sim.validation.max_h_penetration=1",
         "--set", "sim.validation.max_stretch=100", "--set", "sim.validation.max_h_crossing_clear=1",
         "--out", "runs/quickstart/data"], work, env)
    run([layers, "train", os.path.join(configs, "experiments", "layersnet_tiny.yaml"), "--quiet",
         "--set", "data.dataset=runs/quickstart/data", "--set", "run.output=runs/quickstart/layersnet",
         "--set", "train.epochs=0"], work, env)
    failed = []
    python = []
    for lang, line, text in blocks(doc):
        if lang == "bash":
            r = subprocess.run(["bash", "-e", "-c", text], cwd=work, env=env, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True)
            print("docs/python.md:%d (bash): exit %d\n%s" % (line, r.returncode, r.stdout[-2000:]))
            if r.returncode != 0:
                failed.append(line)
        elif lang == "python":
            python.append((line, text))
    script = ["import os, sys, traceback", "ns = {}", "failed = []"]
    for line, text in python:
        script.append("try:\n    exec(compile(%r, 'docs/python.md:%d', 'exec'), ns)\n"
                      "    print('docs/python.md:%d (python): ran')\n"
                      "except BaseException:\n    traceback.print_exc()\n    failed.append(%d)" %
                      (text, line, line, line))
    script.append("sys.exit(1 if failed else 0)")
    penv = dict(env, PYTHONPATH=package)
    r = subprocess.run(["/usr/bin/python3", "-c", "\n".join(script)], cwd=work, env=penv,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(r.stdout[-6000:])
    if r.returncode != 0:
        failed.append("python blocks")
    if not python or not any(lang == "bash" for lang, _, _ in blocks(doc)):
        sys.exit("docs/python.md: expected bash and python blocks, found none")
    if failed:
        sys.exit("docs/python.md: blocks failed at %s" % failed)
    print("docs/python.md: %d bash and %d python blocks ran" %
          (sum(1 for b in blocks(doc) if b[0] == "bash"), len(python)))


def write_glb(obj_path, glb_path):
    """The mesh of an OBJ (positions and triangles) as a minimal glTF 2.0
    binary, as a modelling tool would export it."""
    points, faces = [], []
    with open(obj_path) as f:
        for line in f:
            part = line.split()
            if not part:
                continue
            if part[0] == "v":
                points.append([float(x) for x in part[1:4]])
            elif part[0] == "f":
                corner = [int(p.split("/")[0]) - 1 for p in part[1:]]
                for k in range(1, len(corner) - 1):
                    faces.append([corner[0], corner[k], corner[k + 1]])
    positions = b"".join(struct.pack("<3f", *p) for p in points)
    indices = b"".join(struct.pack("<3I", *t) for t in faces)
    blob = positions + indices
    lo = [min(p[i] for p in points) for i in range(3)]
    hi = [max(p[i] for p in points) for i in range(3)]
    gltf = {
        "asset": {"version": "2.0", "generator": "run_doc_blocks.py"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "name": "my_jacket"}],
        "meshes": [{"name": "my_jacket", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(blob)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(positions), "target": 34962},
                        {"buffer": 0, "byteOffset": len(positions), "byteLength": len(indices), "target": 34963}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(points), "type": "VEC3",
                       "min": lo, "max": hi},
                      {"bufferView": 1, "componentType": 5125, "count": 3 * len(faces), "type": "SCALAR"}],
    }
    write_glb_chunks(glb_path, gltf, blob)


def write_glb_chunks(path, gltf, blob):
    text = json.dumps(gltf).encode()
    text += b" " * (-len(text) % 4)
    blob += b"\0" * (-len(blob) % 4)
    size = 12 + 8 + len(text) + 8 + len(blob)
    with open(path, "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, size))
        f.write(struct.pack("<I4s", len(text), b"JSON") + text)
        f.write(struct.pack("<I4s", len(blob), b"BIN\0") + blob)


def rename_animation(src, dst, name):
    """A copy of a GLB whose first animation is called `name`."""
    with open(src, "rb") as f:
        data = f.read()
    length = struct.unpack("<I", data[12:16])[0]
    gltf = json.loads(data[20:20 + length])
    gltf["animations"][0]["name"] = name
    rest = data[20 + length:]
    blob_length = struct.unpack("<I", rest[:4])[0]
    write_glb_chunks(dst, gltf, rest[8:8 + blob_length])


def replace_sections(config, block):
    """my_scene.yaml with the top-level sections that `block` names
    replaced by the block (the other sections kept)."""
    keys = set(re.findall(r"^(\w+):", block, re.M))
    kept, skipping = [], False
    with open(config) as f:
        for line in f:
            top = re.match(r"^(\w+):", line)
            if top:
                skipping = top.group(1) in keys
            if not skipping:
                kept.append(line)
    with open(config, "w") as f:
        f.write("".join(kept) + block)


WRAPPER = """#!/bin/bash
# Short scenes and small datasets for the doc's commands (run_doc_blocks.py).
real=%s
case "$1" in
  generate) exec "$real" "$@" --set frames=16 --set sequences=6 ;;
  animate) exec "$real" "$@" --set frames=16 ;;
  train) exec "$real" "$@" --set train.epochs=1 ;;
  *) exec "$real" "$@" ;;
esac
"""

# Files the comments of a block promise, by the block's first line.
PROMISED = {
    "cat > my_scene.yaml": ["mine/body.obj", "mine/dress.obj", "mine/jacket.obj", "mine/body.glb"],
    "layers animate": ["anim/glb/seq-000000.glb", "anim/data/dataset.yaml"],
    "cat > my_body.yaml": ["mine/rest/body.obj"],
    "layers generate": ["report_mine/report.md", "report_mine/viewer/index.html"],
}


def own_data_md(source, prefix, scratch, env):
    doc = os.path.join(source, "docs", "own-data.md")
    work = os.path.join(scratch, "work")
    shim = os.path.join(scratch, "shim")
    os.makedirs(work)
    os.makedirs(shim)
    with open(os.path.join(shim, "layers"), "w") as f:
        f.write(WRAPPER % os.path.join(prefix, "bin", "layers"))
    os.chmod(os.path.join(shim, "layers"), 0o755)
    env = dict(env, PATH=shim + os.pathsep + env.get("PATH", ""))
    failed = []
    ran = 0
    mine = os.path.join(work, "mine")
    for lang, line, text in blocks(doc):
        where = "docs/own-data.md:%d (%s)" % (line, lang)
        if lang == "bash":
            r = subprocess.run(["bash", "-e", "-c", text], cwd=work, env=env, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True)
            print("%s: exit %d\n%s" % (where, r.returncode, r.stdout[-2500:]))
            first = text.lstrip().splitlines()[0]
            missing = [p for key, files in PROMISED.items() if first.startswith(key) for p in files
                       if not os.path.exists(os.path.join(work, p))]
            if first.startswith("layers animate") and not any(
                    n.endswith(".obj") for n in os.listdir(os.path.join(work, "anim", "obj"))
                    if os.path.isdir(os.path.join(work, "anim", "obj"))):
                missing.append("anim/obj/*.obj")
            if r.returncode != 0 or missing:
                failed.append(line)
                if missing:
                    print("%s: missing %s" % (where, missing))
            if first.startswith("cat > my_scene.yaml") and r.returncode == 0:
                # Section 2 by hand: the garments made from the T-pose ones.
                shutil.copy(os.path.join(mine, "dress.obj"), os.path.join(mine, "my_dress.obj"))
                shutil.copy(os.path.join(mine, "jacket.obj"), os.path.join(mine, "my_jacket.obj"))
                write_glb(os.path.join(mine, "jacket.obj"), os.path.join(mine, "my_jacket.glb"))
                rename_animation(os.path.join(mine, "body.glb"), os.path.join(mine, "character.glb"), "Walk")
            ran += 1
        elif lang == "yaml":
            if text.startswith("name: my_dress"):
                target = os.path.join(mine, "my_dress.yaml")
                with open(target, "w") as f:
                    f.write(text)
                print("%s: written as mine/my_dress.yaml" % where)
            elif re.match(r"^(garments|body):", text):
                if "garment_pose: bind" in text:
                    # The stand-in rig is our body.glb, whose bind pose is not
                    # the T-pose the garments were made around: the doc's
                    # "Our body as a rig" names first_frame for it.
                    text = text.replace("garment_pose: bind", "garment_pose: first_frame")
                    print("%s: garment_pose: first_frame for the stand-in body.glb" % where)
                replace_sections(os.path.join(work, "my_scene.yaml"), text)
                r = subprocess.run(["layers", "tpose", "--config", "my_scene.yaml", "--out", "tpose-%d" % line],
                                   cwd=work, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
                print("%s: in my_scene.yaml, `layers tpose` exit %d\n%s" % (where, r.returncode, r.stdout[-1500:]))
                if r.returncode != 0:
                    failed.append(line)
            else:
                print("%s: a yaml block the runner does not know where to put" % where)
                failed.append(line)
            ran += 1
    if ran < 6:
        sys.exit("docs/own-data.md: expected the doc's bash and yaml blocks, found %d" % ran)
    if failed:
        sys.exit("docs/own-data.md: blocks failed at %s" % failed)
    print("docs/own-data.md: %d blocks ran" % ran)


def main():
    source, build, cmake, doc = sys.argv[1:5]
    scratch = tempfile.mkdtemp(prefix="layers-doc-blocks-")
    try:
        env = {k: v for k, v in os.environ.items() if k not in ("LAYERS_PLUGIN_PATH", "LAYERS_ASSETS", "PYTHONPATH")}
        prefix = install(build, cmake, scratch, env)
        if doc == "python.md":
            python_md(source, prefix, scratch, env)
        elif doc == "own-data.md":
            own_data_md(source, prefix, scratch, env)
        else:
            sys.exit("run_doc_blocks.py: expected python.md or own-data.md, got %s" % doc)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    main()
