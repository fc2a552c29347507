# Copyright (c) 2026 The Surface_mesh_correspondence developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Matching a collection of pairs listed in a CSV file.

    python3 -m comap.batch PAIRS.csv --out DIR [--settings FILE.json] [--threads N] [--index-base 0|1]

PAIRS.csv has a header and one row per pair. Columns (paths relative to the CSV file's folder):

- ``source``, ``target`` (required): the two meshes (OFF, OBJ, PLY or STL);
- ``init_12``, ``init_21`` (optional, both or neither): initial maps;
- ``gt_source``, ``gt_target`` (optional, both or neither): ground-truth correspondences (.vts:
  sample k of ``gt_source`` on the source corresponds to sample k of ``gt_target`` on the target);
- ``name`` (optional): the pair's name in the outputs (default ``SOURCE-TARGET`` from the file
  names).

Map and correspondence files have one vertex index per line, ``--index-base``-based (1 by default,
as comap's). Outputs, each written atomically (a killed run loses nothing finished):

- ``DIR/maps/NAME_12.map`` and ``DIR/maps/NAME_21.map``: the maps of each pair that succeeded;
- ``DIR/results.csv``: one row per pair, rewritten as each pair ends: ``status`` (``ok`` or
  ``failed``), ``error`` (the message of a failed pair), times, accuracy (with ground truth) and
  consistency figures (see RESULT_COLUMNS).

Exit status: 0 when every pair is ``ok``; 1 when some pair failed (its row says why; the others
are done); 2 for a bad command line or pairs file (nothing is matched).
"""

import argparse
import collections
import csv
import json
import os
import re
import sys
import tempfile
import time

import comap

#: The columns of results.csv, in order.
RESULT_COLUMNS = [
    "name", "source", "target", "status", "error",
    "seconds",                      # wall time of the pair, reading and preparing its shapes included
    "match_seconds",                # comap.match_shapes alone
    "vertices_source", "vertices_target",
    "mean_error_12", "mean_error_21",        # geodesic error / sqrt(area), with ground truth
    "within_0.025_12", "within_0.025_21",    # fraction of samples with error <= 0.025
    "inconsistent_vertices",                 # x with T21(T12(x)) != x, both directions
    "cycle_error_1", "cycle_error_2",        # mean normalised geodesic cycle error on each mesh
    "coverage_12", "coverage_21",            # fraction of the target's vertices reached
    "map_12", "map_21",                      # the output map files, relative to DIR
]

INPUT_COLUMNS = ["name", "source", "target", "init_12", "init_21", "gt_source", "gt_target"]


class PairsFileError(ValueError):
    """A pairs file that cannot be used (missing columns, empty, unknown columns)."""


def read_pairs(pairs_file):
    """The rows of a pairs file as dicts with the columns of INPUT_COLUMNS (paths made absolute,
    relative to the file's folder; missing optional columns empty) and a unique ``name``.
    Raises PairsFileError naming the file, the line and the problem, OSError for a missing file."""
    folder = os.path.dirname(os.path.abspath(pairs_file))
    with open(pairs_file, newline="") as f:
        reader = csv.DictReader(f)
        if reader.fieldnames is None:
            raise PairsFileError(f"{pairs_file}: the file is empty (expected a header: source,target,...)")
        columns = [c.strip() for c in reader.fieldnames]
        unknown = [c for c in columns if c not in INPUT_COLUMNS]
        if unknown:
            raise PairsFileError(f"{pairs_file}:1: unknown column {unknown[0]!r} (the columns are "
                                 + ", ".join(INPUT_COLUMNS) + ")")
        for c in ("source", "target"):
            if c not in columns:
                raise PairsFileError(f"{pairs_file}:1: the header has no {c!r} column")
        pairs, names = [], collections.Counter()
        for row in reader:
            line = reader.line_num
            row = {k.strip(): (v or "").strip() for k, v in row.items() if k is not None}
            if not any(row.values()):
                continue
            p = {c: row.get(c, "") for c in INPUT_COLUMNS}
            for c in ("source", "target"):
                if not p[c]:
                    raise PairsFileError(f"{pairs_file}:{line}: no {c}")
            for a, b in (("init_12", "init_21"), ("gt_source", "gt_target")):
                if bool(p[a]) != bool(p[b]):
                    raise PairsFileError(f"{pairs_file}:{line}: give both {a} and {b}, or neither")
            for c in ("source", "target", "init_12", "init_21", "gt_source", "gt_target"):
                if p[c]:
                    p[c] = os.path.normpath(os.path.join(folder, p[c]))
            if not p["name"]:
                stem = lambda path: os.path.splitext(os.path.basename(path))[0]
                p["name"] = f"{stem(p['source'])}-{stem(p['target'])}"
            p["name"] = re.sub(r"[^A-Za-z0-9._+-]", "_", p["name"])
            names[p["name"]] += 1
            if names[p["name"]] > 1:
                p["name"] += f"_{names[p['name']]}"
            p["line"] = line
            pairs.append(p)
    if not pairs:
        raise PairsFileError(f"{pairs_file}: no pair (only a header)")
    return pairs


def read_settings(file):
    """A settings file as comap reads it: a JSON object, with // comments; null keeps a
    setting's default."""
    with open(file) as f:
        text = f.read()
    # Remove // comments outside strings.
    text = re.sub(r'("(?:\\.|[^"\\])*")|//[^\n]*', lambda m: m.group(1) or "", text)
    try:
        given = json.loads(text)
    except json.JSONDecodeError as e:
        raise ValueError(f"{file}:{e.lineno}: {e.msg}") from None
    if not isinstance(given, dict):
        raise ValueError(f"{file}: a settings file holds one JSON object")
    return {k: v for k, v in given.items() if v is not None}


def _write_atomically(path, write):
    folder = os.path.dirname(os.path.abspath(path))
    fd, temporary = tempfile.mkstemp(dir=folder, prefix="." + os.path.basename(path) + ".tmp-")
    try:
        with os.fdopen(fd, "w", newline="") as f:
            write(f)
        os.replace(temporary, path)
    except BaseException:
        if os.path.exists(temporary):
            os.remove(temporary)
        raise


def write_results(path, rows):
    """Writes the results table atomically."""
    def write(f):
        w = csv.DictWriter(f, fieldnames=RESULT_COLUMNS, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: _cell(r.get(k, "")) for k in RESULT_COLUMNS})
    _write_atomically(path, write)


def _cell(v):
    if isinstance(v, float):
        return f"{v:.6g}"
    return v


class _Shapes:
    """Prepared shapes by file, the most recently used few kept (pairs that share a mesh prepare
    it once)."""

    def __init__(self, settings, threads, keep=4):
        self.settings, self.threads, self.keep = settings, threads, keep
        self.cache = collections.OrderedDict()

    def get(self, path):
        if path in self.cache:
            self.cache.move_to_end(path)
            return self.cache[path]
        V, F = comap.read_mesh(path)
        shape = comap.Shape(V, F, name=path, settings=self.settings, threads=self.threads)
        self.cache[path] = shape
        while len(self.cache) > self.keep:
            self.cache.popitem(last=False)
        return shape


def _split_settings(settings):
    registry = comap.settings()
    comap.check_settings(settings)  # unknown names, types and ranges
    preparation = {k: v for k, v in settings.items() if registry[k]["stage"] == "preparation"}
    # The shapes take the preparation settings and those of the initialisation their data depend
    # on; match_shapes takes all but the preparation ones.
    shape = {k: v for k, v in settings.items() if registry[k]["stage"] in ("preparation", "initialization")}
    run = {k: v for k, v in settings.items() if k not in preparation}
    return shape, run


def match_pair(pair, shapes, out_dir, run_settings=None, threads=None, index_base=1):
    """Matches one pair of a pairs file (a dict of read_pairs()) and writes its maps under
    ``out_dir/maps``. Returns its row of the results table; a failure is a row with status
    ``failed`` and the error's message, never an exception (except KeyboardInterrupt)."""
    start = time.perf_counter()
    row = {"name": pair["name"], "source": pair["source"], "target": pair["target"], "status": "failed"}
    try:
        s1 = shapes.get(pair["source"])
        s2 = shapes.get(pair["target"])
        row["vertices_source"], row["vertices_target"] = s1.number_of_vertices, s2.number_of_vertices
        init = None
        if pair["init_12"]:
            init = (comap.read_map(pair["init_12"], index_base), comap.read_map(pair["init_21"], index_base))
        t = time.perf_counter()
        m12, m21, info = comap.match_shapes(s1, s2, init=init, settings=run_settings, threads=threads)
        row["match_seconds"] = time.perf_counter() - t
        maps = os.path.join(out_dir, "maps")
        os.makedirs(maps, exist_ok=True)
        row["map_12"] = os.path.join("maps", pair["name"] + "_12.map")
        row["map_21"] = os.path.join("maps", pair["name"] + "_21.map")
        comap.write_map(os.path.join(out_dir, row["map_12"]), m12, index_base)
        comap.write_map(os.path.join(out_dir, row["map_21"]), m21, index_base)
        row["inconsistent_vertices"] = comap.inconsistent_vertices(m12, m21)
        row["cycle_error_1"] = float(comap.cycle_errors(s1.V, s1.F, m12, m21).mean())
        row["cycle_error_2"] = float(comap.cycle_errors(s2.V, s2.F, m21, m12).mean())
        row["coverage_12"] = comap.coverage(m12, s2.number_of_vertices)
        row["coverage_21"] = comap.coverage(m21, s1.number_of_vertices)
        if pair["gt_source"]:
            g1 = comap.read_map(pair["gt_source"], index_base)
            g2 = comap.read_map(pair["gt_target"], index_base)
            e12 = comap.geodesic_errors(s2.V, s2.F, m12, g1, g2)
            e21 = comap.geodesic_errors(s1.V, s1.F, m21, g2, g1)
            row["mean_error_12"], row["mean_error_21"] = float(e12.mean()), float(e21.mean())
            row["within_0.025_12"] = float((e12 <= 0.025).mean())
            row["within_0.025_21"] = float((e21 <= 0.025).mean())
        row["status"] = "ok"
    except Exception as e:  # the pair fails, the batch goes on
        row["error"] = " ".join(str(e).split()) or type(e).__name__
    row["seconds"] = time.perf_counter() - start
    return row


def run_batch(pairs_file, out_dir, settings=None, threads=None, index_base=1, progress=True):
    """Matches every pair of ``pairs_file`` (see the module's documentation) and writes the maps
    and ``out_dir/results.csv``. Returns the rows of the results table (dicts with the keys of
    RESULT_COLUMNS). ``settings``: a dict by registry name, as for comap.match; ``threads``: the
    threads of each run (default every core); ``progress``: a progress bar on stderr. Raises
    PairsFileError / OSError for a pairs file that cannot be used, before any pair is matched."""
    pairs = read_pairs(pairs_file)
    shape_settings, run_settings = _split_settings(dict(settings or {}))
    os.makedirs(out_dir, exist_ok=True)
    results = os.path.join(out_dir, "results.csv")
    shapes = _Shapes(shape_settings, threads)
    rows = []
    bar = _progress_bar(len(pairs), progress)
    try:
        for pair in pairs:
            if bar is not None:
                bar.set_postfix_str(pair["name"], refresh=True)
            rows.append(match_pair(pair, shapes, out_dir, run_settings, threads, index_base))
            write_results(results, rows)
            if bar is not None:
                bar.update(1)
    finally:
        if bar is not None:
            bar.close()
    return rows


def _progress_bar(total, enabled):
    if not enabled:
        return None
    try:
        from tqdm import tqdm
    except ImportError:  # a plain line per pair instead
        class Lines:
            def __init__(self):
                self.done = 0

            def set_postfix_str(self, text, refresh=True):
                print(f"[{self.done}/{total}] {text}", file=sys.stderr, flush=True)

            def update(self, n):
                self.done += n

            def close(self):
                print(f"[{self.done}/{total}] done", file=sys.stderr, flush=True)
        return Lines()
    return tqdm(total=total, unit="pair", file=sys.stderr, dynamic_ncols=True)


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="python3 -m comap.batch",
        description="Matches every pair of a CSV pairs file (columns source, target, optional init_12/init_21 and "
                    "gt_source/gt_target, name); writes DIR/maps/NAME_12.map, NAME_21.map and DIR/results.csv. "
                    "Exit status: 0 all pairs ok, 1 some pair failed, 2 bad command line or pairs file.")
    parser.add_argument("pairs", help="the pairs file (CSV with a header)")
    parser.add_argument("--out", required=True, metavar="DIR", help="output folder (created if needed)")
    parser.add_argument("--settings", metavar="FILE.json", help="expert settings (the format of comap settings)")
    parser.add_argument("--threads", type=int, metavar="N", help="threads per pair (default: every core)")
    parser.add_argument("--index-base", type=int, choices=(0, 1), default=1,
                        help="index of the first vertex in map and correspondence files (default 1)")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
    args = parser.parse_args(argv)
    try:
        settings = read_settings(args.settings) if args.settings else None
        rows = run_batch(args.pairs, args.out, settings=settings, threads=args.threads,
                         index_base=args.index_base, progress=not args.quiet)
    except (PairsFileError, ValueError, OSError) as e:
        print(f"comap.batch: {e}", file=sys.stderr)
        return 2
    failed = [r for r in rows if r["status"] != "ok"]
    print(f"{len(rows) - len(failed)} of {len(rows)} pairs ok; results in {os.path.join(args.out, 'results.csv')}",
          file=sys.stderr)
    for r in failed:
        print(f"failed: {r['name']}: {r['error']}", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
