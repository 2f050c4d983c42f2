#!/usr/bin/env python3
"""Runs the code blocks of docs/python.md as a reader would, from an
installed prefix (ctest `docs_python_blocks`).

The prefix is installed from the build into a scratch folder, and a
folder laid out as the README's quickstart leaves it is made with the
installed binary: runs/quickstart/data (configs/data/tiny.yaml, cut to
three short, coarse scenes) and runs/quickstart/layersnet (layersnet_tiny
with its checkpoints, trained for no epoch: the examples need a model,
not a good one). In that folder, every ```bash block runs with bash -e
(build/python is the installed package, as in a clone) and the ```python
blocks run in order in one interpreter, as a reader pastes them. A block
that fails is named by its line in the doc; exit 1.
"""
import os
import re
import shutil
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


def main():
    source, build, cmake = sys.argv[1:4]
    doc = os.path.join(source, "docs", "python.md")
    scratch = tempfile.mkdtemp(prefix="layers-doc-blocks-")
    try:
        prefix = os.path.join(scratch, "prefix")
        env = {k: v for k, v in os.environ.items() if k not in ("LAYERS_PLUGIN_PATH", "LAYERS_ASSETS", "PYTHONPATH")}
        run([cmake, "--install", build, "--prefix", prefix], scratch, env)
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
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    main()
