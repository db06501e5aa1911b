"""Byte-identity of the result documents across a change (issue 27): run the commands in one
checkout, again in another, compare the files.

    .venv/bin/python bench/documents.py dump  /tmp/docs-before   # in the old checkout
    .venv/bin/python bench/documents.py dump  /tmp/docs-after    # in the new one
    .venv/bin/python bench/documents.py check /tmp/docs-before /tmp/docs-after

or, from the new checkout, against a git revision (checked out into a temporary worktree and
run with this checkout's interpreter, the revision's package first on the path):

    .venv/bin/python bench/documents.py compare --base HEAD~3

Per case (seed, iso_pair, drivetrain; each with a short end time, :data:`CASES`) the command
line writes: timeseries.csv and summary.json (`gearcli simulate -o`), analysis.json
(`gearcli analyze`), stress.json (`gearcli stress`), the modal JSON (`gearcli modal --json`)
and the mesh JSON (`gearcli mesh --json`). They are compared byte for byte, after dropping
only the volatile entries of :data:`VOLATILE` (timings of this machine; no document holds a
date, a version or a git hash: those are in manifest.json, which is not compared). The
modal and mesh JSON are compared as printed. The results schema (`gearcli schema --results --kind
KIND`) is compared by its property names only (descriptions and order may change).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: case -> overrides: the end times keep the three runs short (a few seconds each) while the
#: steady window, the spectra and the stress maxima are still computed.
CASES = {
    "seed": ("cases/seed.yaml", ["run.end_time=0.5"]),
    "iso_pair": ("cases/iso_pair.yaml", ["run.end_time=0.15"]),
    "drivetrain": ("cases/drivetrain.yaml", ["run.end_time=0.3"]),
}
#: (file, dotted key) left out of the comparison: the solver's wall time on this machine and
#: whether it included compiling the solver (depends on the numba cache, not the results).
VOLATILE = (("summary.json", "solver.wall_time_s"),
            ("summary.json", "solver.wall_time_includes_compilation"))
DOCUMENTS = ("timeseries.csv", "summary.json", "analysis.json", "stress.json", "modal.json",
             "mesh.json",
             # not in the list, compared as well: the other files of the same commands
             "zoom.csv", "spectrum.csv", "harmonics.csv", "stress.csv")
SCHEMA_KINDS = ("summary", "analysis", "stress", "modal", "mesh")


def _gearcli(args: list[str], env: dict, stdout=None) -> None:
    cmd = [sys.executable, "-m", "gearcli", *args]
    proc = subprocess.run(cmd, env=env, stdout=stdout or subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True)
    if proc.returncode not in (0, 4):  # 4: a check failed, the documents are written
        raise SystemExit(f"{' '.join(args)}: exit {proc.returncode}\n{proc.stderr}")


def dump(out: str, source: Path = ROOT) -> None:
    """Run the commands for every case with the package in ``source``; files into ``out``."""
    env = dict(os.environ, PYTHONPATH=str(source), NO_COLOR="1", COLUMNS="100")
    out_p = Path(out)
    out_p.mkdir(parents=True, exist_ok=True)
    for name, (case, overrides) in CASES.items():
        sets = [a for o in overrides for a in ("--set", o)]
        run = out_p / name
        case_path = str(source / case)
        _gearcli(["simulate", case_path, "-o", str(run), "--force", "--quiet", *sets], env)
        _gearcli(["analyze", str(run)], env)
        _gearcli(["stress", str(run)], env)
        for cmd in ("modal", "mesh"):
            with open(run / f"{cmd}.json", "w", encoding="utf-8") as fh:
                _gearcli([cmd, case_path, "--json", *sets], env, stdout=fh)
        print(f"{name}: {', '.join(f for f in DOCUMENTS if (run / f).is_file())}", flush=True)
    schema = {}
    for kind in SCHEMA_KINDS:
        with tempfile.TemporaryFile("w+", encoding="utf-8") as fh:
            _gearcli(["schema", "--results", "--kind", kind], env, stdout=fh)
            fh.seek(0)
            schema[kind] = _property_names(json.load(fh))
    (out_p / "schema_properties.json").write_text(json.dumps(schema, indent=1, sort_keys=True))


def _property_names(schema, prefix: str = "") -> list[str]:
    """Every property path of a JSON Schema (nested objects and array items), sorted."""
    out = []
    if isinstance(schema, dict):
        for key, sub in (schema.get("properties") or {}).items():
            out.append(prefix + key)
            out.extend(_property_names(sub, f"{prefix}{key}."))
        if isinstance(schema.get("items"), dict):
            out.extend(_property_names(schema["items"], f"{prefix}[]."))
    return sorted(out)


def _drop_volatile(name: str, text: str) -> str:
    keys = [k for f, k in VOLATILE if f == name]
    if not keys:
        return text
    doc = json.loads(text)
    for key in keys:
        *parents, last = key.split(".")
        node = doc
        for p in parents:
            node = node.get(p, {})
        node.pop(last, None)
    return json.dumps(doc, indent=2)


def check(before: str, after: str) -> int:
    bad = 0
    for name in CASES:
        for doc in DOCUMENTS:
            a, b = Path(before, name, doc), Path(after, name, doc)
            if not a.is_file() or not b.is_file():
                print(f"{name}/{doc}: missing in {'before' if not a.is_file() else 'after'}")
                bad += 1
                continue
            same = _drop_volatile(doc, a.read_text()) == _drop_volatile(doc, b.read_text())
            print(f"{name + '/' + doc:<28} {a.stat().st_size:>10} B  "
                  f"{'identical' if same else 'DIFFERENT'}")
            bad += not same
    a, b = (json.loads(Path(p, "schema_properties.json").read_text()) for p in (before, after))
    for kind in SCHEMA_KINDS:
        gone, new = sorted(set(a[kind]) - set(b[kind])), sorted(set(b[kind]) - set(a[kind]))
        print(f"schema --results {kind:<9} {'same properties' if not gone and not new else ''}"
              + (f" removed {gone}" if gone else "") + (f" added {new}" if new else ""))
        bad += bool(gone)  # added properties are reported; removed ones fail
    print("all identical" if not bad else f"{bad} differ")
    return 1 if bad else 0


def compare(base: str) -> int:
    with tempfile.TemporaryDirectory(prefix="gearcli-docs-") as tmp:
        tree = Path(tmp, "base")
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(tree), base],
                       check=True, capture_output=True)
        try:
            print(f"base {base}:")
            dump(str(Path(tmp, "before")), tree)
            print("this checkout:")
            dump(str(Path(tmp, "after")))
            return check(str(Path(tmp, "before")), str(Path(tmp, "after")))
        finally:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(tree)],
                           check=False, capture_output=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    for name, positional in (("dump", ("path",)), ("check", ("before", "after"))):
        command = sub.add_parser(name)
        for arg in positional:
            command.add_argument(arg)
    sub.add_parser("compare").add_argument("--base", default="HEAD")
    args = ap.parse_args()
    if args.cmd == "dump":
        dump(args.path)
    elif args.cmd == "check":
        sys.exit(check(args.before, args.after))
    else:
        sys.exit(compare(args.base))


if __name__ == "__main__":
    main()
