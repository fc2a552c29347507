# Copyright (c) 2026 The Surface_mesh_correspondence developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Matching a collection of pairs listed in a CSV file.

    python3 -m comap.batch PAIRS.csv --out DIR [--workers N | --scheduler tcp://HOST:PORT]
                           [--settings FILE.json] [--threads N] [--index-base 0|1] [--redo] [--quiet]

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

The pairs run on dask.distributed: by default an embedded LocalCluster with one worker process
per core and one thread each (the C++ code of each pair then runs on one thread); ``--workers N``
sets the number of workers, ``--workers 0`` runs the pairs one after the other in this process,
``--scheduler`` uses an existing cluster as it is. Each worker keeps the shapes it prepared (the
last 4) and pairs are submitted grouped by source, so that a source shared by several pairs is
prepared once per worker. A worker that dies costs only its pair, which dask runs again on another
worker (a pair whose workers keep dying is recorded as failed). A run into a folder that holds a
previous run's outputs skips the pairs that run finished (status ``ok`` and both maps present);
``--redo`` matches them again.

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


def _file_mode(path):
    """The permissions a rewritten `path` keeps: its own, or for a new file those that open() would
    give it (0666 less the umask; mkstemp's temporary files are 0600)."""
    try:
        return os.stat(path).st_mode & 0o7777
    except FileNotFoundError:
        mask = os.umask(0)
        os.umask(mask)
        return 0o666 & ~mask


def _write_atomically(path, write):
    folder = os.path.dirname(os.path.abspath(path))
    fd, temporary = tempfile.mkstemp(dir=folder, prefix="." + os.path.basename(path) + ".tmp-")
    try:
        with os.fdopen(fd, "w", newline="") as f:
            write(f)
        os.chmod(temporary, _file_mode(path))
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


def match_pair(pair, shapes, run_settings=None, threads=None, index_base=1):
    """Matches one pair of a pairs file (a dict of read_pairs()). Returns ``(row, map_12, map_21)``:
    its row of the results table and the maps (None when the pair failed). A failure is a row
    with status ``failed`` and the error's message, never an exception (except
    KeyboardInterrupt)."""
    start = time.perf_counter()
    row = {"name": pair["name"], "source": pair["source"], "target": pair["target"], "status": "failed"}
    m12 = m21 = None
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
        m12 = m21 = None
    row["seconds"] = time.perf_counter() - start
    return row, m12, m21


_MALLOC_CHECKED = False


def _undo_malloc_trim_threshold():
    """On the workers of a cluster started with dask's defaults (MALLOC_TRIM_THRESHOLD_ set by the
    nanny), raise glibc's mmap and trim thresholds once per process, which gives back most of
    the speed the adaptive threshold gives."""
    global _MALLOC_CHECKED
    if _MALLOC_CHECKED:
        return
    _MALLOC_CHECKED = True
    if "MALLOC_TRIM_THRESHOLD_" not in os.environ or not sys.platform.startswith("linux"):
        return
    try:
        import ctypes

        libc = ctypes.CDLL("libc.so.6")
        libc.mallopt(-3, 32 << 20)  # M_MMAP_THRESHOLD
        libc.mallopt(-1, 64 << 20)  # M_TRIM_THRESHOLD
    except OSError:
        pass


#: The prepared shapes of this process (a dask worker's), per preparation settings.
_PROCESS_SHAPES = {}


def _match_on_worker(pair, shape_settings, run_settings, threads, index_base):
    """A task of the dask engine: match_pair with the shapes this worker prepared before."""
    hook = os.environ.get("COMAP_BATCH_TEST_DIE_ON")  # test hook: NAME:MARKER kills this worker once
    if hook:
        name, marker = hook.split(":", 1)
        if name == pair["name"] and not os.path.exists(marker):
            open(marker, "w").close()
            os._exit(1)
    _undo_malloc_trim_threshold()
    key = json.dumps(shape_settings, sort_keys=True)
    if key not in _PROCESS_SHAPES:
        _PROCESS_SHAPES[key] = _Shapes(shape_settings, threads)
    return match_pair(pair, _PROCESS_SHAPES[key], run_settings, threads, index_base)


def _previous_rows(results, pairs, out_dir):
    """The rows of a previous run's results.csv whose pair is done: status ok, same name, source
    and target, and both map files present."""
    if not os.path.exists(results):
        return {}
    try:
        with open(results, newline="") as f:
            old = {r["name"]: r for r in csv.DictReader(f)}
    except (OSError, csv.Error, KeyError):
        return {}
    done = {}
    for i, p in enumerate(pairs):
        r = old.get(p["name"])
        if (r and r.get("status") == "ok" and r.get("source") == p["source"] and r.get("target") == p["target"]
                and all(r.get(k) and os.path.exists(os.path.join(out_dir, r[k])) for k in ("map_12", "map_21"))):
            done[i] = r
    return done


def run_batch(pairs_file, out_dir, settings=None, threads=None, index_base=1, progress=True, workers=None,
              scheduler=None, redo=False):
    """Matches every pair of ``pairs_file`` (see the module's documentation) and writes the maps
    and ``out_dir/results.csv``. Returns the rows of the results table (dicts with the keys of
    RESULT_COLUMNS), in the order of the pairs file.

    - ``settings``: a dict by registry name, as for comap.match;
    - ``workers``: the engine. None (default): an embedded dask.distributed LocalCluster with one
      worker process per core, one thread each; N > 0: N such workers; 0: no dask, the pairs one
      after the other in this process. ``scheduler``: the address of an existing dask cluster
      ("tcp://HOST:PORT"), used as it is (the meshes must be readable at the same paths on its
      workers; the outputs are written by this process);
    - ``threads``: the C++ threads of each pair (default: 1 on dask workers, every core without);
    - ``redo``: match again the pairs that a previous run into ``out_dir`` finished (by default
      they are kept and skipped);
    - ``progress``: a progress bar on stderr.

    Raises PairsFileError / ValueError / OSError for a pairs file or settings that cannot be
    used, before any pair is matched. The embedded cluster starts worker processes: in a script,
    call run_batch under ``if __name__ == "__main__":``."""
    pairs = read_pairs(pairs_file)
    shape_settings, run_settings = _split_settings(dict(settings or {}))
    if workers is not None and (isinstance(workers, bool) or int(workers) != workers or workers < 0):
        raise ValueError(f"workers must be a non-negative integer, got {workers!r}")
    os.makedirs(out_dir, exist_ok=True)
    results = os.path.join(out_dir, "results.csv")
    rows = [None] * len(pairs)
    if not redo:
        for i, r in _previous_rows(results, pairs, out_dir).items():
            rows[i] = r
    todo = [i for i in range(len(pairs)) if rows[i] is None]
    # Pairs that share a source next to each other: a worker reuses the shapes it prepared.
    todo.sort(key=lambda i: (pairs[i]["source"], pairs[i]["target"]))
    bar = _progress_bar(len(pairs), progress)
    if bar is not None:
        bar.update(len(pairs) - len(todo))

    def record(i, result):
        row, m12, m21 = result
        if m12 is not None:
            maps = os.path.join(out_dir, "maps")
            os.makedirs(maps, exist_ok=True)
            row["map_12"] = os.path.join("maps", pairs[i]["name"] + "_12.map")
            row["map_21"] = os.path.join("maps", pairs[i]["name"] + "_21.map")
            comap.write_map(os.path.join(out_dir, row["map_12"]), m12, index_base)
            comap.write_map(os.path.join(out_dir, row["map_21"]), m21, index_base)
        rows[i] = row
        write_results(results, [r for r in rows if r is not None])
        if bar is not None:
            bar.set_postfix_str(pairs[i]["name"], refresh=False)
            bar.update(1)

    try:
        if scheduler is None and workers == 0:
            shapes = _Shapes(shape_settings, threads)
            for i in todo:
                record(i, match_pair(pairs[i], shapes, run_settings, threads, index_base))
        elif todo:
            _run_on_dask(pairs, todo, record, shape_settings, run_settings, threads, index_base, workers, scheduler)
    finally:
        if bar is not None:
            bar.close()
    return rows


def _run_on_dask(pairs, todo, record, shape_settings, run_settings, threads, index_base, workers, scheduler):
    import logging
    import uuid

    from distributed import Client, LocalCluster, as_completed

    cluster = None
    if scheduler is None:
        # dask's nanny sets MALLOC_TRIM_THRESHOLD_ in its workers' environment, which turns off
        # glibc's adaptive mmap threshold: the library's large, short-lived buffers are then
        # mapped and unmapped at every allocation, and a FAUST pair takes 3.5 times as long.
        # The embedded cluster's workers keep glibc's defaults.
        import dask

        environ = dict(dask.config.get("distributed.nanny.pre-spawn-environ", {}))
        environ.pop("MALLOC_TRIM_THRESHOLD_", None)
        dask.config.set({"distributed.nanny.pre-spawn-environ": environ})
        scratch = tempfile.TemporaryDirectory(prefix="comap-batch-")  # the workers' scratch space
        cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                               dashboard_address=None, silence_logs=logging.ERROR, local_directory=scratch.name)
        client = Client(cluster)
    else:
        client = Client(scheduler)
    try:
        run = uuid.uuid4().hex[:8]
        task_threads = threads if threads is not None else 1
        futures = {}
        for i in todo:
            f = client.submit(_match_on_worker, pairs[i], shape_settings, run_settings, task_threads, index_base,
                              key=f"comap-pair-{run}-{i}", pure=False)
            futures[f] = i
        for f in as_completed(list(futures)):
            i = futures[f]
            try:
                result = f.result()
            except Exception as e:  # the task itself failed (its worker died too often)
                row = {"name": pairs[i]["name"], "source": pairs[i]["source"], "target": pairs[i]["target"],
                       "status": "failed", "error": " ".join(f"{type(e).__name__}: {e}".split())}
                result = (row, None, None)
            record(i, result)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
            scratch.cleanup()


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
    parser.add_argument("--workers", type=int, metavar="N",
                        help="dask workers of the embedded LocalCluster, one thread each (default: one per core; "
                             "0: no dask, one pair after the other in this process)")
    parser.add_argument("--scheduler", metavar="tcp://HOST:PORT", help="use this existing dask cluster")
    parser.add_argument("--threads", type=int, metavar="N",
                        help="C++ threads per pair (default: 1 on dask workers, every core with --workers 0)")
    parser.add_argument("--redo", action="store_true",
                        help="match again the pairs a previous run into DIR finished (default: skip them)")
    parser.add_argument("--index-base", type=int, choices=(0, 1), default=1,
                        help="index of the first vertex in map and correspondence files (default 1)")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
    args = parser.parse_args(argv)
    try:
        settings = comap.read_settings(args.settings) if args.settings else None
        rows = run_batch(args.pairs, args.out, settings=settings, threads=args.threads,
                         index_base=args.index_base, progress=not args.quiet, workers=args.workers,
                         scheduler=args.scheduler, redo=args.redo)
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
    # The dask workers import comap.batch: run its main, not this __main__ module's copy.
    from comap.batch import main as _main

    sys.exit(_main())
